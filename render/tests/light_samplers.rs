//! The light samplers (docs/src/light-samplers.md): each is unbiased against the reference
//! on a small city, and the error each test exists to catch — a BVH PDF that leaves out
//! the orientation term the walk uses, ReGIR slots whose weights are not divided out — is
//! caught. Bad parameter values and degenerate light sets stay safe.

mod common;

use std::sync::Arc;

use common::scene_parts::{material, rect};
use glam::Vec3;
use restir_render::scene::{Camera, Material, PunctualKind, PunctualLight};
use restir_render::timeline::AnimatedScene;
use restir_render::{LinearImage, Mode, Renderer, Scene, load_environment, load_scene};

const SCENE: &str = "builtin:city:4096";
const WIDTH: u32 = 48;
const HEIGHT: u32 = 32;
/// Blocks of BLOCK × BLOCK pixels compared one by one (a bias can hide in an image mean
/// by darkening one part and brightening another).
const BLOCK: u32 = 16;

fn luma(p: [f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Mean luma of each BLOCK × BLOCK block, row by row.
fn block_means(img: &LinearImage) -> Vec<f64> {
    let mut means = Vec::new();
    for by in 0..img.height / BLOCK {
        for bx in 0..img.width / BLOCK {
            let mut sum = 0.0;
            for y in by * BLOCK..(by + 1) * BLOCK {
                for x in bx * BLOCK..(bx + 1) * BLOCK {
                    sum += luma(img.pixels[(y * img.width + x) as usize]);
                }
            }
            means.push(sum / (BLOCK * BLOCK) as f64);
        }
    }
    means
}

fn city(sampler: &str, mode: Mode) -> Renderer {
    common::renderer(
        SCENE,
        WIDTH,
        HEIGHT,
        mode,
        common::settings(&["jitter=false", &format!("light_sampler={sampler}")]),
    )
}

/// The `ris` estimate with `sampler` averaged over `frames` frames of each of three
/// seeds, with the `planted` errors compiled in.
fn ris_average(sampler: &str, planted: &[&str], frames: u32) -> Vec<f64> {
    let mut r = city(sampler, Mode::Ris);
    r.plant_for_tests(planted);
    let mut sum = vec![0.0; ((WIDTH / BLOCK) * (HEIGHT / BLOCK)) as usize];
    for seed in 0..3 {
        r.set_seed(seed);
        let img = common::accumulate(&mut r, frames);
        for (s, m) in sum.iter_mut().zip(block_means(&img)) {
            *s += m / 3.0;
        }
    }
    sum
}

/// The largest relative difference of a block against the reference's.
fn worst_block(estimate: &[f64], reference: &[f64]) -> f64 {
    estimate
        .iter()
        .zip(reference)
        .map(|(e, r)| (e - r).abs() / r.max(1e-6))
        .fold(0.0, f64::max)
}

fn reference_blocks() -> Vec<f64> {
    let mut r = city("power", Mode::Ris);
    block_means(&common::reference(&mut r, 2, 512))
}

/// Worst block of an unbiased sampler and the smallest planted error, over three seeds of
/// 32 frames against a 1024-spp reference (measured: 3.7–7.7 % for the four samplers,
/// 2.2–4.5 % at 160 frames, so noise; 265 % and 283 % for the twins).
/// 20 %: above the noise of both estimates at this size (blocks of 256 pixels in a dark
/// street, where a few lamps decide the mean), and far below either planted error.
const UNBIASED_TOLERANCE: f64 = 0.2;
const PLANTED_AT_LEAST: f64 = 0.5;

#[test]
fn every_sampler_is_unbiased_against_the_reference_and_planted_errors_are_caught() {
    let reference = reference_blocks();
    for sampler in ["power", "tiles", "regir", "bvh"] {
        let worst = worst_block(&ris_average(sampler, &[], 32), &reference);
        assert!(
            worst < UNBIASED_TOLERANCE,
            "{sampler}: a block {:.1} % off the reference",
            100.0 * worst
        );
    }
    for (sampler, planted) in [
        ("regir", "PLANTED_REGIR_WEIGHT_IGNORED"),
        ("bvh", "PLANTED_BVH_PDF_WITHOUT_ORIENTATION"),
    ] {
        let worst = worst_block(&ris_average(sampler, &[planted], 32), &reference);
        assert!(
            worst > PLANTED_AT_LEAST,
            "{planted} went unseen: worst block only {:.1} % off",
            100.0 * worst
        );
    }
}

/// A 6 × 6 m grey floor with a wall behind it, no lights, and a camera looking at both.
fn floor_and_wall(name: &str) -> Scene {
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
fn every_kind_of_light() -> Scene {
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

#[test]
fn with_every_kind_of_light_the_samplers_agree_with_the_power_table() {
    let scene = every_kind_of_light();
    let blocks_of = |sampler: &str| {
        let settings = common::settings(&["jitter=false", &format!("light_sampler={sampler}")]);
        let mut r = Renderer::new(common::gpu(), &scene, WIDTH, HEIGHT, settings)
            .unwrap_or_else(|e| panic!("{e:#}"));
        r.set_mode(Mode::Ris);
        block_means(&common::accumulate(&mut r, 64))
    };
    let power = blocks_of("power");
    for sampler in ["regir", "bvh"] {
        let worst = worst_block(&blocks_of(sampler), &power);
        // Measured below 2 %; 5 %: 64 frames of 32 candidates per pixel in blocks of 256
        // pixels leave ~1 % of noise on each side.
        assert!(
            worst < 0.05,
            "{sampler}: a block {:.1} % off",
            100.0 * worst
        );
    }
}

/// The light BVH follows the city's traffic: built while half the signs are dark (t =
/// 1.5 s), then refitted after the cars drove on and the signs lit again (t = 2.5 s), its
/// estimate agrees with the reference at that moment. Planted: a tree never refitted keeps
/// the signs at no power, never draws them, and reads darker (no BSDF candidates here:
/// they would find the signs and keep even the stale tree unbiased).
#[test]
fn the_light_bvh_follows_moving_and_blinking_lights() {
    let traffic = |refit: bool| {
        let mut scene = AnimatedScene::new(load_scene("builtin:city-traffic:4096").unwrap());
        let settings =
            common::settings(&["jitter=false", "light_sampler=bvh", "bsdf_candidates=0"]);
        let mut r = Renderer::new(common::gpu(), scene.scene(), WIDTH, HEIGHT, settings)
            .unwrap_or_else(|e| panic!("{e:#}"));
        r.set_mode(Mode::Ris);
        scene.set_time(&mut r, 1.5);
        r.render_frame().unwrap();
        if !refit {
            r.freeze_light_sampler_for_tests();
        }
        scene.set_time(&mut r, 2.5);
        let estimate = block_means(&common::accumulate(&mut r, 48));
        let reference = block_means(&common::reference(&mut r, 2, 512));
        (worst_block(&estimate, &reference), r.light_sampler_stats())
    };
    // Measured: refitted 3.6 %, stale 46 % (without BSDF candidates: with them, MIS gives
    // the lights the stale tree cannot draw to the BSDF rays, unbiased but noisy).
    let (worst, stats) = traffic(true);
    assert!(stats.bvh_refits >= 1, "{stats:?}");
    assert!(
        worst < UNBIASED_TOLERANCE,
        "refitted: a block {:.1} % off",
        100.0 * worst
    );
    let (stale, _) = traffic(false);
    assert!(
        stale > 0.3,
        "a stale tree went unseen: {:.1} %",
        100.0 * stale
    );
}

/// One light, none, all lights in one plane, all in one point (zero-area triangles), and
/// extreme ReGIR values: every sampler renders finite frames.
#[test]
fn degenerate_light_sets_and_extreme_values_stay_finite() {
    let mut scenes = vec![load_scene("builtin:city:1").unwrap()];
    let dark = floor_and_wall("no lights");
    let mut coplanar = dark.clone();
    coplanar.name = "coplanar lights".into();
    let panel = material(
        &mut coplanar,
        Material::emitter("panel", Vec3::splat(5.0), false),
    );
    for i in 0..64 {
        let (x, z) = ((i % 8) as f32 * 0.5 - 2.0, (i / 8) as f32 * 0.5 - 2.0);
        rect(
            &mut coplanar,
            Vec3::new(x, 2.0, z),
            Vec3::X * 0.2,
            Vec3::Z * -0.2,
            panel,
        );
    }
    let mut point = dark.clone();
    point.name = "lights in one point".into();
    let bulb = material(
        &mut point,
        Material::emitter("bulb", Vec3::splat(5.0), false),
    );
    for _ in 0..16 {
        rect(
            &mut point,
            Vec3::new(0.0, 1.5, 0.0),
            Vec3::ZERO,
            Vec3::ZERO,
            bulb,
        );
    }
    scenes.extend([dark, coplanar, point]);
    for scene in &scenes {
        for assignments in [
            &["light_sampler=regir"][..],
            &["light_sampler=bvh"],
            &["light_sampler=tiles"],
            &[
                "light_sampler=regir",
                "regir_grid=1",
                "regir_slots=1",
                "regir_build_samples=1",
                "regir_jitter=4",
                "regir_cell_size=0.0001",
            ],
            &[
                "light_sampler=regir",
                "regir_grid=32",
                "regir_slots=1024",
                "regir_jitter=0",
                "regir_cell_size=1",
            ],
        ] {
            let settings = common::settings(&[&["jitter=false"][..], assignments].concat());
            let mut r = Renderer::new(common::gpu(), scene, 24, 16, settings)
                .unwrap_or_else(|e| panic!("{e:#}"));
            for _ in 0..2 {
                r.render_frame()
                    .unwrap_or_else(|e| panic!("{}: {e}", scene.name));
            }
            let bad = r.read_radiance().non_finite_count();
            assert_eq!(
                bad, 0,
                "{} with {assignments:?}: {bad} non-finite pixels",
                scene.name
            );
        }
    }
}
