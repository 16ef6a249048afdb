//! One tracing interface, two backends (docs/src/ray-tracing.md). The software BVH and hardware ray
//! queries must see the same scene: closed forms through both (a tinted pane's transmittance, an
//! alpha-masked hole and a masked solid, a single-sided sheet the camera sees from behind), a
//! statistical comparison over seeds on a scene of glass, layers and emitters behind them
//! (builtin:lamps), the same shadow-ray counters, the same images while the scene moves, and the
//! clear error where the device has no ray queries. Each backend has a planted twin that breaks it
//! alone, and the detectors fire on it.
//!
//! These tests need a device with ray queries (Mesa 25's lavapipe: docs/src/getting-started.md, "A
//! machine without a GPU"); without one they fail saying so. Sizes are tiny (lavapipe on two
//! cores); every tolerance says where it comes from.

use crate::common;

use common::scene_parts::{material, rect};
use glam::{Vec3, Vec4};
use restir_render::scene::{AlphaMode, Camera, Material};
use restir_render::stats::StatsSummary;
use restir_render::timeline::AnimatedScene;
use restir_render::tracing::RayBackend;
use restir_render::{Gpu, LinearImage, Mode, Renderer, Scene, Settings, load_scene};

const BACKENDS: [&str; 2] = ["software", "ray-query"];
/// Software twin: a closest-hit ray reports the last accepted hit, not the nearest.
const PLANTED_LAST_HIT: &str = "PLANTED_BVH_LAST_HIT_NOT_NEAREST";
/// Ray-query twins: tested geometry's hits mapped to the opaque geometry's slots; culling
/// rays that let the hardware commit opaque back faces.
const PLANTED_NO_GEOMETRY_OFFSET: &str = "PLANTED_RAY_QUERY_NO_GEOMETRY_OFFSET";
const PLANTED_NO_CULLING: &str = "PLANTED_RAY_QUERY_NO_CULLING";

fn ray_query_gpu() -> Gpu {
    let gpu = common::gpu();
    assert!(
        gpu.ray_query,
        "these tests need a device with ray queries (VK_KHR_ray_query); '{}' has none. On a \
         machine without a GPU install Mesa 25's lavapipe (docs/src/getting-started.md, \
         \"A machine without a GPU\")",
        gpu.adapter_name()
    );
    gpu
}

fn backend_renderer(scene: &Scene, size: (u32, u32), backend: &str, extra: &[&str]) -> Renderer {
    let mut assignments = vec![format!("ray_backend={backend}")];
    assignments.extend(extra.iter().map(|s| s.to_string()));
    let settings = common::settings(&assignments.iter().map(String::as_str).collect::<Vec<_>>());
    Renderer::new(ray_query_gpu(), scene, size.0, size.1, settings)
        .unwrap_or_else(|e| panic!("{e:#}"))
}

/// What stands between the square light and the floor in `occluder_scene`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Occluder {
    None,
    /// Coverage 0.5, transmission 0.8, tint (1, 0.5, 0.25): transmittance (0.9, 0.7, 0.6).
    Pane,
    /// Alpha mask, alpha 0.3 below the cutoff 0.5 everywhere: a hole, transmittance 1.
    MaskedHole,
    /// Alpha mask, alpha 0.8 above the cutoff: opaque, transmittance 0.
    MaskedSolid,
}

impl Occluder {
    fn transmittance(self) -> [f64; 3] {
        match self {
            Occluder::None | Occluder::MaskedHole => [1.0; 3],
            Occluder::Pane => [0.9, 0.7, 0.6],
            Occluder::MaskedSolid => [0.0; 3],
        }
    }
}

