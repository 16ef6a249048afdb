//! The default estimator is unbiased where users look (docs/src/mis-and-bias.md, "The two
//! rules of unbiased reuse"). Reuse decisions ignore
//! the sample under pairwise MIS (a null sample, a target of 0 here, a light gone off stay
//! domains), every MIS term carries visibility (`mis_visibility`), and the `bias` view shows
//! bias, not noise. Each test has a planted twin that must fire: the old sample-dependent
//! rejections (`PLANTED_SAMPLE_REJECTION`), or visibility out of the MIS terms.
//!
//! Sizes are tiny (lavapipe on two cores); every tolerance says where it comes from.

use crate::common;

use std::sync::Arc;

use restir_render::metrics::black_pixel_fraction;
use restir_render::timeline::AnimatedScene;
use restir_render::{
    DebugView, LinearImage, Mode, Renderer, Scene, Settings, ViewSettings, load_environment,
    load_scene,
};

const SAMPLE_REJECTION: &str = "PLANTED_SAMPLE_REJECTION";

fn sun_lit_cornell() -> Scene {
    let mut scene = load_scene("builtin:cornell").unwrap();
    scene.environment = Some(Arc::new(load_environment("builtin:sky").unwrap()));
    scene
}

fn renderer_of(scene: &Scene, (w, h): (u32, u32), settings: Settings) -> Renderer {
    Renderer::new(common::gpu(), scene, w, h, settings).unwrap_or_else(|e| panic!("{e:#}"))
}

