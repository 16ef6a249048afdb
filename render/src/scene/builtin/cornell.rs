//! The Cornell box (after the Cornell University measurements, rescaled from 555 mm to a 2 m
//! room), also used at extreme scales by `hard:scale-small` / `hard:scale-large`.

use glam::{Quat, Vec3};

use super::shapes::{Facing, SceneBuilder, scaled_look_at};
use crate::scene::{Material, Scene};

/// Radiance of the ceiling light in the classic setup.
const LIGHT_RADIANCE: Vec3 = Vec3::new(17.0, 12.0, 4.0);

/// The box scaled uniformly by `scale` (1 = the 2 m room), camera included; radiance is not
/// scaled, so the image should look the same at every scale.
pub(super) fn cornell_box(name: &str, scale: f32) -> Scene {
    let mut b = SceneBuilder::new(name);
    let white = b.material(Material::diffuse("white", Vec3::new(0.725, 0.71, 0.68)));
    let red = b.material(Material::diffuse("red", Vec3::new(0.63, 0.065, 0.05)));
    let green = b.material(Material::diffuse("green", Vec3::new(0.14, 0.45, 0.091)));
    let light = b.material(Material::emitter("light", LIGHT_RADIANCE, false));
    let s = |v: Vec3| v * scale;

    // Room x∈[-1,1], y∈[0,2], z∈[-1,1], faces inward, open towards the camera (+z).
    // Face order: +x (right wall), -x (left wall), ceiling, floor, +z (open), back wall.
    let walls = [
        Some(green),
        Some(red),
        Some(white),
        Some(white),
        None,
        Some(white),
    ];
    b.cuboid(
        s(Vec3::Y),
        s(Vec3::ONE),
        Quat::IDENTITY,
        Facing::Inward,
        walls,
    );

    // The two blocks, placed and turned as in the original data (short front-right, tall
    // back-left, about ∓17° about the vertical).
    let short_half = Vec3::new(0.297, 0.297, 0.297);
    let tall_half = Vec3::new(0.297, 0.594, 0.297);
    let short = Quat::from_rotation_y(-17f32.to_radians());
    let tall = Quat::from_rotation_y(17f32.to_radians());
    b.solid_box(
        s(Vec3::new(0.333, 0.297, 0.398)),
        s(short_half),
        short,
        white,
    );
    b.solid_box(
        s(Vec3::new(-0.326, 0.594, -0.258)),
        s(tall_half),
        tall,
        white,
    );

    // 0.47 m × 0.38 m light 1 mm below the ceiling, facing down (x × z = -y).
    let center = Vec3::new(0.0, 2.0 - 0.001, 0.0);
    b.rect(s(center), s(Vec3::X * 0.234), s(Vec3::Z * 0.189), light);

    let camera = scaled_look_at(Vec3::new(0.0, 1.0, 3.9), Vec3::Y, 39.3, scale);
    b.finish(Some(camera))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_small_downward_light_inside_a_2m_room() {
        let s = cornell_box("cornell", 1.0);
        assert_eq!(s.emissive_triangle_count(), 2);
        let b = s.bounds();
        assert!(b.min.abs_diff_eq(Vec3::new(-1.0, 0.0, -1.0), 1e-6));
        assert!(b.max.abs_diff_eq(Vec3::new(1.0, 2.0, 1.0), 1e-6));
        for (t, tri) in s.triangles.iter().enumerate() {
            if s.materials[tri.material as usize].is_emissive() {
                let [a, b, c] = s.triangle_positions(t);
                assert!(
                    (b - a)
                        .cross(c - a)
                        .normalize()
                        .abs_diff_eq(Vec3::NEG_Y, 1e-6)
                );
            }
        }
    }

    #[test]
    fn scaling_scales_geometry_and_camera_only() {
        let (a, b) = (cornell_box("a", 1.0), cornell_box("b", 1e4));
        let (ca, cb) = (a.camera.unwrap(), b.camera.unwrap());
        assert!((cb.position - ca.position * 1e4).length() < 1e-2);
        assert_eq!(ca.yfov, cb.yfov);
        assert_eq!(a.materials, b.materials);
    }
}