/// A floor under a downward square emitter and a large sheet between them that every light
/// path to the floor crosses (transparency.rs's pane scene, with more sheets). The camera
/// looks down at the floor from under the sheet, through a small single-sided black card it
/// sees from behind, which camera rays cull (the raster G-buffer and the reference's own
/// camera rays alike): the camera must see the floor there, not black. The card's faint
/// shadow falls alike with and without the sheet.
fn occluder_scene(occluder: Occluder) -> Scene {
    let mut s = Scene {
        name: format!("occluder {occluder:?}"),
        ..Scene::default()
    };
    let floor = material(&mut s, Material::diffuse("floor", Vec3::splat(0.5)));
    let light = material(&mut s, Material::emitter("light", Vec3::splat(4.0), false));
    rect(&mut s, Vec3::ZERO, Vec3::Z * 2.0, Vec3::X * 2.0, floor);
    rect(&mut s, Vec3::Y * 2.0, Vec3::X, Vec3::Z, light);
    // The card: 4 cm wide, 0.1 m in front of the camera (a sixth of the image), its front
    // face toward the floor.
    let card = material(&mut s, Material::diffuse("card", Vec3::ZERO));
    let eye = Vec3::new(0.0, 0.9, 1.2);
    let toward = (Vec3::ZERO - eye).normalize();
    let side = toward.cross(Vec3::Y).normalize();
    let up = side.cross(toward);
    rect(&mut s, eye + toward * 0.1, up * 0.02, side * 0.02, card);
    let sheet = |name: &str, base_color: Vec4, alpha_mode: AlphaMode, transmission: f32| Material {
        name: name.into(),
        base_color,
        alpha_mode,
        transmission,
        double_sided: true,
        specular: 0.0,
        ..Material::default()
    };
    let m = match occluder {
        Occluder::None => None,
        Occluder::Pane => Some(sheet(
            "pane",
            Vec4::new(1.0, 0.5, 0.25, 0.5),
            AlphaMode::Blend,
            0.8,
        )),
        Occluder::MaskedHole => Some(sheet(
            "hole",
            Vec4::new(0.5, 0.5, 0.5, 0.3),
            AlphaMode::Mask(0.5),
            0.0,
        )),
        Occluder::MaskedSolid => Some(sheet(
            "solid",
            Vec4::new(0.5, 0.5, 0.5, 0.8),
            AlphaMode::Mask(0.5),
            0.0,
        )),
    };
    if let Some(m) = m {
        let m = material(&mut s, m);
        rect(&mut s, Vec3::Y, Vec3::Z * 3.0, Vec3::X * 3.0, m);
    }
    s.camera = Some(Camera::look_at(eye, Vec3::ZERO, 60f32.to_radians()));
    s
}

/// Per channel, the image's mean radiance in each mode (Reference, Restir) with `occluder`
/// over without it. One renderer per scene serves both modes (one compile per backend).
fn occluder_ratios(occluder: Occluder, backend: &str, planted: &[&str]) -> [[f64; 3]; 2] {
    let render = |o: Occluder| {
        let mut r = backend_renderer(&occluder_scene(o), (32, 24), backend, &["reference_spp=32"]);
        r.plant_for_tests(planted);
        [Mode::Reference, Mode::Restir].map(|mode| {
            // The reference traces its own (jittered) camera rays; the real-time modes see
            // the scene through the rasterised G-buffer, here at pixel centres.
            let mut settings = r.settings().clone();
            settings.jitter = mode == Mode::Reference;
            r.set_settings(settings);
            r.set_mode(mode);
            r.request_cut();
            let frames = if mode == Mode::Reference { 2 } else { 12 };
            common::channel_means(&common::accumulate(&mut r, frames))
        })
    };
    let (with, without) = (render(occluder), render(Occluder::None));
    assert!(
        without.iter().flatten().all(|&c| c > 0.01),
        "the floor is lit: {without:?}"
    );
    [0, 1].map(|m| [0, 1, 2].map(|c| with[m][c] / without[m][c]))
}

/// Whether every channel is within 1.5 % of the closed form (transparency.rs: > 3 σ of the
/// scene's noise at these frame counts; an opaque closed form of 0 within 0.005).
fn matches_closed_form(ratio: [f64; 3], expected: [f64; 3]) -> bool {
    (0..3).all(|c| (ratio[c] - expected[c]).abs() <= 0.015 * expected[c].max(1.0 / 3.0))
}