fn luma(p: [f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

// ---------------------------------------------------------------------------------------
// Visibility in the MIS terms: the sun-lit Cornell box.

const CORNELL: (u32, u32) = (64, 48);

/// Accumulated `restir` (64 frames) over its reference (512 spp), with `extra` settings.
fn sun_lit_ratio(extra: &[&str]) -> f64 {
    let scene = sun_lit_cornell();
    let settings = common::settings(&[&["jitter=false"], extra].concat());
    let mut r = renderer_of(&scene, CORNELL, settings);
    let reference = common::reference(&mut r, 8, 64);
    r.set_mode(Mode::Restir);
    let image = common::accumulate(&mut r, 64);
    image.mean_luminance() / reference.mean_luminance()
}

#[test]
fn the_default_is_unbiased_on_a_sun_lit_box() {
    // Visibility reuse under a sun: every sample reused across a shadow edge was traced
    // where it was drawn. With visibility in every MIS term the weights know which domains
    // can produce which samples. Measured 1.001 at 96×72. 1.5 %: the 512-spp reference's
    // mean and 64 correlated frames each carry ~0.3 % standard error here (the sun patch
    // dominates the variance, tests/environment.rs), so 1.5 % is > 3.5 σ of both together;
    // the twin is 5× further out.
    let ratio = sun_lit_ratio(&[]);
    eprintln!("sun-lit cornell, defaults: restir / reference = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.015, "ratio {ratio:.4}");
}

#[test]
fn planted_unshadowed_mis_terms_darken_the_sun_lit_box() {
    // The twin: visibility reuse with unshadowed MIS terms (measured 0.924 at 96×72).
    let ratio = sun_lit_ratio(&["mis_visibility=false"]);
    eprintln!("sun-lit cornell, mis_visibility off: restir / reference = {ratio:.4}");
    assert!(ratio < 0.96, "detector silent: {ratio:.4}");
}

#[test]
fn shading_skips_exactly_the_ray_it_knows_the_answer_of() {
    // With visibility in the target every survivor was traced from the pixel when it was
    // picked, so shading traces no ray. Tracing it anyway (TEST_TRACE_SURVIVOR) must give the
    // same image bit for bit, and the counters must say where the rays went.
    let scene = sun_lit_cornell();
    let frames = |planted: &[&str]| {
        let mut r = renderer_of(&scene, (48, 36), common::settings(&["jitter=false"]));
        r.plant_for_tests(planted);
        r.set_mode(Mode::Restir);
        let mut rays = (0.0, 0.0);
        let mut images = Vec::new();
        for _ in 0..6 {
            r.render_frame().unwrap();
            let reports = r.collect_reports(true);
            let s = restir_render::stats::StatsSummary::from_reports(&reports, 0);
            rays.0 += s.shadow_rays_per_pixel.get("shade").copied().unwrap_or(0.0);
            rays.1 += s.shadow_rays_per_pixel_total;
            images.push(r.read_radiance());
        }
        (images, rays)
    };
    let (skipped, rays) = frames(&[]);
    let (traced, traced_rays) = frames(&["TEST_TRACE_SURVIVOR"]);
    assert_eq!(rays.0, 0.0, "shading traced rays with mis_visibility on");
    assert!(traced_rays.0 > 0.0, "the verification variant traced none");
    assert!(
        rays.1 > 4.0 * 6.0,
        "reuse should trace several rays per pixel: {}",
        rays.1
    );
    for (i, (a, b)) in skipped.iter().zip(&traced).enumerate() {
        assert!(
            a.pixels == b.pixels,
            "frame {i} differs: a survivor was not visible"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Sample-dependent decisions: a frozen scene at M cap 100 with permutation sampling, and
// the frames after lights switch off.

const BLINK: (u32, u32) = (64, 48);

fn blinking_at(time: f32) -> AnimatedScene {
    let mut scene = AnimatedScene::new(load_scene("builtin:dynamic:blinking-lights").unwrap());
    scene.pose_only(time);
    scene
}

/// Frozen at 0.2 s, pairwise, permutation on, M cap 100: accumulated frames 24..72 of four
/// seeds over the reference.
fn frozen_high_cap_ratio(planted: &[&str], extra: &[&str]) -> f64 {
    let scene = blinking_at(0.2);
    let settings = common::settings(&[&["jitter=false", "m_cap=100"], extra].concat());
    let mut r = renderer_of(scene.scene(), BLINK, settings);
    let reference = common::reference(&mut r, 8, 64).mean_luminance();
    let mut ratio = 0.0;
    for seed in 1..=4u32 {
        r.plant_for_tests(planted);
        r.set_mode(Mode::Restir);
        r.set_seed(seed);
        r.request_cut();
        for _ in 0..24 {
            r.render_frame().unwrap();
        }
        ratio += common::accumulate(&mut r, 48).mean_luminance() / reference / 4.0;
    }
    ratio
}

#[test]
fn a_high_m_cap_with_permutation_is_unbiased() {
    // The history is a neighbour's reservoir carrying 100× the fresh sample's confidence;
    // rejecting it for its sample gave the canonical sample weight 1 instead of ~1/101
    // (+3–6 % in docs/src/measured/dynamic-scenes.md). Kept as a domain the estimate is
    // unbiased: 8 seeds measured 0.998–1.012, mean 1.0036 ± 0.0016. 1.5 % is > 6 σ of the
    // 4-seed mean (one seed spreads by ±0.45 %); the planted twin's seeds are all above +3.5 %.
    let ratio = frozen_high_cap_ratio(&[], &[]);
    eprintln!("frozen blinking-lights, M cap 100: restir / reference = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.015, "ratio {ratio:.4}");
}

#[test]
fn planted_rejection_on_target_zero_brightens_a_high_m_cap() {
    // The twin: the history rejected whenever its sample's target here is 0 (the null and
    // ratio checks off, so that this one rejection is what is measured).
    let ratio = frozen_high_cap_ratio(
        &[SAMPLE_REJECTION],
        &["check_reservoir=false", "check_target_ratio=false"],
    );
    eprintln!("planted target-0 rejection, M cap 100: restir / reference = {ratio:.4}");
    assert!(ratio > 1.025, "detector silent: {ratio:.4}");
}

/// Pixels whose reference changes by more than 10 % when the blinking set goes off, and
/// the half-off reference the frames are compared with. The pixels are chosen with another
/// half-off reference (another seed): chosen with the one compared against, pixels where
/// its noise happens to be low would be picked more often, and the frames would look too
/// bright by that selection alone (+5 % here).
fn switch_references() -> &'static (Vec<usize>, LinearImage) {
    static REFS: std::sync::OnceLock<(Vec<usize>, LinearImage)> = std::sync::OnceLock::new();
    REFS.get_or_init(|| {
        let mut scene = blinking_at(0.5);
        let mut r = renderer_of(scene.scene(), SWITCH, common::settings(&["jitter=false"]));
        let on = common::reference(&mut r, 8, 64);
        scene.set_time(&mut r, 1.5);
        let off_for_selection = common::reference(&mut r, 8, 64);
        r.set_seed(99);
        let off = common::reference(&mut r, 8, 64);
        let changed = (0..on.pixels.len())
            .filter(|&i| {
                let (a, b) = (luma(on.pixels[i]), luma(off_for_selection.pixels[i]));
                (a - b).abs() > 0.1 * a.max(b)
            })
            .collect();
        (changed, off)
    })
}

/// The switch-off tests' size, and their seeds: one seed's signed bias spreads by ±3 % at
/// this size (a frame's error is shared by the pixels a reused sample reaches; ±6.5 % at
/// 64×48), so the mean of 8 spreads by ±1.1 %.
const SWITCH: (u32, u32) = (96, 64);
const SWITCH_SEEDS: u32 = 8;

/// Signed bias in the changed region, Σ(frame − reference) / Σ reference, over the first 5
/// frames after the switch-off at 1 s (9 frames of history from 0.7 s, M cap 20), mean over
/// SWITCH_SEEDS seeds.
fn switch_off_bias(planted: &[&str]) -> f64 {
    let (changed, off) = switch_references();
    let reference: f64 = changed.iter().map(|&i| luma(off.pixels[i])).sum();
    let mut bias = 0.0;
    for seed in 1..=SWITCH_SEEDS {
        let mut scene = blinking_at(0.7);
        let mut r = renderer_of(scene.scene(), SWITCH, common::settings(&["jitter=false"]));
        r.plant_for_tests(planted);
        r.set_mode(Mode::Restir);
        r.set_seed(seed);
        for i in 0..9 {
            scene.set_time(&mut r, 0.7 + i as f32 / 30.0);
            r.render_frame().unwrap();
        }
        for k in 0..5 {
            scene.set_time(&mut r, 1.0 + k as f32 / 30.0);
            r.render_frame().unwrap();
            let frame = r.read_radiance();
            let sum: f64 = changed.iter().map(|&p| luma(frame.pixels[p])).sum();
            bias += (sum - reference) / reference / (5 * SWITCH_SEEDS) as f64;
        }
    }
    bias
}

#[test]
fn lights_switching_off_leave_no_ghost_on_average() {
    let (changed, _) = switch_references();
    assert!(changed.len() > 100, "{} changed pixels", changed.len());
    // A history sample on a light that went off is a domain of target 0: the canonical
    // sample keeps only its own share, the mean is right from the first frame (the
    // switch-off experiment: −0.002 against +0.41). What stays is per-pixel lag: stale weights of
    // histories on lights still on, high and low around the mean. Measured −0.002 over 12
    // seeds; 5 % is > 4 σ of the 8-seed mean (SWITCH_SEEDS); the planted twin is at +64 %.
    let bias = switch_off_bias(&[]);
    eprintln!("switch-off, first 5 frames, changed region: signed bias {bias:+.4}");
    assert!(bias.abs() <= 0.05, "signed bias {bias:+.4}");
}

#[test]
fn planted_light_gone_rejection_ghosts_after_a_switch_off() {
    let bias = switch_off_bias(&[SAMPLE_REJECTION]);
    eprintln!("planted light_gone rejection: signed bias {bias:+.4}");
    assert!(bias > 0.2, "detector silent: {bias:+.4}");
}

// ---------------------------------------------------------------------------------------
// Black speckles on the showcase floor.

/// Mean black-pixel fraction of frames 10..20 of `restir` on the concourse (jitter off).
fn concourse_black_pixels(extra: &[&str]) -> f64 {
    let scene = load_scene("builtin:concourse").unwrap();
    let settings = common::settings(&[&["jitter=false"], extra].concat());
    let mut r = renderer_of(&scene, (120, 96), settings);
    let reference = common::reference(&mut r, 8, 32);
    r.set_mode(Mode::Restir);
    r.request_cut();
    let mut sum = 0.0;
    for i in 0..20 {
        r.render_frame().unwrap();
        if i >= 10 {
            sum += black_pixel_fraction(&r.read_radiance(), &reference).unwrap() / 10.0;
        }
    }
    sum
}

#[test]
fn the_showcase_floor_has_no_black_speckles() {
    // A pixel resamples only among samples it can see (p̂·V here), so it is black only where
    // the light really is hidden. Measured 0.12 % at 225×180; the 256-spp reference's own
    // noise makes a few of its pixels look lit where frames are right to be black. 0.5 % is
    // the bar set for the showcase; the twin is several times above it.
    let fraction = concourse_black_pixels(&[]);
    eprintln!(
        "concourse black pixels, defaults: {:.3} %",
        100.0 * fraction
    );
    assert!(fraction <= 0.005, "{:.3} % black", 100.0 * fraction);
}

#[test]
fn planted_unshadowed_target_leaves_black_speckles() {
    let fraction = concourse_black_pixels(&["mis_visibility=false"]);
    eprintln!(
        "concourse black pixels, mis_visibility off: {:.3} %",
        100.0 * fraction
    );
    assert!(
        fraction > 0.02,
        "detector silent: {:.3} %",
        100.0 * fraction
    );
}

// ---------------------------------------------------------------------------------------
// The bias view.

/// The share of pixels the bias view paints (not the neutral grey) after 128 frames of
/// `mode` on the sun-lit box, and the share painted blue (darker than the reference).
fn painted_by_bias_view(mode: Mode, extra: &[&str]) -> (f64, f64) {
    let scene = sun_lit_cornell();
    let settings = common::settings(&[&["jitter=false"], extra].concat());
    let mut r = renderer_of(&scene, CORNELL, settings);
    // The reference from two independent halves, and its own noise from their difference
    // (the RMSE of the mean of two is half the RMSE between them), as the cache estimates it.
    let first = common::reference(&mut r, 8, 64);
    r.set_seed(77);
    let second = common::reference(&mut r, 8, 64);
    r.set_seed(0);
    let noise = restir_render::metrics::luma_rmse(&first, &second).unwrap() / 2.0;
    let reference = LinearImage::from_fn(first.width, first.height, |x, y| {
        let i = (y * first.width + x) as usize;
        std::array::from_fn(|c| 0.5 * (first.pixels[i][c] + second.pixels[i][c]))
    });
    r.set_reference_image(&reference, noise as f32).unwrap();
    r.set_mode(mode);
    r.set_view(ViewSettings {
        view: DebugView::Bias,
        ..ViewSettings::default()
    });
    common::accumulate(&mut r, 128);
    r.redisplay().unwrap();
    let rgba = r.read_display_rgba8();
    let pixels = rgba.len() / 4;
    let (mut painted, mut blue) = (0usize, 0usize);
    for p in rgba.chunks(4) {
        // Neutral pixels are grey, at most 0.55 linear (196 in sRGB); the palette is white
        // at 0 and coloured elsewhere.
        let grey = p[0] == p[1] && p[1] == p[2] && p[0] < 230;
        if !grey {
            painted += 1;
            if p[2] > p[0] {
                blue += 1;
            }
        }
    }
    (painted as f64 / pixels as f64, blue as f64 / pixels as f64)
}

#[test]
fn the_bias_view_paints_bias_not_noise() {
    // Unbiased estimators: the difference from a 1024-spp reference is noise, and the view
    // leaves it grey. Every pixel is tested at 3 σ (0.3 % false alarms for Gaussian noise);
    // batch means of 16 correlated frames underestimate the noise a little, so up to 4 % of
    // the pixels may be painted.
    let (reference_painted, _) = painted_by_bias_view(Mode::Reference, &["reference_spp=4"]);
    let (restir_painted, _) = painted_by_bias_view(Mode::Restir, &[]);
    eprintln!(
        "bias view, painted share: reference {:.2} %, restir {:.2} %",
        100.0 * reference_painted,
        100.0 * restir_painted
    );
    assert!(
        reference_painted < 0.04,
        "{:.2} %",
        100.0 * reference_painted
    );
    assert!(restir_painted < 0.04, "{:.2} %", 100.0 * restir_painted);
    // The planted twin: visibility reuse with unshadowed MIS terms is 8 % dark along the
    // sun's shadow edges and in the shadowed walls: blue, over 15 % of the image (measured).
    let (planted, blue) = painted_by_bias_view(Mode::Restir, &["mis_visibility=false"]);
    eprintln!(
        "bias view, mis_visibility off: painted {:.2} %, blue {:.2} %",
        100.0 * planted,
        100.0 * blue
    );
    assert!(planted > 0.08, "detector silent: {:.2} %", 100.0 * planted);
    assert!(
        blue > 0.8 * planted,
        "the bias is dark: {:.2} % blue",
        100.0 * blue
    );
}
