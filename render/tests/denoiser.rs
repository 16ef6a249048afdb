//! The denoiser on the GPU (docs/src/denoiser.md): its passes compute what the plain-Rust
//! model computes, it keeps the image's energy, follows the camera without a trail, stays
//! finite on the hard scenes, and is neither compiled nor run when off. Each property's
//! planted twin (a `PLANTED_*` define in the WGSL) is caught.

use crate::common;

use glam::Vec3;
use restir_render::denoise::model::{self, Frame, Params, Pixel, Planted};
use restir_render::timeline::AnimatedScene;
use restir_render::{LinearImage, Mode, Renderer, load_scene};

const W: u32 = 64;
const H: u32 = 48;

fn denoising(scene: &str, extra: &[&str]) -> Renderer {
    let mut assignments = vec!["denoise=true", "jitter=false"];
    assignments.extend_from_slice(extra);
    common::renderer(scene, W, H, Mode::Restir, common::settings(&assignments))
}

fn frame(r: &mut Renderer) {
    r.render_frame().unwrap_or_else(|e| panic!("{e}"));
}

fn model_params(r: &Renderer) -> Params {
    restir_render::denoise::settings::model_params(
        r.settings(),
        Params::pixel_angle(r.camera().yfov, H),
    )
}

fn rgb(img: &LinearImage) -> Vec<Vec3> {
    img.pixels
        .iter()
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .collect()
}

/// Largest |a − b| relative to the image's mean luminance (a scale every pixel shares,
/// so dark pixels' rounding does not dominate).
fn worst_difference(a: &[Vec3], b: &[Vec3]) -> f32 {
    let mean = a.iter().map(|c| c.dot(Vec3::ONE) / 3.0).sum::<f32>() / a.len() as f32;
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().max_element() / mean.max(1e-6))
        .fold(0.0, f32::max)
}

/// Two frames of the Cornell box: the first without history, the second with the first's.
/// The model, fed the GPU's own raw radiance, surfaces and history, gives the GPU's
/// denoised radiance and history up to float rounding (exp, pow and sqrt differ in the last
/// bits between lavapipe and Rust, and the variance and à-trous passes compound them: 1e-3 of the mean).
#[test]
fn the_wgsl_passes_compute_what_the_model_computes() {
    let mut r = denoising("builtin:cornell", &[]);
    let p = model_params(&r);
    let mut previous: Option<(Vec<Pixel>, Vec<restir_render::gpu_types::GpuDenoiseHistory>)> = None;
    for n in 0..2 {
        frame(&mut r);
        let pixels: Vec<Pixel> = r.read_surfaces().iter().map(Pixel::from_surface).collect();
        let raw = rgb(&r.read_denoise_input());
        let denoised = rgb(&r.read_radiance());
        let gpu_history = r.read_denoise_history();
        let samples: Vec<[f32; 2]> = r.read_debug().iter().map(|d| d.gradient).collect();
        let prev_pixels = previous.as_ref().map_or(&pixels, |p| &p.0).clone();
        let f = Frame {
            width: W,
            height: H,
            pixels: &pixels,
            previous: &prev_pixels,
            radiance: &raw,
        };
        let history = previous.as_ref().map(|p| p.1.as_slice());
        let (model_history, model_out) =
            model::denoise(&f, history, Some(&samples), &p, Planted::default());
        let lengths: Vec<f32> = gpu_history.iter().map(|h| h.length).collect();
        let model_lengths: Vec<f32> = model_history.iter().map(|h| h.length).collect();
        assert_eq!(lengths, model_lengths, "frame {n}: history lengths");
        let illum = |h: &[restir_render::gpu_types::GpuDenoiseHistory]| -> Vec<Vec3> {
            h.iter().map(|h| Vec3::from(h.illumination)).collect()
        };
        let d = worst_difference(&illum(&model_history), &illum(&gpu_history));
        assert!(d < 1e-4, "frame {n}: temporal history differs by {d}");
        let d = worst_difference(&model_out, &denoised);
        assert!(d < 1e-3, "frame {n}: denoised radiance differs by {d}");
        // The filter did something: the denoised frame is not the raw one.
        assert!(
            worst_difference(&raw, &denoised) > 0.05,
            "frame {n}: nothing was filtered"
        );
        previous = Some((pixels, gpu_history));
    }
}

