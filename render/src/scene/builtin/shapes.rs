//! Geometry building blocks for the built-in scenes: rectangles, boxes and rooms, with the
//! project's winding convention (counter-clockwise seen from the front, which is the side an
//! emitter lights).

use glam::{Quat, Vec2, Vec3};

use crate::scene::{Camera, Material, Scene, Vertex};

/// The six faces of an axis-aligned box, in the order `BoxFaces` arrays use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Face {
    PosX,
    NegX,
    PosY,
    NegY,
    PosZ,
    NegZ,
}

impl Face {
    pub(super) const ALL: [Face; 6] = [
        Face::PosX,
        Face::NegX,
        Face::PosY,
        Face::NegY,
        Face::PosZ,
        Face::NegZ,
    ];

    /// Outward normal and two in-plane axes with `u × v = normal`.
    fn frame(self) -> (Vec3, Vec3, Vec3) {
        match self {
            Face::PosX => (Vec3::X, Vec3::Y, Vec3::Z),
            Face::NegX => (Vec3::NEG_X, Vec3::Z, Vec3::Y),
            Face::PosY => (Vec3::Y, Vec3::Z, Vec3::X),
            Face::NegY => (Vec3::NEG_Y, Vec3::X, Vec3::Z),
            Face::PosZ => (Vec3::Z, Vec3::X, Vec3::Y),
            Face::NegZ => (Vec3::NEG_Z, Vec3::Y, Vec3::X),
        }
    }
}

/// Which way the faces of a box point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Facing {
    /// A solid object seen from outside.
    Outward,
    /// A room seen from inside.
    Inward,
}

/// Accumulates a `Scene`. Vertices carry the flat face normal.
pub(super) struct SceneBuilder {
    scene: Scene,
}

impl SceneBuilder {
    /// `name` without the `builtin:` prefix.
    pub(super) fn new(name: &str) -> Self {
        Self::with_capacity(name, 0, 0)
    }

    /// For generators of millions of triangles: reserve up front, no regrowth.
    pub(super) fn with_capacity(name: &str, vertices: usize, triangles: usize) -> Self {
        Self {
            scene: Scene {
                name: format!("builtin:{name}"),
                vertices: Vec::with_capacity(vertices),
                triangles: Vec::with_capacity(triangles),
                ..Scene::default()
            },
        }
    }

    pub(super) fn material(&mut self, material: Material) -> u32 {
        self.scene.materials.push(material);
        (self.scene.materials.len() - 1) as u32
    }

    pub(super) fn texture(&mut self, texture: crate::scene::Texture) -> u32 {
        self.scene.textures.push(texture);
        (self.scene.textures.len() - 1) as u32
    }

    /// One triangle as given (counter-clockwise = front). Degenerate input is kept as is.
    pub(super) fn triangle(&mut self, p: [Vec3; 3], material: u32) {
        let normal = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        let uvs = [Vec2::ZERO, Vec2::X, Vec2::Y];
        self.scene
            .push_flat(&p, &uvs, normal, &[[0, 1, 2]], material);
    }

    /// The rectangle `center ± u ± v` (half-extents), front face along `u × v`.
    pub(super) fn rect(&mut self, center: Vec3, u: Vec3, v: Vec3, material: u32) {
        self.scene.push_rect(center, u, v, material);
    }

    /// A box of half-size `half`, rotated by `rotation` about its centre. `materials[i]` is
    /// the material of `Face::ALL[i]`; `None` leaves that face open.
    pub(super) fn cuboid(
        &mut self,
        center: Vec3,
        half: Vec3,
        rotation: Quat,
        facing: Facing,
        materials: [Option<u32>; 6],
    ) {
        for (face, material) in Face::ALL.into_iter().zip(materials) {
            let Some(material) = material else { continue };
            let (n, u, v) = face.frame();
            let (u, v) = match facing {
                Facing::Outward => (u, v),
                Facing::Inward => (v, u),
            };
            let extent = |axis: Vec3| rotation * (axis * half.dot(axis.abs()));
            self.rect(center + extent(n), extent(u), extent(v), material);
        }
    }

    /// A room: the box `center ± half` seen from inside, its sides in `wall`, its top and
    /// bottom faces in `ceiling` and `floor`.
    pub(super) fn room(&mut self, center: Vec3, half: Vec3, wall: u32, ceiling: u32, floor: u32) {
        self.cuboid(
            center,
            half,
            Quat::IDENTITY,
            Facing::Inward,
            room_faces(wall, ceiling, floor),
        );
    }

    /// A closed solid box with one material.
    pub(super) fn solid_box(&mut self, center: Vec3, half: Vec3, rotation: Quat, material: u32) {
        self.cuboid(center, half, rotation, Facing::Outward, [Some(material); 6]);
    }

    /// Vertices so far: where the next shape's vertices start.
    pub(super) fn vertex_count(&self) -> u32 {
        self.scene.vertices.len() as u32
    }

    /// The vertices added since `first` (a moving shape is built in its node's space).
    pub(super) fn vertices_since(&self, first: u32) -> Vec<Vertex> {
        self.scene.vertices[first as usize..].to_vec()
    }

    pub(super) fn finish(mut self, camera: Option<Camera>) -> Scene {
        self.scene.camera = camera;
        self.scene
    }
}

/// A camera, scaled with its scene (positions scale, angles do not).
pub(super) fn scaled_look_at(eye: Vec3, target: Vec3, yfov_degrees: f32, scale: f32) -> Camera {
    Camera::look_at(eye * scale, target * scale, yfov_degrees.to_radians())
}

/// A room's materials in `Face::ALL` order (+x, −x, ceiling, floor, +z, −z).
pub(super) fn room_faces(wall: u32, ceiling: u32, floor: u32) -> [Option<u32>; 6] {
    [
        Some(wall),
        Some(wall),
        Some(ceiling),
        Some(floor),
        Some(wall),
        Some(wall),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn face_normals(scene: &Scene) -> Vec<Vec3> {
        (0..scene.triangles.len())
            .map(|t| {
                let [a, b, c] = scene.triangle_positions(t);
                (b - a).cross(c - a).normalize()
            })
            .collect()
    }

    #[test]
    fn rect_faces_u_cross_v_and_matches_vertex_normals() {
        let mut b = SceneBuilder::new("t");
        let m = b.material(Material::default());
        b.rect(Vec3::ZERO, Vec3::X, Vec3::Z, m);
        let s = b.finish(None);
        for n in face_normals(&s) {
            assert!(n.abs_diff_eq(Vec3::NEG_Y, 1e-6));
        }
        assert!(s.vertices.iter().all(|v| v.normal == Vec3::NEG_Y));
    }

    #[test]
    fn boxes_face_out_and_rooms_face_in() {
        for (facing, sign) in [(Facing::Outward, 1.0), (Facing::Inward, -1.0)] {
            let mut b = SceneBuilder::new("t");
            let m = b.material(Material::default());
            let center = Vec3::new(1.0, 2.0, 3.0);
            let rot = Quat::from_rotation_y(0.3);
            b.cuboid(center, Vec3::new(1.0, 2.0, 0.5), rot, facing, [Some(m); 6]);
            let s = b.finish(None);
            assert_eq!(s.triangles.len(), 12);
            for (t, n) in face_normals(&s).into_iter().enumerate() {
                let [a, bb, c] = s.triangle_positions(t);
                let out = ((a + bb + c) / 3.0 - center).dot(n) * sign;
                assert!(out > 0.0, "{facing:?} triangle {t}");
            }
        }
    }
}
