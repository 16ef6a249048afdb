//! The hard cases (docs/src/scenes.md, "Built-in scenes"): scenes built to break light
//! sampling in one specific way each.
//! They must load; what they render is for the renderer's tests to judge.

use glam::{Quat, Vec3};

use super::shapes::{Facing, SceneBuilder};
use crate::scene::{Camera, Material, Scene};

const GREY: Vec3 = Vec3::splat(0.7);
/// Radiance of the "ordinary" lights the cases mix in.
const ORDINARY: Vec3 = Vec3::splat(5.0);

/// A closed 4 × 3 × 4 m grey room facing inward, with a camera inside looking at the back,
/// and the grey material's index.
fn room(name: &str) -> (SceneBuilder, Camera, u32) {
    let mut b = SceneBuilder::new(name);
    let grey = b.material(Material::diffuse("room", GREY));
    b.cuboid(
        Vec3::new(0.0, 1.5, 0.0),
        Vec3::new(2.0, 1.5, 2.0),
        Quat::IDENTITY,
        Facing::Inward,
        [Some(grey); 6],
    );
    let camera = Camera::look_at(
        Vec3::new(0.0, 1.5, 1.9),
        Vec3::new(0.0, 1.0, -2.0),
        60f32.to_radians(),
    );
    (b, camera, grey)
}

/// A 6 × 6 m upward-facing grey floor at y = 0, a camera from `eye` to `target`, and the
/// grey material's index.
fn floor(name: &str, eye: Vec3, target: Vec3) -> (SceneBuilder, Camera, u32) {
    let mut b = SceneBuilder::new(name);
    let grey = b.material(Material::diffuse("floor", GREY));
    b.rect(Vec3::ZERO, Vec3::Z * 3.0, Vec3::X * 3.0, grey);
    (b, Camera::look_at(eye, target, 50f32.to_radians()), grey)
}

/// A downward-facing square light of half-side `half` centred at `center`.
fn ceiling_light(b: &mut SceneBuilder, center: Vec3, half: f32, material: u32) {
    b.rect(center, Vec3::X * half, Vec3::Z * half, material);
}

/// Ordinary lights plus one emitter of 1e-6 m² and radiance 1e6 (huge density, tiny area).
pub(super) fn tiny_bright(name: &str) -> Scene {
    let (mut b, camera, _) = room(name);
    let ordinary = b.material(Material::emitter("ordinary", ORDINARY, false));
    let tiny = b.material(Material::emitter("tiny bright", Vec3::splat(1e6), false));
    for x in [-1.0, 0.0, 1.0] {
        ceiling_light(&mut b, Vec3::new(x, 2.999, -0.5), 0.2, ordinary);
    }
    ceiling_light(&mut b, Vec3::new(0.5, 1.0, -0.5), 0.5e-3, tiny);
    b.finish(Some(camera))
}

/// Emitters at distance → 0 from a lit floor: one lying on it, one cutting through it, one
/// at a grazing angle a tenth of a millimetre above it.
pub(super) fn touching(name: &str) -> Scene {
    let (mut b, camera, _) = floor(name, Vec3::new(0.0, 1.2, 2.5), Vec3::ZERO);
    let light = b.material(Material::emitter("touching", ORDINARY, false));
    // Coplanar with the floor, facing up.
    b.rect(
        Vec3::new(-1.2, 0.0, 0.0),
        Vec3::Z * 0.3,
        Vec3::X * 0.3,
        light,
    );
    // Vertical, half below the floor, facing +z (X × Y = Z).
    b.rect(
        Vec3::new(0.0, 0.1, 0.0),
        Vec3::X * 0.3,
        Vec3::Y * 0.3,
        light,
    );
    // Tilted 1° from vertical so it faces slightly down: X × (0, cos, sin) = (0, -sin, cos).
    let tilt = 1f32.to_radians();
    let v = Vec3::new(0.0, tilt.cos(), tilt.sin()) * 0.3;
    b.rect(Vec3::new(1.2, v.y + 1e-4, 0.0), Vec3::X * 0.3, v, light);
    b.finish(Some(camera))
}

