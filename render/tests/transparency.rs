//! Light through glass (docs/src/transparency.md). Shadow rays through a pane of known coverage and
//! transmission carry exactly its transmittance; emitters behind glass are seen and light
//! the scene, and accumulated `restir` agrees with the reference on `builtin:lamps` and on
//! Khronos' LightsPunctualLamp, also behind grey glass where the visibility factor of the
//! targets is far from 0 and 1 (unlit surfaces: unlit.rs). Each test has a planted twin:
//! glass treated as opaque (`PLANTED_OPAQUE_GLASS`, what the loader did before), or the
//! target-ratio window on the stored p̂·V (`PLANTED_WINDOW_ON_STORED_TARGETS`).
//!
//! Sizes are tiny (lavapipe on two cores); every tolerance says where it comes from.

use crate::common;

use common::scene_parts::{material, rect};
use glam::{Vec3, Vec4};
use restir_render::scene::{AlphaMode, Camera, Material, PunctualKind, PunctualLight};
use restir_render::shader_constants::{
    REJECT_DEPTH, REJECT_MATERIAL, REJECT_NORMAL, STAT_TEMPORAL_REJECT,
};
use restir_render::{LinearImage, Mode, Renderer, Scene, load_scene};

const OPAQUE_GLASS: &str = "PLANTED_OPAQUE_GLASS";

/// The pane's model values: coverage 0.5, transmission 0.8, tint (1, 0.5, 0.25), so
/// transmittance = (1 − a) + a·t·tint = (0.9, 0.7, 0.6) (docs/src/transparency.md, "The
/// thin-layer model").
const PANE_TRANSMITTANCE: [f64; 3] = [0.9, 0.7, 0.6];

/// A floor under a downward square emitter, optionally with a large pane between them that
/// every light path to the floor crosses; the camera sits under the pane looking down.
fn pane_scene(with_pane: bool) -> Scene {
    let mut s = Scene {
        name: "pane".into(),
        ..Scene::default()
    };
    let floor = material(&mut s, Material::diffuse("floor", Vec3::splat(0.5)));
    let light = material(&mut s, Material::emitter("light", Vec3::splat(4.0), false));
    rect(&mut s, Vec3::ZERO, Vec3::Z * 2.0, Vec3::X * 2.0, floor);
    rect(&mut s, Vec3::Y * 2.0, Vec3::X, Vec3::Z, light);
    // Under the floor, out of every light path: it only makes occlusion possible, so both
    // scenes compile shadow rays and run the same estimators (effects.rs).
    rect(&mut s, Vec3::NEG_Y, Vec3::Z * 0.1, Vec3::X * 0.1, floor);
    if with_pane {
        let pane = material(
            &mut s,
            Material {
                name: "pane".into(),
                base_color: Vec4::new(1.0, 0.5, 0.25, 0.5),
                alpha_mode: AlphaMode::Blend,
                transmission: 0.8,
                double_sided: true,
                specular: 0.0,
                ..Material::default()
            },
        );
        rect(&mut s, Vec3::Y, Vec3::Z * 3.0, Vec3::X * 3.0, pane);
    }
    s.camera = Some(Camera::look_at(
        Vec3::new(0.0, 0.9, 1.2),
        Vec3::ZERO,
        60f32.to_radians(),
    ));
    s
}

/// Per channel: the floor's mean radiance with the pane over without it, in `mode`.
fn pane_ratio(mode: Mode, planted: &[&str]) -> [f64; 3] {
    let render = |with_pane: bool| {
        let scene = pane_scene(with_pane);
        let settings = common::settings(&["jitter=false", "reference_spp=64"]);
        let mut r = Renderer::new(common::gpu(), &scene, 32, 24, settings).unwrap();
        r.plant_for_tests(planted);
        r.set_mode(mode);
        let frames = if mode == Mode::Reference { 4 } else { 64 };
        common::channel_means(&common::accumulate(&mut r, frames))
    };
    let (with, without) = (render(true), render(false));
    assert!(
        without.iter().all(|&c| c > 0.01),
        "the floor is lit: {without:?}"
    );
    [0, 1, 2].map(|c| with[c] / without[c])
}