/// Mean luminance of the denoised frames over their raw input's, frames 8..40 of a static
/// Cornell box under plain NEE (the noisiest estimator, so the gate has fireflies to treat
/// unequally), after the history filled.
fn energy_ratio(planted: &[&str]) -> f64 {
    let mut r = denoising("builtin:cornell", &[]);
    r.set_mode(Mode::Nee);
    r.plant_for_tests(planted);
    let (mut raw, mut denoised) = (0.0, 0.0);
    for n in 0..40 {
        frame(&mut r);
        if n >= 8 {
            raw += common::indirect::mean_luma(&r.read_denoise_input());
            denoised += common::indirect::mean_luma(&r.read_radiance());
        }
    }
    denoised / raw
}

/// The denoised frames keep their input's energy within 2 % (the temporal blend is an
/// average, the filter's weights are normalised; what could lose energy is a luminance gate
/// that treats bright and dark pixels unequally). Planted: the centre-only gate loses it.
/// Rendering is deterministic (fixed seeds), so the two runs differ only by the gate:
/// measured 1.0041 and 0.9966. Temporal accumulation leaves the filter little variance
/// to be unequal about on a real scene; the model's firefly field shows the gate's effect
/// at full size (render/src/denoise/tests.rs: 1.0001 against 0.960).
#[test]
fn denoising_keeps_the_energy_and_a_centre_only_gate_is_caught() {
    let kept = energy_ratio(&[]);
    assert!(
        (kept - 1.0).abs() < 0.02,
        "denoised / raw mean luminance {kept}"
    );
    let planted = energy_ratio(&["PLANTED_CENTRE_VARIANCE_GATE"]);
    assert!(
        planted < kept - 0.004,
        "the centre-only gate should lose bright energy: {planted} against {kept}"
    );
}

/// Per-frame luma RMSE against a converged image, at the pixels next to a depth edge
/// (a neighbour at least 20 % nearer or farther), after 16 denoised frames.
fn edge_error(planted: &[&str]) -> f64 {
    let mut r = denoising("builtin:cornell", &[]);
    let reference = common::reference(&mut r, 16, 32);
    r.plant_for_tests(planted);
    for _ in 0..16 {
        frame(&mut r);
    }
    let surfaces = r.read_surfaces();
    let depth = |x: u32, y: u32| surfaces[(y * W + x) as usize].depth;
    let out = r.read_radiance();
    let (mut sum, mut n) = (0.0f64, 0);
    for y in 1..H - 1 {
        for x in 1..W - 1 {
            let d = depth(x, y);
            let edge = [(1, 0), (0, 1), (-1, 0), (0, -1)].iter().any(|(dx, dy)| {
                let e = depth((x as i32 + dx) as u32, (y as i32 + dy) as u32);
                d > 0.0 && (e <= 0.0 || (e - d).abs() > 0.2 * d)
            });
            if edge {
                let diff = out.luminance_at(x, y) - reference.luminance_at(x, y);
                sum += (diff * diff) as f64;
                n += 1;
            }
        }
    }
    assert!(n > 50, "only {n} edge pixels");
    (sum / n as f64).sqrt()
}

/// Edge-stopping has power: along the Cornell box's silhouettes the denoised frame is
/// nearer the converged image than the same filter without its edge weights, which
/// smears the boxes into the walls behind them.
#[test]
fn silhouettes_survive_the_filter_and_a_plain_blur_is_caught() {
    let kept = edge_error(&[]);
    let blurred = edge_error(&["PLANTED_NO_EDGE_STOPPING"]);
    assert!(
        blurred > 1.5 * kept,
        "edge RMSE {kept} with edge-stopping, {blurred} without: the test cannot tell a blur"
    );
}

