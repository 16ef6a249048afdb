//! Pieces for scenes built in a test: a rectangle, a material.

use glam::{Vec2, Vec3};
use restir_render::Scene;
use restir_render::scene::{Material, Triangle, Vertex};

/// The rectangle `center ± u ± v`, front face along u × v.
pub fn rect(scene: &mut Scene, center: Vec3, u: Vec3, v: Vec3, material: u32) {
    let base = scene.vertices.len() as u32;
    let normal = u.cross(v).normalize();
    let corners = [
        center - u - v,
        center + u - v,
        center + u + v,
        center - u + v,
    ];
    let uvs = [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    for (position, uv) in corners.into_iter().zip(uvs) {
        scene.vertices.push(Vertex {
            position,
            normal,
            uv,
        });
    }
    for t in [[0, 1, 2], [0, 2, 3]] {
        scene.triangles.push(Triangle {
            indices: t.map(|i| base + i),
            material,
        });
    }
}

pub fn material(scene: &mut Scene, m: Material) -> u32 {
    scene.materials.push(m);
    scene.materials.len() as u32 - 1
}