#[test]
fn layers_masks_and_culling_have_their_closed_forms_through_both_backends() {
    // Every light path to the floor crosses the sheet once and both renders draw the same
    // random numbers, so the ratio is the sheet's transmittance up to the few samples whose
    // path the sheet changes (the BSDF candidates that reach the light): measured exact to
    // 4 digits, held to 1.5 %.
    for backend in BACKENDS {
        for occluder in [Occluder::Pane, Occluder::MaskedHole, Occluder::MaskedSolid] {
            let expected = occluder.transmittance();
            for (mode, ratio) in
                ["reference", "restir"]
                    .into_iter()
                    .zip(occluder_ratios(occluder, backend, &[]))
            {
                eprintln!("{backend} {occluder:?} {mode}: {ratio:.4?} (closed form {expected:?})");
                assert!(
                    matches_closed_form(ratio, expected),
                    "{backend} {occluder:?} {mode}: {ratio:.4?}, closed form {expected:?}"
                );
            }
        }
    }
}

/// The share of black pixels of `mode`'s image of the scene with the card, less that of the
/// same view without it (the floor is lit wherever the camera sees it, and where the view
/// passes the floor's edge both are black alike): what the card covers.
fn card_share(mode: Mode, backend: &str, planted: &[&str]) -> f64 {
    let jitter = if mode == Mode::Reference {
        "jitter=true"
    } else {
        "jitter=false"
    };
    let black_share = |with_card: bool| {
        let mut scene = occluder_scene(Occluder::None);
        if !with_card {
            scene
                .triangles
                .retain(|t| scene.materials[t.material as usize].name != "card");
        }
        let mut r = backend_renderer(&scene, (32, 24), backend, &[jitter, "reference_spp=8"]);
        r.plant_for_tests(planted);
        r.set_mode(mode);
        let img = common::accumulate(&mut r, 1);
        let black = img
            .pixels
            .iter()
            .filter(|p| p[0] + p[1] + p[2] <= 0.0)
            .count();
        black as f64 / img.pixels.len() as f64
    };
    black_share(true) - black_share(false)
}

#[test]
fn camera_rays_cull_single_sided_backs_through_both_backends() {
    // The card covers ~10 % of the image; culled, it blackens no pixel (jittered camera
    // rays spread each pixel over its area, so a pixel at the card's edge is still lit).
    for backend in BACKENDS {
        for mode in [Mode::Reference, Mode::Restir] {
            let share = card_share(mode, backend, &[]);
            eprintln!(
                "{backend} {mode:?}: the card blackens {:.2} % of the image",
                100.0 * share
            );
            assert!(
                share.abs() < 0.005,
                "{backend} {mode:?}: {:.2} % more black: the card shows",
                100.0 * share
            );
        }
    }
}

#[test]
fn planted_culling_error_of_the_ray_query_backend_is_detected() {
    // Camera rays without the flag that sends opaque geometry to the shader: the hardware
    // commits the card's back face, which the material says to cull.
    let share = card_share(Mode::Reference, "ray-query", &[PLANTED_NO_CULLING]);
    eprintln!(
        "planted: the card blackens {:.2} % of the image",
        100.0 * share
    );
    assert!(
        share > 0.03,
        "detector silent: {:.2} % black",
        100.0 * share
    );
}

#[test]
fn planted_slot_map_error_of_the_ray_query_backend_is_detected() {
    // The pane's triangles are tested geometry; read through the opaque geometry's slots
    // they become floor triangles, opaque: the light is blocked.
    let ratio = occluder_ratios(Occluder::Pane, "ray-query", &[PLANTED_NO_GEOMETRY_OFFSET])[0];
    eprintln!("planted ray-query slot map: {ratio:.4?}");
    assert!(
        !matches_closed_form(ratio, Occluder::Pane.transmittance()),
        "detector silent: {ratio:?}"
    );
}