/// Luma RMSE of the denoised frame against the converged image at the final camera after
/// a pan of 12 frames (1 % of the scene per frame, sideways).
fn trail_error(planted: &[&str]) -> f64 {
    let mut r = denoising("builtin:cornell", &[]);
    let start = r.camera();
    let right = start.rotation * Vec3::X;
    let step = 0.01 * r.scene_scale();
    let at = |k: u32| {
        let mut c = start;
        c.position += right * step * k as f32;
        c
    };
    r.set_camera(at(12));
    let reference = common::reference(&mut r, 16, 32);
    r.plant_for_tests(planted);
    for k in 0..=12 {
        r.set_camera(at(k));
        frame(&mut r);
    }
    restir_render::metrics::luma_rmse(&r.read_radiance(), &reference).unwrap()
}

/// Under camera motion the reprojected history stays on its surfaces: the panned frame is
/// as near the converged image as a static one is; read without reprojection, the
/// history drags last frames' image along (a trail), and the error grows.
#[test]
fn a_panning_camera_leaves_no_trail_and_a_history_not_reprojected_is_caught() {
    let kept = trail_error(&[]);
    let trailed = trail_error(&["PLANTED_NO_REPROJECTION"]);
    assert!(
        trailed > 1.3 * kept,
        "RMSE {kept} reprojected, {trailed} not: the test cannot see a trail"
    );
}

/// The denoiser is compiled and dispatched only when on; with it on, its passes run after
/// shading and its views draw; a cut restarts its history.
#[test]
fn the_denoiser_runs_only_when_on_and_restarts_after_a_cut() {
    let mut r = common::renderer("builtin:cornell", W, H, Mode::Restir, Default::default());
    frame(&mut r);
    assert!(
        !r.last_passes().iter().any(|p| p.starts_with("denoise")),
        "{:?}",
        r.last_passes()
    );
    let mut s = r.settings().clone();
    s.denoise = true;
    s.denoise_iterations = 3;
    r.set_settings(s);
    frame(&mut r);
    let passes = r.last_passes();
    let shade = passes.iter().position(|p| *p == "shade").unwrap();
    let temporal = passes
        .iter()
        .position(|p| *p == "denoise temporal")
        .unwrap();
    let modulate = passes
        .iter()
        .position(|p| *p == "denoise modulate")
        .unwrap();
    let moments = passes.iter().position(|p| *p == "moments").unwrap();
    assert!(
        shade < temporal && temporal < modulate && modulate < moments,
        "{passes:?}"
    );
    assert!(passes.contains(&"denoise atrous"), "{passes:?}");
    // The inspector shows the pixel's history: the length the history buffer holds.
    let pixel = (W / 2, H / 2);
    let inspection = common::inspect_next_frame(&mut r, pixel);
    let d = inspection
        .denoise
        .expect("the denoiser ran: its part of the inspection is there");
    let index = (pixel.1 * W + pixel.0) as usize;
    assert_eq!(d.history, r.read_denoise_history()[index]);
    assert_eq!(d.history.length, 2.0);
    assert!((0.0..=1.0).contains(&d.gradient), "λ {}", d.gradient);
    r.set_inspected_pixel(None);
    r.request_cut();
    frame(&mut r);
    assert!(r.read_denoise_history().iter().all(|h| h.length <= 1.0));
    // Each view draws something of its own: not the final image, not another view.
    let mut drawn = vec![r.read_display_rgba8()];
    for view in [
        "denoise-input",
        "history-length",
        "denoise-variance",
        "temporal-gradient",
    ] {
        let mut v = *r.view();
        v.view = restir_render::DebugView::from_name(view).unwrap();
        r.set_view(v);
        frame(&mut r);
        assert!(
            r.last_passes().contains(&"denoise view"),
            "{view}: {:?}",
            r.last_passes()
        );
        let rgba = r.read_display_rgba8();
        assert!(
            !drawn.contains(&rgba),
            "{view} draws what another view drew"
        );
        drawn.push(rgba);
    }
}

