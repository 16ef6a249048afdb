//! The furnace box shared by the multi-bounce reference and ReSTIR GI tests: inside, every
//! bounce of an N-bounce estimate has an exact expectation (see multi_bounce.rs).

use glam::{Vec2, Vec3};
use restir_render::Scene;
use restir_render::scene::{Material, Triangle, Vertex};

/// A 2 m cube around the origin, every face emitting `le` inward (single-sided, so the
/// front-face rule is exercised) with diffuse albedo `albedo`.
pub fn furnace_box(le: f32, albedo: f32) -> Scene {
    let mut scene = Scene {
        name: "furnace-box".into(),
        materials: vec![Material {
            emission: Vec3::splat(le),
            ..Material::diffuse("wall", Vec3::splat(albedo))
        }],
        ..Scene::default()
    };
    // Each face: its inward normal n and two tangents with t1 × t2 = n (counter-clockwise
    // seen from inside).
    for n in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
        let t1 = n.any_orthonormal_vector();
        let t2 = n.cross(t1);
        let centre = -n; // the face at distance 1 against the normal
        let base = scene.vertices.len() as u32;
        for (s, t) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            scene.vertices.push(Vertex {
                position: centre + t1 * s + t2 * t,
                normal: Vec3::ZERO,
                uv: Vec2::ZERO,
            });
        }
        for indices in [[base, base + 1, base + 2], [base, base + 2, base + 3]] {
            scene.triangles.push(Triangle {
                indices,
                material: 0,
            });
        }
    }
    scene
}
