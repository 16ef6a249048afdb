//! `many-lights:N`: a 12 × 4 × 12 m room with occluders and N small coloured ceiling-facing quads,
//! the stress test for light selection (ReSTIR's reason to exist; docs/src/ris.md, "Light sampling"
//! and "Light tiles"). Total emitted power is the same for every N so images compare across N.

use glam::{Quat, Vec3, Vec4};

use super::rng::SplitMix64;
use super::shapes::SceneBuilder;
use crate::scene::{Camera, Material, Scene};

/// Σ area × luminance(radiance) over all lights, whatever N is.
pub(super) const TOTAL_POWER: f32 = 400.0;
/// Light colours are drawn from a palette of this many materials: millions of materials
/// would cost memory for nothing (every light still gets the same power).
const PALETTE: usize = 64;
const ROOM_HALF: Vec3 = Vec3::new(6.0, 2.0, 6.0);
/// Occluders standing on the floor: (centre x, centre z, half-size, rotation about y in °).
const OCCLUDERS: [(f32, f32, Vec3, f32); 7] = [
    (-2.5, -1.5, Vec3::new(0.8, 0.6, 0.8), 20.0),
    (2.0, 2.5, Vec3::new(1.0, 0.4, 0.6), -30.0),
    (3.0, -3.0, Vec3::new(0.6, 1.0, 0.6), 45.0),
    (-1.5, 1.5, Vec3::new(0.25, 1.6, 0.25), 0.0),
    (1.5, -1.5, Vec3::new(0.25, 1.6, 0.25), 0.0),
    (-4.0, -4.0, Vec3::new(0.25, 1.6, 0.25), 0.0),
    (4.0, 4.0, Vec3::new(0.25, 1.6, 0.25), 0.0),
];

/// Side of one light at the default count. Smaller than the 0.25 m first proposed: the
/// lights float in a volume and also occlude, and at 0.25 m the 4096 squares would add up to
/// 1.8× the floor area, shadowing the floor with lights.
const SIDE_AT_DEFAULT: f32 = 0.1;

/// Side of one light: shrinks mildly (N^-1/4) with N, so the summed light area still grows
/// like √N and the cloud of lights gets denser, as "many lights" should.
pub(super) fn light_side(n: usize) -> f32 {
    (SIDE_AT_DEFAULT * (4096.0 / n as f32).powf(0.25)).clamp(0.01, 0.5)
}

/// Rec. 709 luminance, the weight used for "power" here and in light selection.
pub(super) fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// The Lambertian variant (`many-lights-diffuse`): every material diffuse, so the
/// specialised pipeline has no GGX code at all.
pub(super) fn diffuse_floor() -> Material {
    Material::diffuse("floor", Vec3::splat(0.5))
}

/// The glossy floor of `many-lights` (GGX roughness 0.5 over a grey base).
pub(super) fn glossy_floor() -> Material {
    Material {
        name: "glossy floor".into(),
        base_color: Vec4::new(0.5, 0.5, 0.5, 1.0),
        metallic: 0.0,
        roughness: 0.5,
        specular: 1.0,
        ..Material::default()
    }
}

/// Smallest distance between a light and any other surface.
const LIGHT_CLEARANCE: f32 = 0.4;

