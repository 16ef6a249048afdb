//! Pieces for scenes built in a test: a rectangle, a material, and scenes more than one
//! test file uses.

use std::sync::Arc;

use glam::Vec3;
use restir_render::scene::{Camera, Material, PunctualKind, PunctualLight};
use restir_render::{Scene, load_environment, load_scene};

/// The rectangle `center ± u ± v`, front face along u × v (the built-ins' own).
pub fn rect(scene: &mut Scene, center: Vec3, u: Vec3, v: Vec3, material: u32) {
    scene.push_rect(center, u, v, material);
}

pub fn material(scene: &mut Scene, m: Material) -> u32 {
    scene.materials.push(m);
    scene.materials.len() as u32 - 1
}

/// The Cornell box under the sky with two more lights of about the ceiling light's power:
/// a red 4 cm square on the left wall and a blue 1.2 m one on the back wall. Areas 900×
/// apart, so a proposal density that forgets 1/area is far off; the sky's density is per
/// steradian. The colours matter: T is the luminance of f, so where f / T is one colour,
/// W' = W · T(y) / T(y') telescopes and a wrong kernel moves samples without moving the
/// mean. Only a change of colour shows it, so the tests compare each channel.
pub fn mixed_lights_cornell() -> Scene {
    let mut scene = load_scene("builtin:cornell").unwrap();
    scene.environment = Some(Arc::new(load_environment("builtin:sky").unwrap()));
    let small = material(
        &mut scene,
        Material::emitter("small", Vec3::new(1.0, 0.05, 0.05) * (3.0 / 0.0016), false),
    );
    let large = material(
        &mut scene,
        Material::emitter("large", Vec3::new(0.05, 0.05, 1.0) * (6.0 / 1.44), false),
    );
    rect(
        &mut scene,
        Vec3::new(-0.999, 1.2, 0.0),
        Vec3::Y * 0.02,
        Vec3::Z * 0.02,
        small,
    );
    rect(
        &mut scene,
        Vec3::new(0.0, 1.0, -0.999),
        Vec3::X * 0.6,
        Vec3::Y * 0.6,
        large,
    );
    scene
}

/// A 6 × 6 m grey floor with a wall behind it, no lights, and a camera looking at both.
pub fn floor_and_wall(name: &str) -> Scene {
    let mut s = Scene {
        name: name.into(),
        ..Scene::default()
    };
    let floor = material(&mut s, Material::diffuse("floor", Vec3::splat(0.5)));
    rect(&mut s, Vec3::ZERO, Vec3::Z * 3.0, Vec3::X * 3.0, floor);
    let wall = (Vec3::new(0.0, 1.0, -3.0), Vec3::X * 3.0, Vec3::Y);
    rect(&mut s, wall.0, wall.1, wall.2, floor);
    s.camera = Some(Camera::look_at(Vec3::new(0.0, 2.0, 3.0), Vec3::ZERO, 1.0));
    s
}

/// A room with every kind of light: two one-sided area lights, a two-sided one, a point
/// light, a spot, a directional light and the sky. The BVH holds the lights with a
/// position and leaves the sky and the sun to the power table; ReGIR's cells weigh all of
/// them. Both agree with the power table (unbiased, tests/estimators.rs) within 5 %.
pub fn every_kind_of_light() -> Scene {
    let mut s = floor_and_wall("every kind of light");
    let one_sided = material(&mut s, Material::emitter("panel", Vec3::splat(6.0), false));
    let two_sided = material(
        &mut s,
        Material::emitter("sheet", Vec3::new(4.0, 2.0, 1.0), true),
    );
    rect(
        &mut s,
        Vec3::new(-1.5, 1.5, 0.0),
        Vec3::X * 0.3,
        Vec3::Z * -0.3,
        one_sided,
    );
    rect(
        &mut s,
        Vec3::new(1.5, 1.2, -1.0),
        Vec3::X * 0.2,
        Vec3::Z * -0.2,
        one_sided,
    );
    rect(
        &mut s,
        Vec3::new(0.0, 0.8, -2.0),
        Vec3::X * 0.3,
        Vec3::Y * 0.3,
        two_sided,
    );
    let punctual = |kind, position, direction, intensity| PunctualLight {
        kind,
        position,
        direction,
        intensity,
        range: None,
    };
    s.punctual_lights = vec![
        punctual(
            PunctualKind::Point,
            Vec3::new(1.0, 0.6, 1.0),
            Vec3::NEG_Y,
            Vec3::new(0.5, 1.0, 0.5),
        ),
        punctual(
            PunctualKind::Spot {
                inner_cone: 0.3,
                outer_cone: 0.6,
            },
            Vec3::new(-1.0, 2.0, 1.0),
            Vec3::NEG_Y,
            Vec3::new(3.0, 3.0, 6.0),
        ),
        punctual(
            PunctualKind::Directional,
            Vec3::ZERO,
            Vec3::new(0.3, -1.0, 0.2).normalize(),
            Vec3::splat(0.5),
        ),
    ];
    s.environment = Some(Arc::new(load_environment("builtin:sky").unwrap()));
    s.camera = Some(Camera::look_at(
        Vec3::new(0.0, 2.5, 3.5),
        Vec3::new(0.0, 0.0, -0.5),
        60f32.to_radians(),
    ));
    s
}
