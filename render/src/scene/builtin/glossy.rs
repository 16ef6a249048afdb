//! `builtin:glossy`: a room lit only indirectly, where the choice of a path shift matters
//! (docs/src/restir-pt.md; in the spirit of the papers' glossy Cornell box and Veach Ajar). A cove
//! light above a shelf shines up onto the ceiling, so every lit point sees it through at least one
//! bounce; a rough-glossy floor reflects the ceiling and two near-mirror panels, whose images of
//! the lit ceiling reach the floor as glossy chains (reconnecting at a mirror fails there,
//! replaying through it works).

use glam::{Quat, Vec3, Vec4};

use super::shapes::{Facing, SceneBuilder, room_faces, scaled_look_at};
use crate::scene::{Material, Scene};

const LIGHT_RADIANCE: Vec3 = Vec3::new(30.0, 26.0, 20.0);

fn glossy_floor() -> Material {
    Material {
        name: "rough-glossy floor".into(),
        base_color: Vec4::new(0.45, 0.45, 0.5, 1.0),
        metallic: 0.0,
        roughness: 0.3,
        specular: 1.0,
        ..Material::default()
    }
}

fn near_mirror() -> Material {
    Material {
        name: "near mirror".into(),
        base_color: Vec4::new(0.92, 0.92, 0.92, 1.0),
        metallic: 1.0,
        roughness: 0.05,
        specular: 1.0,
        ..Material::default()
    }
}

pub(super) fn glossy_room(name: &str) -> Scene {
    let mut b = SceneBuilder::new(name);
    let wall = b.material(Material::diffuse("wall", Vec3::new(0.7, 0.7, 0.68)));
    let floor = b.material(glossy_floor());
    let mirror = b.material(near_mirror());
    let shelf = b.material(Material::diffuse("shelf", Vec3::new(0.5, 0.45, 0.4)));
    let light = b.material(Material::emitter("cove light", LIGHT_RADIANCE, false));

    // Room x∈[-2,2], y∈[0,2.5], z∈[-2,2], faces inward, open towards the camera (+z).
    let mut faces = room_faces(wall, wall, floor);
    faces[4] = None; // +z
    b.cuboid(
        Vec3::new(0.0, 1.25, 0.0),
        Vec3::new(2.0, 1.25, 2.0),
        Quat::IDENTITY,
        Facing::Inward,
        faces,
    );
    // The shelf along the back wall and the cove light on it, facing the ceiling (z × x = +y).
    b.solid_box(
        Vec3::new(0.0, 1.75, -1.8),
        Vec3::new(1.6, 0.04, 0.2),
        Quat::IDENTITY,
        shelf,
    );
    b.rect(
        Vec3::new(0.0, 1.80, -1.8),
        Vec3::Z * 0.12,
        Vec3::X * 1.4,
        light,
    );
    // Two near-mirror panels on the floor, facing the room's middle and leaning back (their
    // normals tilt up), so the camera sees the lit ceiling in them and the floor receives
    // it from them. Both sides reflect.
    for (center, facing) in [
        (Vec3::new(1.25, 0.6, -0.6), Vec3::new(-0.6, 0.35, 0.7)),
        (Vec3::new(-1.3, 0.6, 0.1), Vec3::new(0.7, 0.35, 0.5)),
    ] {
        let n = facing.normalize();
        let u = Vec3::Y.cross(n).normalize() * 0.45;
        let v = n.cross(u).normalize() * 0.55;
        b.rect(center, u, v, mirror);
        b.rect(center, v, u, mirror);
    }
    let camera = scaled_look_at(
        Vec3::new(0.0, 1.4, 3.6),
        Vec3::new(0.0, 0.7, -0.6),
        50.0,
        1.0,
    );
    b.finish(Some(camera))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The light faces the ceiling from above every other surface but the ceiling and
    /// the walls' tops: nothing below it (floor, mirrors, shelf top) sees its front.
    #[test]
    fn the_room_is_lit_only_indirectly_below_the_cove() {
        let s = glossy_room("builtin:glossy");
        let mut emitters = 0;
        for (t, tri) in s.triangles.iter().enumerate() {
            let [a, b, c] = s.triangle_positions(t);
            let n = (b - a).cross(c - a).normalize();
            if s.materials[tri.material as usize].is_emissive() {
                emitters += 1;
                assert!(n.abs_diff_eq(Vec3::Y, 1e-6), "the cove light faces up: {n}");
                assert!(a.y >= 1.8 - 1e-6);
            } else if s.materials[tri.material as usize].metallic > 0.5 {
                assert!(
                    a.y.max(b.y).max(c.y) <= 1.2 + 1e-6,
                    "mirrors stand below the light"
                );
            }
        }
        assert_eq!(emitters, 2);
    }
}