const BLINK_SIZE: (u32, u32) = (48, 32);

/// References of `blinking-lights` with every light on (0.9 s) and half off (1.5 s).
fn blink_references() -> &'static (LinearImage, LinearImage) {
    static REFS: std::sync::OnceLock<(LinearImage, LinearImage)> = std::sync::OnceLock::new();
    REFS.get_or_init(|| {
        let mut scene = AnimatedScene::new(load_scene("builtin:dynamic:blinking-lights").unwrap());
        scene.pose_only(0.9);
        let settings = common::settings(&["jitter=false"]);
        let (w, h) = BLINK_SIZE;
        let mut r = Renderer::new(common::gpu(), scene.scene(), w, h, settings).unwrap();
        scene.set_time(&mut r, 0.9);
        let before = common::reference(&mut r, 8, 64);
        scene.set_time(&mut r, 1.5);
        let after = common::reference(&mut r, 8, 64);
        (before, after)
    })
}

/// Frames after `blinking-lights` switches half its lights off (at 30 fps, after 15 frames
/// of history with all on) until the denoised image of the region that changed has moved
/// 90 % of the way to the new reference; 20 if it never does.
fn frames_to_follow_a_switch_off(gradients: bool) -> u32 {
    let (before, after) = blink_references();
    let changed = common::changed_pixels(before, after);
    let luma = |p: [f32; 4]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    assert!(changed.len() > 50, "only {} pixels change", changed.len());
    let mean = |img: &LinearImage| {
        changed
            .iter()
            .map(|&i| luma(img.pixels[i]) as f64)
            .sum::<f64>()
            / changed.len() as f64
    };
    let (from, to) = (mean(before), mean(after));
    let mut scene = AnimatedScene::new(load_scene("builtin:dynamic:blinking-lights").unwrap());
    scene.pose_only(0.5);
    let switch = if gradients {
        "denoise_gradients=true"
    } else {
        "denoise_gradients=false"
    };
    let settings = common::settings(&["jitter=false", "denoise=true", switch]);
    let (w, h) = BLINK_SIZE;
    let mut r = Renderer::new(common::gpu(), scene.scene(), w, h, settings).unwrap();
    let fps = 30.0;
    for k in 0..15 {
        scene.set_time(&mut r, 0.5 + k as f32 / fps);
        frame(&mut r);
    }
    for k in 0..20 {
        scene.set_time(&mut r, 1.0 + (k + 1) as f32 / fps);
        frame(&mut r);
        if (mean(&r.read_radiance()) - to).abs() < 0.1 * (from - to).abs() {
            return k + 1;
        }
    }
    20
}

/// Temporal gradients make the denoiser follow a light switched off: within 3 frames
/// (measured: 2), where the plain exponential history (α = 0.2) lags (measured: 6).
/// Gradients off, the same detector must see the lag.
#[test]
fn gradients_follow_a_light_switched_off_and_without_them_the_lag_is_caught() {
    let with = frames_to_follow_a_switch_off(true);
    let without = frames_to_follow_a_switch_off(false);
    eprintln!("frames to follow the switch: {with} with gradients, {without} without");
    assert!(
        with <= 3,
        "with gradients the denoised image took {with} frames"
    );
    assert!(
        without > with + 2,
        "without gradients {without} frames, with {with}: no lag seen"
    );
}