/// The only emitters face up into empty space, above the camera: nothing visible is lit and
/// their visible back faces are black.
pub(super) fn back_facing(name: &str) -> Scene {
    let (mut b, camera, grey) = floor(name, Vec3::new(0.0, 0.6, 3.0), Vec3::new(0.0, 0.9, 0.0));
    b.solid_box(
        Vec3::new(0.8, 0.3, -0.5),
        Vec3::splat(0.3),
        Quat::from_rotation_y(0.4),
        grey,
    );
    let light = b.material(Material::emitter("up", Vec3::splat(10.0), false));
    for x in [-1.0, 0.0, 1.0] {
        // Z × X = +Y: facing up, away from the floor and the camera.
        b.rect(Vec3::new(x, 1.2, -0.5), Vec3::Z * 0.3, Vec3::X * 0.3, light);
    }
    b.finish(Some(camera))
}

/// Emitters of zero area (coincident or collinear vertices, a zero-size quad) and a zero
/// emission "emitter", next to one good light.
pub(super) fn degenerate(name: &str) -> Scene {
    let (mut b, camera, _) = room(name);
    let good = b.material(Material::emitter("good", ORDINARY, false));
    let bright = b.material(Material::emitter("degenerate", Vec3::splat(1e6), true));
    let zero = b.material(Material::emitter("zero emission", Vec3::ZERO, false));
    ceiling_light(&mut b, Vec3::new(0.0, 2.999, 0.0), 0.3, good);
    let p = Vec3::new(-1.0, 2.0, -1.0);
    b.triangle([p, p, p], bright);
    b.triangle([p, p + Vec3::X, p], bright);
    b.triangle([p, p + Vec3::X, p + 2.0 * Vec3::X], bright);
    b.triangle([p, p + Vec3::X * 1e-30, p + Vec3::Z * 1e-30], bright);
    b.rect(Vec3::new(1.0, 2.0, -1.0), Vec3::ZERO, Vec3::Z * 0.2, bright);
    ceiling_light(&mut b, Vec3::new(1.0, 2.999, 1.0), 0.3, zero);
    b.finish(Some(camera))
}

/// Geometry only: every pixel's direct light is zero.
pub(super) fn no_emitters(name: &str) -> Scene {
    let (mut b, camera, grey) = room(name);
    b.solid_box(
        Vec3::new(-0.6, 0.4, -0.8),
        Vec3::splat(0.4),
        Quat::from_rotation_y(0.3),
        grey,
    );
    b.solid_box(
        Vec3::new(0.7, 0.8, -1.0),
        Vec3::new(0.3, 0.8, 0.3),
        Quat::from_rotation_y(-0.3),
        grey,
    );
    b.finish(Some(camera))
}

/// Every emitter is sealed inside a closed box: every shadow ray from outside is blocked.
pub(super) fn occluded(name: &str) -> Scene {
    let (mut b, camera, _) = floor(name, Vec3::new(0.0, 2.0, 4.0), Vec3::new(0.0, 0.5, 0.0));
    // Double-sided, so the seal holds even for renderers that cull back faces on shadow rays.
    let wall = b.material(Material {
        double_sided: true,
        ..Material::diffuse("seal", GREY)
    });
    b.solid_box(
        Vec3::new(0.0, 0.5, 0.0),
        Vec3::splat(0.5),
        Quat::IDENTITY,
        wall,
    );
    let light = b.material(Material::emitter("sealed", Vec3::splat(10.0), true));
    ceiling_light(&mut b, Vec3::new(0.0, 0.9, 0.0), 0.2, light);
    b.rect(
        Vec3::new(0.0, 0.5, 0.3),
        Vec3::X * 0.2,
        Vec3::Y * 0.2,
        light,
    );
    b.finish(Some(camera))
}

/// One scene whose emitters' radiance spans 1e-20 … 1e8.
pub(super) fn radiance_range(name: &str) -> Scene {
    let (mut b, camera, _) = room(name);
    for (i, exponent) in (-20..=8).step_by(4).enumerate() {
        let radiance = Vec3::splat(10f32.powi(exponent));
        let m = b.material(Material::emitter(&format!("1e{exponent}"), radiance, false));
        let x = -1.75 + 0.5 * i as f32;
        ceiling_light(&mut b, Vec3::new(x, 2.999, -1.0), 0.15, m);
    }
    b.finish(Some(camera))
}

/// The near-mirror floor of `hard:mirror` (the room itself is `many-lights` with 512 lights).
pub(super) fn mirror_floor() -> Material {
    Material {
        name: "mirror floor".into(),
        base_color: glam::Vec4::new(0.9, 0.9, 0.9, 1.0),
        metallic: 1.0,
        roughness: 0.02,
        specular: 1.0,
        ..Material::default()
    }
}
