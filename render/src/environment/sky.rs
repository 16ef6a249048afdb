//! `builtin:sky`: a procedural clear sky with a sun, so sky lighting needs no file. A blue
//! gradient brightening toward the horizon, a glow around the sun, a dim ground below the
//! horizon and a sun disc 2° in radius (several texels wide at this resolution, so the
//! distribution resolves it) whose irradiance is about three times the sky's.

use glam::Vec3;

use super::{Environment, uv_to_direction};

pub const BUILTIN_SKY: &str = "builtin:sky";

const WIDTH: u32 = 512;
const HEIGHT: u32 = 256;
/// Sun elevation and azimuth (u of the image), degrees and [0, 1).
const SUN_ELEVATION_DEG: f32 = 35.0;
const SUN_U: f32 = 0.62;
const SUN_RADIUS_DEG: f32 = 2.0;
/// Radiance of the disc: irradiance ≈ 2000 · π(2°)² ≈ 7.7 at normal incidence, against
/// ≈ 2.5 from the sky on a horizontal plane.
const SUN_RADIANCE: [f32; 3] = [2000.0, 1900.0, 1700.0];

fn sky_radiance(d: Vec3, sun: Vec3) -> Vec3 {
    let cos_sun = d.dot(sun).clamp(-1.0, 1.0);
    if cos_sun >= SUN_RADIUS_DEG.to_radians().cos() {
        return Vec3::from(SUN_RADIANCE);
    }
    if d.y < 0.0 {
        // Ground: a dim, warm grey, darker straight down.
        return Vec3::new(0.22, 0.2, 0.17) * (0.6 + 0.4 * (1.0 + d.y));
    }
    let zenith = Vec3::new(0.18, 0.32, 0.75);
    let horizon = Vec3::new(0.75, 0.85, 1.0);
    let t = (1.0 - d.y).powi(4);
    let glow = Vec3::new(1.0, 0.85, 0.6) * (2.0 * (-(1.0 - cos_sun) * 25.0).exp());
    zenith.lerp(horizon, t) + glow
}

pub fn clear_sky() -> Environment {
    Environment::from_texels(BUILTIN_SKY, WIDTH, HEIGHT, clear_sky_texels(WIDTH, HEIGHT))
}

/// The same sky at any resolution (`bench-env` times a 4K one).
pub fn clear_sky_texels(width: u32, height: u32) -> Vec<[f32; 3]> {
    let el = SUN_ELEVATION_DEG.to_radians();
    let sun = uv_to_direction([SUN_U, 0.5 - el / std::f32::consts::PI], [1.0, 0.0]);
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let uv = [
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / height as f32,
            ];
            sky_radiance(uv_to_direction(uv, [1.0, 0.0]), sun).to_array()
        })
        .collect()
}