#[test]
fn shadow_rays_through_a_pane_carry_its_transmittance() {
    // Every light path to the floor crosses the pane once, so the closed form is the
    // unobstructed image times the transmittance, per channel. The two scenes' light tables
    // are ordered differently (the pane changes the BVH), so their noise differs: 256 spp
    // of the reference, 64 frames of nee/restir over 768 pixels put the mean's standard
    // error near 0.2 % (measured spread below 0.5 %); 1.5 % is > 3 σ, and the nearest wrong
    // model (the tint dropped: 0.9 in every channel) is 50 % off in blue.
    for mode in [Mode::Reference, Mode::Nee, Mode::Restir] {
        let ratio = pane_ratio(mode, &[]);
        eprintln!("{mode:?}: with / without pane = {ratio:.4?}");
        for c in 0..3 {
            assert!(
                (ratio[c] / PANE_TRANSMITTANCE[c] - 1.0).abs() < 0.015,
                "{mode:?} channel {c}: {:.4} vs {}",
                ratio[c],
                PANE_TRANSMITTANCE[c]
            );
        }
    }
}

#[test]
fn planted_opaque_pane_blocks_the_light() {
    // The twin: the pane as an opaque surface (the loader's old "BLEND is opaque").
    let ratio = pane_ratio(Mode::Reference, &[OPAQUE_GLASS]);
    eprintln!("opaque pane: with / without = {ratio:.4?}");
    assert!(
        ratio.iter().all(|&c| c < 0.05),
        "detector silent: {ratio:?}"
    );
}

const SUN_IRRADIANCE: f32 = 2.0;
const SUN_ANGLE_DEGREES: f32 = 30.0;
const PANE_ALBEDO: f32 = 0.8;
const CARD_RADIANCE: f32 = 2.0;

/// A white BLEND pane of coverage `alpha` facing the camera, lit by the sun from the
/// camera's side (or `unlit`, with radiance PANE_ALBEDO), in front of an unlit card
/// (radiance seen directly, not a light: the sun stays the only light, so every
/// estimator's light sample is exact).
fn half_covered_scene(alpha: f32, unlit: bool) -> Scene {
    let mut s = Scene {
        name: "partial coverage".into(),
        ..Scene::default()
    };
    let pane = material(
        &mut s,
        Material {
            name: "pane".into(),
            base_color: Vec4::new(PANE_ALBEDO, PANE_ALBEDO, PANE_ALBEDO, alpha),
            alpha_mode: AlphaMode::Blend,
            specular: 0.0,
            unlit,
            ..Material::default()
        },
    );
    rect(&mut s, Vec3::ZERO, Vec3::X * 3.0, Vec3::Y * 3.0, pane);
    let card = material(
        &mut s,
        Material {
            name: "card".into(),
            base_color: Vec4::new(CARD_RADIANCE, CARD_RADIANCE, CARD_RADIANCE, 1.0),
            unlit: true,
            ..Material::default()
        },
    );
    rect(&mut s, Vec3::NEG_Z, Vec3::X * 4.0, Vec3::Y * 4.0, card);
    let angle = SUN_ANGLE_DEGREES.to_radians();
    s.punctual_lights.push(PunctualLight {
        kind: PunctualKind::Directional,
        position: Vec3::ZERO,
        direction: Vec3::new(angle.sin(), 0.0, -angle.cos()),
        intensity: Vec3::splat(SUN_IRRADIANCE),
        range: None,
    });
    s.camera = Some(Camera::look_at(
        Vec3::Z * 2.0,
        Vec3::ZERO,
        30f32.to_radians(),
    ));
    s
}

/// The closed form: a·(albedo/π)·E·cos θ + (1 − a)·card, or a·albedo + (1 − a)·card unlit.
fn half_covered_expected(alpha: f32, unlit: bool) -> f64 {
    let sun = SUN_IRRADIANCE * SUN_ANGLE_DEGREES.to_radians().cos() / std::f32::consts::PI;
    let pane = if unlit {
        PANE_ALBEDO
    } else {
        PANE_ALBEDO * sun
    };
    (alpha * pane + (1.0 - alpha) * CARD_RADIANCE) as f64
}

fn half_covered_mean(alpha: f32, unlit: bool, mode: Mode, planted: &[&str]) -> f64 {
    let settings = common::settings(&["jitter=false", "reference_spp=8"]);
    let scene = half_covered_scene(alpha, unlit);
    let mut r = Renderer::new(common::gpu(), &scene, 16, 12, settings).unwrap();
    r.plant_for_tests(planted);
    r.set_mode(mode);
    common::accumulate(&mut r, 8).mean_luminance()
}