/// Mean luminance of 8 accumulated restir frames of `scene`, one per seed. Each backend
/// gets seeds of its own, so the two are independent estimates.
const SEEDS: u32 = 4;

fn seed_means(scene: &Scene, backend: &str, planted: &[&str]) -> Vec<f64> {
    let first = if backend == "software" { 1 } else { 1 + SEEDS };
    let mut r = backend_renderer(scene, (40, 30), backend, &["jitter=false"]);
    r.plant_for_tests(planted);
    r.set_mode(Mode::Restir);
    (first..first + SEEDS)
        .map(|seed| {
            r.set_seed(seed);
            r.request_cut();
            common::accumulate(&mut r, 8).mean_luminance()
        })
        .collect()
}

fn mean_and_standard_error(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// (relative difference of the two backends' means, z score of that difference).
fn backend_difference(software: &[f64], ray_query: &[f64]) -> (f64, f64) {
    let (a, sa) = mean_and_standard_error(software);
    let (b, sb) = mean_and_standard_error(ray_query);
    ((b - a) / a, (b - a) / (sa * sa + sb * sb).sqrt().max(1e-12))
}

#[test]
fn both_backends_agree_over_seeds_on_lamps_behind_glass() {
    // builtin:lamps: every emitter behind a layer (camera walks through glass, BSDF rays
    // finding light through layers, shadow rays multiplying them), a glossy floor. The two
    // backends draw different samples wherever a tie resolves differently, so they are
    // compared as estimates: four seeds each (their own), a two-sample z test. |z| < 4 (a
    // false alarm below 1e-4) and a relative difference under 4 % (a seed's mean of 8 frames
    // at 40×30 scatters by 1.5 %, so the difference of two 4-seed means has a standard error
    // near 1 %; measured −0.7 %, z −0.6); the planted twin below is at +130 %, z 40.
    let scene = load_scene("builtin:lamps").unwrap();
    let software = seed_means(&scene, "software", &[]);
    let ray_query = seed_means(&scene, "ray-query", &[]);
    let (relative, z) = backend_difference(&software, &ray_query);
    eprintln!(
        "lamps: software {software:.5?}, ray-query {ray_query:.5?}: {:+.3} %, z {z:.2}",
        100.0 * relative
    );
    assert!(
        relative.abs() < 0.04 && z.abs() < 4.0,
        "{:+.3} %, z {z:.2}",
        100.0 * relative
    );
}

#[test]
fn planted_nearest_hit_error_of_the_software_backend_is_detected() {
    // The software twin: closest-hit rays report the last hit the traversal meets, so the
    // G-buffer's walk through the globes and BSDF rays toward the bulbs stop at the wrong
    // layer; against the (correct) ray-query backend the comparison above fires.
    let scene = load_scene("builtin:lamps").unwrap();
    let software = seed_means(&scene, "software", &[PLANTED_LAST_HIT]);
    let ray_query = seed_means(&scene, "ray-query", &[]);
    let (relative, z) = backend_difference(&software, &ray_query);
    eprintln!("planted last hit: {:+.3} %, z {z:.2}", 100.0 * relative);
    assert!(
        relative.abs() >= 0.04 || z.abs() >= 4.0,
        "detector silent: {:+.3} %, z {z:.2}",
        100.0 * relative
    );
}

/// Shadow rays per surface pixel, per pass and in total, of `frames` restir frames.
fn shadow_rays(scene: &Scene, backend: &str, frames: u32) -> StatsSummary {
    let mut r = backend_renderer(scene, (48, 32), backend, &["jitter=false"]);
    r.set_mode(Mode::Restir);
    r.set_seed(7);
    for _ in 0..frames {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
    }
    r.gpu().wait_idle();
    let reports = r.collect_reports(true);
    StatsSummary::from_reports(&reports, 0)
}

#[test]
fn both_backends_count_the_same_shadow_rays() {
    // Same seed, same rays: the counters follow the samples, which follow visibility, so
    // they agree but for the few rays whose answer a tie decides (within 1 %).
    let scene = load_scene("builtin:cornell").unwrap();
    let software = shadow_rays(&scene, "software", 8);
    let ray_query = shadow_rays(&scene, "ray-query", 8);
    eprintln!(
        "software {:?}\nray-query {:?}",
        software.shadow_rays_per_pixel, ray_query.shadow_rays_per_pixel
    );
    assert!(software.shadow_rays_per_pixel_total > 3.0, "{software:?}");
    for (pass, rays) in &software.shadow_rays_per_pixel {
        let other = ray_query
            .shadow_rays_per_pixel
            .get(pass)
            .copied()
            .unwrap_or(0.0);
        assert!(
            (other - rays).abs() <= 0.01 * rays,
            "{pass}: software {rays}, ray-query {other}"
        );
    }
}

/// A moving scene's frames through one backend, same seed: images and their mean.
fn moving_frames(backend: &str, name: &str, times: &[f32]) -> Vec<LinearImage> {
    let mut scene = AnimatedScene::new(load_scene(name).unwrap());
    scene.pose_only(times[0]);
    let mut r = backend_renderer(scene.scene(), (48, 32), backend, &["jitter=false"]);
    r.set_mode(Mode::Restir);
    r.set_seed(3);
    times
        .iter()
        .map(|&t| {
            scene.set_time(&mut r, t);
            r.render_frame().unwrap_or_else(|e| panic!("{e}"));
            r.read_radiance()
        })
        .collect()
}

#[test]
fn both_backends_follow_a_moving_scene() {
    // Orbiting lights (one BLAS shared by all, an instance each, the TLAS rebuilt every
    // frame) and a turning blade (previous-frame TLAS in the temporal terms); the software
    // tree of each keeps the moving triangles in their own subtree under the root
    // (scene::bvh::split). With the same seed each frame of one backend matches the
    // other's but for ties — per frame the mean within 1 %, the luma RMSE between them
    // under 5 % of the mean (measured: 1e-6 and less).
    for name in [
        "builtin:dynamic:many-lights:256",
        "builtin:dynamic:moving-occluder",
    ] {
        let times: Vec<f32> = (0..10).map(|i| 0.2 + i as f32 / 10.0).collect();
        let software = moving_frames("software", name, &times);
        let ray_query = moving_frames("ray-query", name, &times);
        for (i, (a, b)) in software.iter().zip(&ray_query).enumerate() {
            let (ma, mb) = (a.mean_luminance(), b.mean_luminance());
            let rmse = restir_render::metrics::luma_rmse(a, b).unwrap();
            assert!(ma > 0.0, "{name} frame {i} is black");
            assert!(
                (mb / ma - 1.0).abs() < 0.01 && rmse < 0.05 * ma,
                "{name} frame {i}: means {ma} {mb}, RMSE {rmse}"
            );
        }
    }
}

#[test]
fn ray_queries_on_a_device_without_them_are_one_clear_error() {
    let gpu = Gpu::new_headless_without_ray_queries()
        .unwrap_or_else(|e| panic!("GPU tests need a wgpu adapter: {e}"));
    assert!(!gpu.ray_query);
    let scene = load_scene("builtin:cornell").unwrap();
    let mut settings = Settings::default();
    settings.set_from_str("ray_backend", "ray-query").unwrap();
    let mut r = Renderer::new(gpu.clone(), &scene, 16, 16, settings).unwrap();
    let message = r
        .render_frame()
        .expect_err("ray-query must be refused")
        .to_string();
    assert!(
        !message.contains('\n') && message.contains("ray_backend=ray-query"),
        "{message}"
    );
    // auto falls back to the software backend there.
    let mut r = Renderer::new(gpu, &scene, 16, 16, Settings::default()).unwrap();
    r.render_frame().unwrap();
    assert_eq!(r.last_ray_backend(), Some(RayBackend::Software));
}