/// The room with `n` lights (1 ≤ n, checked by the caller) over the given floor material.
pub(super) fn many_lights_room(name: &str, n: usize, floor: Material) -> Scene {
    let occluder_faces = OCCLUDERS.len() * 6;
    let mut b = SceneBuilder::with_capacity(
        name,
        4 * (n + 6 + occluder_faces),
        2 * (n + 6 + occluder_faces),
    );
    let floor = b.material(floor);
    let wall = b.material(Material::diffuse("wall", Vec3::splat(0.6)));
    let occluder = b.material(Material::diffuse("occluder", Vec3::new(0.55, 0.5, 0.45)));
    b.room(Vec3::Y * ROOM_HALF.y, ROOM_HALF, wall, wall, floor);

    for (center, half, rotation, _) in occluders() {
        b.solid_box(center, half, rotation, occluder);
    }
    let blocked: Vec<(Vec3, Vec3)> = occluders().map(|(.., bounds)| bounds).collect();

    let mut rng = SplitMix64::new(0x5EED_0F11_6475);
    let side = light_side(n);
    let area = side * side;
    let power_per_light = TOTAL_POWER / n as f32;
    let palette: Vec<u32> = (0..PALETTE.min(n))
        .map(|i| {
            let colour = saturated_colour(&mut rng);
            let radiance = colour * (power_per_light / (area * luminance(colour)));
            b.material(Material::emitter(&format!("light {i}"), radiance, false))
        })
        .collect();

    let half = side * 0.5;
    // Lights keep LIGHT_CLEARANCE from every surface: a lantern almost touching a wall
    // makes a 1/d² spike that dominates every error metric (the hard-case scenes cover
    // that on purpose; this one is the everyday many-light case).
    let margin = half + LIGHT_CLEARANCE;
    for _ in 0..n {
        let center = loop {
            let p = Vec3::new(
                rng.range(-ROOM_HALF.x + margin, ROOM_HALF.x - margin),
                rng.range(2.0 * ROOM_HALF.y / 3.0, 2.0 * ROOM_HALF.y - LIGHT_CLEARANCE),
                rng.range(-ROOM_HALF.z + margin, ROOM_HALF.z - margin),
            );
            let inside = |(lo, hi): &(Vec3, Vec3)| {
                p.x + margin > lo.x
                    && p.x - margin < hi.x
                    && p.z + margin > lo.z
                    && p.z - margin < hi.z
                    && p.y < hi.y + LIGHT_CLEARANCE
            };
            if !blocked.iter().any(inside) {
                break p;
            }
        };
        let material = palette[(rng.next_u64() % palette.len() as u64) as usize];
        // x × z = -y: facing down into the room.
        b.rect(center, Vec3::X * half, Vec3::Z * half, material);
    }

    let camera = Camera::look_at(
        Vec3::new(-5.5, 1.7, 5.5),
        Vec3::new(1.0, 1.8, -1.0),
        60f32.to_radians(),
    );
    b.finish(Some(camera))
}

/// Each occluder: centre, half-size, rotation and conservative world bounds (min, max).
fn occluders() -> impl Iterator<Item = (Vec3, Vec3, Quat, (Vec3, Vec3))> {
    OCCLUDERS.into_iter().map(|(x, z, half, degrees)| {
        let center = Vec3::new(x, half.y, z);
        let rotation = Quat::from_rotation_y(degrees.to_radians());
        let (c, s) = (rotation * Vec3::X, rotation * Vec3::Z);
        let extent = Vec3::new(
            c.x.abs() * half.x + s.x.abs() * half.z,
            half.y,
            c.z.abs() * half.x + s.z.abs() * half.z,
        );
        (center, half, rotation, (center - extent, center + extent))
    })
}

/// A random hue at high saturation and full value.
fn saturated_colour(rng: &mut SplitMix64) -> Vec3 {
    let hue = rng.next_f32() * 6.0;
    let saturation = rng.range(0.75, 1.0);
    let k = |n: f32| {
        let k = (n + hue) % 6.0;
        1.0 - saturation * (k.min(4.0 - k)).clamp(0.0, 1.0)
    };
    Vec3::new(k(5.0), k(3.0), k(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_are_saturated_and_bright() {
        let mut rng = SplitMix64::new(1);
        for _ in 0..100 {
            let c = saturated_colour(&mut rng);
            assert!((c.max_element() - 1.0).abs() < 1e-6, "{c}");
            assert!(c.min_element() <= 0.25 + 1e-6, "{c}");
        }
    }

    #[test]
    fn side_shrinks_mildly_and_is_clamped() {
        assert_eq!(light_side(4096), SIDE_AT_DEFAULT);
        assert!(light_side(65536) < 0.1 && light_side(65536) > 0.04);
        assert_eq!(light_side(1), 0.5);
        let smallest = SIDE_AT_DEFAULT * (1.0f32 / 1024.0).powf(0.25);
        assert!((light_side(4_194_304) - smallest).abs() < 1e-7);
    }

    #[test]
    fn lights_stay_in_the_upper_room_and_clear_of_occluders() {
        let s = many_lights_room("t", 2000, glossy_floor());
        let light_tris = s
            .triangles
            .iter()
            .filter(|t| s.materials[t.material as usize].is_emissive());
        for t in light_tris {
            for p in t.indices.map(|i| s.vertices[i as usize].position) {
                assert!(
                    p.y >= 4.0 / 3.0 && p.y < 4.0 && p.x.abs() < 6.0 && p.z.abs() < 6.0,
                    "{p}"
                );
                let inside = |(lo, hi): (Vec3, Vec3)| p.cmpge(lo).all() && p.cmple(hi).all();
                assert!(!occluders().any(|(.., bounds)| inside(bounds)), "{p}");
            }
        }
    }
}