/// Every hard scene, the denoiser on, with extreme knob values: every frame finite.
#[test]
fn hard_scenes_stay_finite_with_the_denoiser_on() {
    for (scene, extra) in [
        (
            "builtin:hard:radiance-range",
            &["denoise_phi_luminance=0.01"][..],
        ),
        ("builtin:hard:tiny-bright", &["denoise_alpha=1"][..]),
        ("builtin:hard:no-emitters", &["denoise_phi_depth=1000"][..]),
        (
            "builtin:hard:degenerate",
            &["denoise_phi_normal=1024", "denoise_iterations=5"][..],
        ),
        ("builtin:hard:scale-large", &["denoise_history_cap=1"][..]),
    ] {
        let mut r = denoising(scene, extra);
        for n in 0..4 {
            frame(&mut r);
            let img = r.read_radiance();
            let bad = img.non_finite_count();
            assert_eq!(bad, 0, "{scene} frame {n}: {bad} non-finite pixels");
        }
    }
}

/// Bad knob values get one line naming the parameter; out-of-range ones are clamped.
#[test]
fn bad_denoiser_values_get_one_line() {
    let mut s = restir_render::Settings::default();
    let e = s
        .apply_assignments(["denoise_alpha=nan"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("denoise_alpha") && !e.contains('\n'), "{e}");
    let e = s
        .apply_assignments(["denoise_auto_depth=sometimes"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("denoise_auto_depth") && !e.contains('\n'), "{e}");
    let warnings = s.apply_assignments(["denoise_iterations=99"]).unwrap();
    assert_eq!(s.denoise_iterations, 5, "{warnings:?}");
}

/// `denoise_auto_depth` on the GPU's own frames: no choice until the history has been warm
/// for `DEPTH_PROBE_FRAMES` frames and the next frame has been held out, then one that is
/// finite, the least held-out error, and what the next frames filter at; the same seed
/// chooses the same; new settings forget it (a bad value's one line is checked in
/// `bad_denoiser_values_get_one_line`). (That the choice is the true best depth is
/// measured on simulated histories with a known truth in the model's tests, and against
/// references in docs/src/measured/denoiser.md, "Choosing the depth per scene".)
#[test]
fn the_depth_probe_chooses_once_warm_and_the_frames_follow_it() {
    use restir_render::denoise::depth_probe::DEPTH_PROBE_FRAMES;
    let choose = || {
        let mut r = denoising("builtin:detail", &["denoise_auto_depth=true"]);
        // The first frame has no history: it counts no warm frame. The last warm one is
        // kept, the next held out.
        for _ in 0..DEPTH_PROBE_FRAMES + 1 {
            frame(&mut r);
        }
        assert_eq!(
            r.denoise_depth_choice(),
            None,
            "chose before holding a frame out"
        );
        frame(&mut r);
        let choice = r.denoise_depth_choice().cloned().expect("the probe ran");
        (r, choice)
    };
    let (mut r, choice) = choose();
    eprintln!("{choice:?}");
    assert_eq!(choice.held_out_error.len(), 6, "depths 0..=5");
    assert!(
        choice.held_out_error.iter().all(|v| v.is_finite()),
        "{choice:?}"
    );
    // Jitter is off: every pixel with a surface is seen again.
    assert!(choice.pixels > W * H / 2, "{choice:?}");
    let least = (1..6)
        .min_by(|&a, &b| choice.held_out_error[a].total_cmp(&choice.held_out_error[b]))
        .unwrap();
    assert_eq!(choice.iterations as usize, least);
    assert_eq!(r.effective_settings().denoise_iterations, choice.iterations);
    frame(&mut r);
    assert_eq!(r.denoise_depth_choice(), Some(&choice), "the choice holds");
    let again = choose().1;
    assert_eq!(
        (again.iterations, &again.held_out_error, again.pixels),
        (choice.iterations, &choice.held_out_error, choice.pixels),
        "the same seed chose differently"
    );
    assert!(choice.probe_ms > 0.0, "{choice:?}");

    let mut s = r.settings().clone();
    s.denoise_alpha = 0.3;
    r.set_settings(s);
    assert_eq!(
        r.denoise_depth_choice(),
        None,
        "new settings kept the old choice"
    );
}