#[test]
fn partial_coverage_seen_by_the_camera_matches_the_closed_form() {
    // Coverage 0.3: the card behind holds the primary surface, the pane's share is lit by
    // one light sample; 0.7: the pane holds it, the card is seen through one camera ray
    // (layer_walk.wgsl). Both are exact in nee and restir (one sun, one unlit card); the
    // reference draws its layer at random, 64 samples a pixel over 192 pixels: its mean
    // scatters by ~0.5 %, so 2 %. The twins (the pane opaque; an unlit pane unblended) are
    // 30–70 % off.
    // An unlit pane (glTF: α·colour + (1 − α)·behind) the same way, exact in every mode
    // but the reference.
    for (alpha, unlit) in [(0.3, false), (0.7, false), (0.3, true), (0.7, true)] {
        let expected = half_covered_expected(alpha, unlit);
        for mode in [Mode::Reference, Mode::Nee, Mode::Restir] {
            let mean = half_covered_mean(alpha, unlit, mode, &[]);
            eprintln!(
                "coverage {alpha}, unlit {unlit}, {mode:?}: {mean:.4} (closed form {expected:.4})"
            );
            assert!(
                (mean / expected - 1.0).abs() < 0.02,
                "coverage {alpha}, unlit {unlit}, {mode:?}: {mean:.4} vs {expected:.4}"
            );
        }
    }
}

#[test]
fn planted_opaque_pane_hides_the_card() {
    let mean = half_covered_mean(0.3, false, Mode::Restir, &[OPAQUE_GLASS]);
    let expected = half_covered_expected(0.3, false);
    eprintln!("coverage 0.3, pane opaque: {mean:.4} (closed form {expected:.4})");
    assert!(
        (mean / expected - 1.0).abs() > 0.2,
        "detector silent: {mean:.4}"
    );
}

#[test]
fn planted_unblended_unlit_pane_is_too_bright() {
    // The twin: an unlit pane's colour at full strength whatever its alpha (the code
    // before): 0.8 + 0.7·2 = 2.2 where 1.64 is right.
    let mean = half_covered_mean(0.3, true, Mode::Restir, &["PLANTED_UNLIT_UNBLENDED"]);
    let expected = half_covered_expected(0.3, true);
    eprintln!("unlit coverage 0.3, unblended: {mean:.4} (closed form {expected:.4})");
    assert!(
        (mean / expected - 1.0).abs() > 0.2,
        "detector silent: {mean:.4}"
    );
}

/// Over a still view of builtin:lamps (jitter and permutation off, so nothing else moves):
/// the share of pixels whose G-buffer surface changes between two frames, and the temporal
/// rejections by the surface checks over six frames.
fn still_view_changes(planted: &[&str]) -> (f64, u64) {
    let settings = common::settings(&["jitter=false", "permutation=false"]);
    let mut r = Renderer::new(common::gpu(), &lamps(), 48, 36, settings).unwrap();
    r.plant_for_tests(planted);
    r.set_mode(Mode::Restir);
    let mut surfaces = Vec::new();
    for _ in 0..8 {
        r.render_frame().unwrap();
        surfaces.push(r.read_surfaces());
    }
    let (a, b) = (&surfaces[6], &surfaces[7]);
    let changed = a
        .iter()
        .zip(b)
        .filter(|(p, q)| p.material != q.material || p.depth != q.depth)
        .count();
    let surface_checks = [REJECT_MATERIAL, REJECT_NORMAL, REJECT_DEPTH];
    let rejections = r
        .collect_reports(true)
        .iter()
        .skip(2)
        .map(|report| {
            surface_checks
                .iter()
                .map(|bit| {
                    report
                        .counters
                        .get(STAT_TEMPORAL_REJECT + bit.trailing_zeros())
                })
                .sum::<u64>()
        })
        .sum();
    (changed as f64 / a.len() as f64, rejections)
}

#[test]
fn a_still_view_behind_glass_keeps_its_surfaces() {
    // The G-buffer walks through frosted globes and the paper shade without a random
    // choice: not one pixel changes its surface, so no history is rejected for it.
    let (changed, rejections) = still_view_changes(&[]);
    eprintln!("still lamps: surfaces changed {changed:.4}, surface rejections {rejections}");
    assert_eq!(changed, 0.0);
    assert_eq!(rejections, 0);
}

