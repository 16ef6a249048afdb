//! `plane-light`: the analytic test. One small Lambertian-lit square over a big plane, so the
//! irradiance at any plane point is known in closed form and a renderer's estimate can be
//! checked against it (unbiasedness tests of the reservoir math).

use glam::Vec3;

use super::shapes::SceneBuilder;
use crate::scene::{Camera, Material, Scene};

pub(super) const PLANE_HALF: f32 = 10.0;
pub(super) const LIGHT_HALF: f32 = 0.1;
pub(super) const LIGHT_HEIGHT: f32 = 1.0;
pub(super) const LIGHT_RADIANCE: Vec3 = Vec3::splat(10.0);

pub(super) fn plane_light(name: &str) -> Scene {
    let mut b = SceneBuilder::new(name);
    let plane = b.material(Material::diffuse("plane", Vec3::splat(0.5)));
    let light = b.material(Material::emitter("light", LIGHT_RADIANCE, false));
    // z × x = +y: the plane faces up; x × z = -y: the light faces down at it.
    b.rect(
        Vec3::ZERO,
        Vec3::Z * PLANE_HALF,
        Vec3::X * PLANE_HALF,
        plane,
    );
    b.rect(
        Vec3::Y * LIGHT_HEIGHT,
        Vec3::X * LIGHT_HALF,
        Vec3::Z * LIGHT_HALF,
        light,
    );
    let camera = Camera::look_at(Vec3::new(0.0, 3.0, 0.0), Vec3::ZERO, 40f32.to_radians());
    b.finish(Some(camera))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_matches_the_analytic_setup() {
        let s = plane_light("plane-light");
        assert_eq!(s.triangles.len(), 4);
        assert_eq!(s.emissive_triangle_count(), 2);
        let normal = |t: usize| {
            let [a, b, c] = s.triangle_positions(t);
            (b - a).cross(c - a).normalize()
        };
        assert!(normal(0).abs_diff_eq(Vec3::Y, 1e-6));
        assert!(normal(2).abs_diff_eq(Vec3::NEG_Y, 1e-6));
        let cam = s.camera.unwrap();
        assert!(cam.forward().abs_diff_eq(Vec3::NEG_Y, 1e-5));
        assert_eq!(cam.position, Vec3::new(0.0, 3.0, 0.0));
    }
}