#[test]
fn planted_random_layer_choice_flickers() {
    // The twin: the choice before, at random per frame (measured: 1.2 % of the pixels
    // change, 204 rejections; the frosted globes are small at this size).
    let (changed, rejections) = still_view_changes(&["PLANTED_RANDOM_LAYER_CHOICE"]);
    eprintln!("random choice: surfaces changed {changed:.4}, surface rejections {rejections}");
    assert!(changed > 0.005 && rejections > 0, "detector silent");
}

/// Accumulated `restir` (with `planted` defines) and the correct reference of `scene`
/// (jitter off).
fn restir_and_reference(
    scene: &Scene,
    size: (u32, u32),
    planted: &[&str],
) -> (LinearImage, LinearImage) {
    let settings = common::settings(&["jitter=false"]);
    let mut r = Renderer::new(common::gpu(), scene, size.0, size.1, settings).unwrap();
    let reference = common::reference(&mut r, 8, 64);
    r.plant_for_tests(planted);
    r.set_mode(Mode::Restir);
    let image = common::accumulate(&mut r, 48);
    (image, reference)
}

fn luma(p: [f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Mean luma of `image` and of `reference` over the pixels the reference shows below
/// LIT_LUMA_MAX: lit surfaces, not the emitters seen directly.
fn lit_means(image: &LinearImage, reference: &LinearImage) -> (f64, f64) {
    let (mut a, mut b) = (0.0, 0.0);
    for (p, q) in image.pixels.iter().zip(&reference.pixels) {
        if luma(*q) < LIT_LUMA_MAX {
            a += luma(*p);
            b += luma(*q);
        }
    }
    (a, b)
}

const LIT_LUMA_MAX: f64 = 4.0;

fn lamps() -> Scene {
    load_scene("builtin:lamps").unwrap()
}

#[test]
fn restir_agrees_with_the_reference_behind_glass() {
    // builtin:lamps: every emitter sits in glass (clear and frosted globes, tinted tubes,
    // a textured shade). 2 %: the bar set for glass; measured 1.008, 1.002, 1.005, 0.996 over
    // four seeds (σ 0.5 %), and the twin is far outside.
    let (image, reference) = restir_and_reference(&lamps(), (64, 48), &[]);
    let ratio = image.mean_luminance() / reference.mean_luminance();
    eprintln!("lamps: restir / reference = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.02, "ratio {ratio:.4}");
}

#[test]
fn planted_opaque_glass_darkens_the_lamps() {
    // The twin: glass as opaque hides the bulbs and the neon, and blocks their light; only
    // the shade's open top and bottom let any out.
    let (image, reference) = restir_and_reference(&lamps(), (64, 48), &[OPAQUE_GLASS]);
    let ratio = image.mean_luminance() / reference.mean_luminance();
    eprintln!("lamps, opaque glass: restir / reference = {ratio:.4}");
    assert!(ratio < 0.5, "detector silent: {ratio:.4}");
}

/// builtin:lamps with every transparent layer turned into grey glass (pass 0.5 a layer), so
/// the visibility factor in the targets is far from 0 and 1.
fn grey_lamps() -> Scene {
    let mut scene = lamps();
    for m in scene.materials.iter_mut().filter(|m| m.is_transparent()) {
        m.alpha_mode = AlphaMode::Opaque;
        m.base_color = Vec4::new(0.5, 0.5, 0.5, 1.0);
        m.transmission = 1.0;
        m.transmission_texture = None;
    }
    scene
}

/// Temporal reuse alone (the target-ratio window lives there) on grey-glass lamps: the
/// accumulated mean over `seeds` runs relative to the reference.
fn grey_lamps_temporal_ratio(planted: &[&str]) -> f64 {
    let settings = common::settings(&["jitter=false", "spatial=false"]);
    let mut r = Renderer::new(common::gpu(), &grey_lamps(), 32, 24, settings).unwrap();
    r.plant_for_tests(planted);
    r.set_seed(1000);
    let reference = common::reference(&mut r, 16, 64).mean_luminance();
    r.set_mode(Mode::Restir);
    let seeds = [1, 2];
    let mut sum = 0.0;
    for seed in seeds {
        r.set_seed(seed);
        sum += common::accumulate(&mut r, 128).mean_luminance() / reference;
    }
    sum / seeds.len() as f64
}

#[test]
fn target_ratio_window_stays_unbiased_through_grey_glass() {
    // 1.5 %: the ratio of one 128-frame run scatters by 0.6 % over seeds at this size
    // (measured over 8 seeds), 0.4 % for the mean of two, and the 1024-spp reference adds
    // about 0.2 %: the bar is over 3σ, the twin's −2.9 % is over 6σ away.
    let ratio = grey_lamps_temporal_ratio(&[]);
    eprintln!("grey lamps, temporal only: restir / reference = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.015, "ratio {ratio:.4}");
}

#[test]
fn planted_window_on_stored_targets_darkens_grey_glass() {
    // The twin: the window compares p̂ here with the stored p̂·V there (and p̂·V here with p̂
    // there), so whether the history takes part depends on which side a sample came from.
    let ratio = grey_lamps_temporal_ratio(&["PLANTED_WINDOW_ON_STORED_TARGETS"]);
    eprintln!("grey lamps, window on stored targets: {ratio:.4}");
    assert!(ratio < 0.985, "detector silent: {ratio:.4}");
}

/// Khronos' LightsPunctualLamp (assets/khronos, CC BY 4.0): a bulb and a point light inside
/// a paper shade (KHR_materials_transmission with a texture), lit from outside by four more
/// point lights; no camera in the file, so the automatic one frames it.
fn khronos_lamp() -> Scene {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/khronos/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf"
    );
    load_scene(path).unwrap_or_else(|e| panic!("{e}"))
}

/// Pixels of `image` brighter than LIT_LUMA_MAX: the bulb seen directly (through the shade).
fn bulb_pixels(image: &LinearImage) -> usize {
    image
        .pixels
        .iter()
        .filter(|p| luma(**p) >= LIT_LUMA_MAX)
        .count()
}

/// Accumulated `restir` (with `planted`) on the Khronos lamp against the correct reference:
/// the ratio of the lit surfaces' mean (the bulb seen directly left out: seen through the
/// shade's partial transmission, it is sampled per frame in the image and per sample in
/// the reference, and its few bright pixels would decide the mean and its noise), and the
/// bulb pixels of the image and of the reference.
fn khronos_lamp_lit_ratio(planted: &[&str]) -> (f64, usize, usize) {
    // The power table, as measured below: `auto` takes the light BVH here (the bulb's 5,986
    // emissive triangles, probe 15.4), which with 4 candidates read 1.028 at 128 frames and
    // 1.002 at 1024: unbiased, but too noisy for this bar at this length.
    let settings = common::settings(&["jitter=false", "light_sampler=power"]);
    let mut r = Renderer::new(common::gpu(), &khronos_lamp(), 36, 48, settings).unwrap();
    let reference = common::reference(&mut r, 16, 64);
    r.plant_for_tests(planted);
    r.set_mode(Mode::Restir);
    let image = common::accumulate(&mut r, 128);
    let (a, b) = lit_means(&image, &reference);
    (a / b, bulb_pixels(&image), bulb_pixels(&reference))
}

#[test]
fn restir_agrees_with_the_reference_on_the_khronos_lamp() {
    // 2 %: the bar set for glass. Measured at 36×48 over 256 frames: 1.008, blocks of 6×6 pixels
    // all within 0.98–1.05; the 1024-spp reference's own noise on the lit mean is under 1 %.
    let (ratio, bulb, bulb_reference) = khronos_lamp_lit_ratio(&[]);
    eprintln!(
        "khronos lamp: restir / reference (lit) = {ratio:.4}, bulb pixels {bulb} (reference {bulb_reference})"
    );
    assert!((ratio - 1.0).abs() < 0.02, "ratio {ratio:.4}");
    assert!(
        bulb_reference > 0 && bulb > 0,
        "the bulb behind the shade is seen"
    );
}

#[test]
fn planted_opaque_glass_fails_the_khronos_lamp() {
    // The twin: glass as opaque. The shade then hides the bulb and the stem behind it and
    // shows its own paper lit by the four outside lights (measured 7.8× the lit mean, where
    // the see-through shade only tints what is behind it): far outside the bar above.
    let (ratio, _, _) = khronos_lamp_lit_ratio(&[OPAQUE_GLASS]);
    eprintln!("khronos lamp, opaque shade: restir / reference (lit) = {ratio:.4}");
    assert!((ratio - 1.0).abs() > 0.05, "detector silent: {ratio:.4}");
}
