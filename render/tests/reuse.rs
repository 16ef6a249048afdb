//! Temporal and spatial reuse (docs/src/temporal-reuse.md, docs/src/spatial-reuse.md) lower
//! the error, stay within
//! their documented bias, record their rejections faithfully and keep M within its cap.
//!
//! Sizes are tiny (lavapipe on two cores). The figures below were measured with spatial
//! radii chosen per width — 8 px at 128, 6 px at 96 — before the radius followed the
//! height by itself; the tests set exactly those effective radii (common::radius_px).

use crate::common;

use restir_render::di::constants::*;
use restir_render::gpu_types::GpuPixelDebug;
use restir_render::shader_constants::*;
use restir_render::{Mode, Renderer};

fn temporal_merged(d: &[GpuPixelDebug]) -> usize {
    d.iter()
        .filter(|p| p.flags & DEBUG_FLAG_TEMPORAL_MERGED != 0)
        .count()
}

#[test]
fn temporal_then_spatial_lower_per_frame_error_on_many_lights() {
    let small_radius = common::radius_px(8.0, 80);
    let small_radius = small_radius.as_str();
    let mut r = common::renderer(
        "builtin:many-lights",
        128,
        80,
        Mode::Reference,
        common::settings(&["jitter=false", small_radius]),
    );
    let reference = common::reference(&mut r, 8, 64);
    let mut measure = |assign: &[&str]| {
        r.set_settings(common::settings(
            &[&["jitter=false", small_radius][..], assign].concat(),
        ));
        r.set_mode(Mode::Restir);
        common::per_frame_errors(&mut r, &reference, 24)
    };
    let (ris, ris_stability) = measure(&["temporal=false", "spatial=false"]);
    let (temporal, temporal_stability) = measure(&["spatial=false"]);
    let (both, _) = measure(&[]);
    eprintln!(
        "per-frame luma RMSE: ris {ris:.4}, +temporal {temporal:.4}, +spatial {both:.4}; stability {ris_stability:.4} → {temporal_stability:.4}"
    );
    // Measured (lavapipe) with the default pairwise MIS: 0.387 → 0.271 → 0.249, stability
    // 0.545 → 0.320 (with 1/M, the earlier default: 0.387 → 0.313 → 0.270). Each step must
    // win by 5 %: enough above run-to-run noise at 24 frames, with the same reference
    // noise in every number (it adds Var_ref to each MSE and cannot reorder them).
    assert!(temporal < ris * 0.95, "temporal {temporal} vs ris {ris}");
    assert!(
        both < temporal * 0.95,
        "temporal+spatial {both} vs temporal {temporal}"
    );
    assert!(
        temporal_stability < ris_stability * 0.95,
        "stability {temporal_stability} vs {ris_stability}"
    );
}

/// 1/M weights, the default until pairwise MIS replaced it: the figures below
/// were measured with it.
const ONE_OVER_M: &str = "bias_correction=one-over-m";

/// Accumulated bias of ReSTIR (default settings plus `extra`) against the reference.
fn restir_luminance_ratio(scene: &str, size: (u32, u32), extra: &[&str]) -> f64 {
    let radius = common::radius_for(size.0, size.1);
    let assign = [&["jitter=false", radius.as_str()][..], extra].concat();
    let mut r = common::renderer(
        scene,
        size.0,
        size.1,
        Mode::Reference,
        common::settings(&assign),
    );
    let reference = common::reference(&mut r, 8, 64);
    r.set_mode(Mode::Restir);
    r.request_cut();
    let img = common::accumulate(&mut r, 64);
    img.mean_luminance() / reference.mean_luminance()
}

#[test]
fn accumulated_restir_stays_within_five_percent_of_the_reference() {
    for (scene, size) in [
        ("builtin:cornell", (64, 48)),
        ("builtin:many-lights", (96, 60)),
    ] {
        let ratio = restir_luminance_ratio(scene, size, &[ONE_OVER_M]);
        eprintln!("{scene}: restir (1/M) mean luminance / reference = {ratio:.4}");
        // 5 %: the bound set for the biased 1/M estimator. Measured: cornell 0.99, many-lights
        // 0.957 — darkening where a sample visible at the pixel that found it (visibility reuse) is
        // occluded at the pixel that reuses it while its M still counts; without initial visibility
        // it is 0.99 (docs/src/mis-and-bias.md, "Measured bias").
        assert!((ratio - 1.0).abs() < 0.05, "{scene}: ratio {ratio}");
    }
}

#[test]
fn pairwise_mis_is_closer_to_unbiased_than_one_over_m() {
    let one_over_m = restir_luminance_ratio("builtin:many-lights", (96, 60), &[ONE_OVER_M]);
    // The default settings: pairwise MIS.
    let pairwise = restir_luminance_ratio("builtin:many-lights", (96, 60), &[]);
    eprintln!("luminance ratio: 1/M {one_over_m:.4}, pairwise {pairwise:.4}");
    assert!(
        (pairwise - 1.0).abs() < (one_over_m - 1.0).abs(),
        "pairwise {pairwise} vs 1/M {one_over_m}"
    );
    // Pairwise MIS with unshadowed cross terms is unbiased up to the (documented) bias of
    // visibility reuse; 2 % covers that plus the reference's noise.
    assert!((pairwise - 1.0).abs() < 0.02, "pairwise {pairwise}");
}

fn warm_up(r: &mut Renderer, frames: u32) {
    for _ in 0..frames {
        r.render_frame().unwrap();
    }
}

#[test]
fn a_camera_cut_rejects_every_temporal_sample() {
    let mut r = common::renderer(
        "builtin:cornell",
        64,
        48,
        Mode::Restir,
        common::settings(&[]),
    );
    warm_up(&mut r, 4);
    assert!(
        temporal_merged(&r.read_debug()) > 0,
        "a static camera should reuse history"
    );
    let camera = r.camera();
    r.set_camera(restir_render::Camera::look_at(
        camera.position + glam::Vec3::new(0.5, 0.3, -1.5),
        glam::Vec3::new(0.0, 1.0, 0.0),
        camera.yfov,
    ));
    r.request_cut();
    r.render_frame().unwrap();
    let debug = r.read_debug();
    let surfaces = r.read_surfaces();
    let lit: Vec<_> = debug
        .iter()
        .zip(&surfaces)
        .filter(|(_, s)| s.depth > 0.0)
        .map(|(d, _)| d)
        .collect();
    let invalid = lit
        .iter()
        .filter(|d| d.temporal_mask & (REJECT_OFFSCREEN | REJECT_SURFACE) != 0)
        .count();
    assert!(
        invalid as f64 >= 0.99 * lit.len() as f64,
        "{invalid} of {} pixels flagged",
        lit.len()
    );
    assert_eq!(temporal_merged(&debug), 0);
    let reports = r.collect_reports(true);
    let last = reports.last().unwrap();
    assert_eq!(last.counters.get(STAT_TEMPORAL_ACCEPTED), 0);
    assert_eq!(last.counters.get(STAT_SOURCE + SOURCE_TEMPORAL), 0);
}

#[test]
fn turning_a_check_off_removes_its_bit_everywhere() {
    for (param, bit) in [
        ("check_surface", REJECT_SURFACE),
        ("check_depth", REJECT_DEPTH),
        ("check_normal", REJECT_NORMAL),
    ] {
        let mut r = common::renderer(
            "builtin:many-lights",
            64,
            40,
            Mode::Restir,
            common::settings(&[]),
        );
        warm_up(&mut r, 2);
        // An orbit and a cut produce plenty of every geometric rejection.
        r.set_camera(restir_render::Camera {
            yfov: r.camera().yfov,
            ..r.camera()
        });
        let cam = r.camera();
        r.set_camera(restir_render::Camera::look_at(
            cam.position + cam.right() * 1.0,
            cam.position + cam.forward() * 3.0,
            cam.yfov,
        ));
        r.request_cut();
        r.render_frame().unwrap();
        let with: usize = r
            .read_debug()
            .iter()
            .filter(|d| d.temporal_mask & bit != 0)
            .count();
        r.set_settings(common::settings(&[&format!("{param}=false")]));
        warm_up(&mut r, 2);
        let cam = r.camera();
        r.set_camera(restir_render::Camera::look_at(
            cam.position - cam.right() * 1.0,
            cam.position + cam.forward() * 3.0,
            cam.yfov,
        ));
        r.request_cut();
        r.render_frame().unwrap();
        let debug = r.read_debug();
        let without = debug
            .iter()
            .filter(|d| d.temporal_mask & bit != 0 || d.spatial_mask & bit != 0)
            .count();
        assert!(
            with > 0 || bit != REJECT_SURFACE,
            "{param}: the cut should set the bit first"
        );
        assert_eq!(
            without, 0,
            "{param}=false still sets its bit on {without} pixels"
        );
    }
}

#[test]
fn target_ratio_clamp_one_rejects_every_changed_target() {
    // Static camera, no jitter, no permutation: every pixel re-reads its own history at the same
    // surface point, so the re-evaluated target equals the stored one bit for bit and clamp 1
    // accepts. Then an orbit changes every target: clamp 1 stops every temporal sample. Under 1/M
    // it rejects the history; under pairwise MIS (docs/src/mis-and-bias.md, "The two rules of
    // unbiased reuse") the history stays a domain whose sample gets weight 0 outside the window, so
    // it is merged, counted as a ratio failure, and never survives.
    for bias_correction in ["one-over-m", "pairwise"] {
        let pairwise = bias_correction == "pairwise";
        let base = [
            "jitter=false",
            "permutation=false",
            "target_ratio_clamp=1",
            "spatial=false",
            &format!("bias_correction={bias_correction}"),
        ];
        let mut r = common::renderer(
            "builtin:cornell",
            64,
            48,
            Mode::Restir,
            common::settings(&base),
        );
        warm_up(&mut r, 3);
        let debug = r.read_debug();
        let ratio_rejected = debug
            .iter()
            .filter(|d| d.temporal_mask & REJECT_TARGET_RATIO != 0)
            .count();
        assert_eq!(ratio_rejected, 0, "unchanged targets must pass clamp 1");
        assert!(temporal_merged(&debug) > 0);
        assert!(debug.iter().any(|d| d.source == SOURCE_TEMPORAL));

        let center = r.scene_bounds().center();
        let cam = r.camera();
        let q = glam::Quat::from_rotation_y(2f32.to_radians());
        r.set_camera(restir_render::Camera {
            position: center + q * (cam.position - center),
            rotation: q * cam.rotation,
            yfov: cam.yfov,
        });
        r.render_frame().unwrap();
        let debug = r.read_debug();
        let only_ratio = debug
            .iter()
            .filter(|d| d.temporal_mask == REJECT_TARGET_RATIO)
            .count();
        assert!(
            only_ratio > 100,
            "{bias_correction}: the ratio test should be what stops them ({only_ratio} pixels)"
        );
        let temporal_survivors = debug.iter().filter(|d| d.source == SOURCE_TEMPORAL).count();
        assert_eq!(
            temporal_survivors, 0,
            "{bias_correction}: every target changed, clamp 1 must stop every temporal sample"
        );
        if pairwise {
            assert!(
                temporal_merged(&debug) > 100,
                "pairwise keeps the history as a domain"
            );
        } else {
            assert_eq!(
                temporal_merged(&debug),
                0,
                "1/M: every target changed, clamp 1 must reject every temporal sample"
            );
        }
    }
}

#[test]
fn m_never_exceeds_its_cap_and_nothing_is_non_finite() {
    for cap in ["0", "1", "5", "20"] {
        let mut r = common::renderer(
            "builtin:many-lights",
            48,
            32,
            Mode::Restir,
            common::settings(&[&format!("m_cap={cap}"), "spatial_passes=2"]),
        );
        warm_up(&mut r, 6);
        let cap: f32 = cap.parse().unwrap();
        for d in r.read_debug() {
            for m in [d.m_initial, d.m_temporal, d.m_spatial] {
                assert!(m.is_finite() && m <= cap.max(1.0), "M {m} with cap {cap}");
            }
            assert!(
                d.m_temporal <= cap && d.m_spatial <= cap,
                "M after reuse above cap {cap}"
            );
        }
        for res in r.read_final_reservoirs() {
            assert!(
                res.m <= cap
                    && res.weight.is_finite()
                    && res.w_sum.is_finite()
                    && res.p_hat.is_finite()
            );
        }
        let img = r.read_radiance();
        assert_eq!(img.non_finite_count(), 0);
        let nonfinite: u64 = r
            .collect_reports(true)
            .iter()
            .map(|r| r.counters.non_finite_total())
            .sum();
        assert_eq!(nonfinite, 0, "cap {cap}");
    }
}

/// The rejection view's spatial part (docs/src/debug-views.md, "The views"): where no temporal
/// reason applies, the grey level is the fraction of spatial neighbours rejected, (K·P − accepted)
/// / (K·P).
#[test]
fn the_rejection_view_shows_how_many_spatial_neighbours_were_rejected() {
    // Temporal off: no temporal bits, so every surface pixel shows the spatial count.
    let mut r = common::renderer(
        "builtin:many-lights",
        64,
        40,
        Mode::Restir,
        common::settings(&["temporal=false", "spatial_passes=2"]),
    );
    r.set_view(restir_render::ViewSettings {
        view: restir_render::DebugView::Rejection,
        ..Default::default()
    });
    warm_up(&mut r, 2);
    let debug = r.read_debug();
    let rgba = r.read_display_rgba8();
    let tries = 5 * 2;
    let srgb = |x: f32| {
        let c = if x <= 0.0031308 {
            x * 12.92
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        };
        (c * 255.0).round() as i32
    };
    let surfaces = r.read_surfaces();
    let (mut checked, mut partly) = (0, 0);
    for (i, d) in debug.iter().enumerate() {
        if surfaces[i].depth <= 0.0 {
            continue;
        }
        let rejected = tries - d.spatial_accepted.min(tries);
        let expected = srgb(0.45 * rejected as f32 / tries as f32);
        let shown = rgba[4 * i] as i32;
        assert!(
            (shown - expected).abs() <= 1 && rgba[4 * i + 1] == rgba[4 * i],
            "pixel {i}: {rejected} of {tries} rejected should be grey {expected}, shows {:?}",
            &rgba[4 * i..4 * i + 3]
        );
        checked += 1;
        partly += (rejected > 0 && rejected < tries) as usize;
    }
    // Not a uniform image: the count varies over the frame.
    assert!(
        checked > 1000 && partly > checked / 10,
        "{checked} pixels, {partly} partly rejected"
    );
}

/// The spatial radius follows the image height (docs/src/spatial-reuse.md, "The radius follows
/// the resolution"). At 96×96 with default settings
/// restir is clearly below ris; left at 30 px (the rule skipped, planted here) the disk
/// reaches across a third of the image, onto other surfaces, and reuse loses its lead.
#[test]
fn with_defaults_restir_beats_ris_at_96_pixels_because_the_radius_scales() {
    let mut r = common::renderer(
        "builtin:many-lights",
        96,
        96,
        Mode::Reference,
        common::settings(&["jitter=false"]),
    );
    let reference = common::reference(&mut r, 8, 64);
    let mut measure = |mode: Mode, assign: &[&str]| {
        r.set_settings(common::settings(&[&["jitter=false"][..], assign].concat()));
        r.set_mode(mode);
        common::per_frame_errors(&mut r, &reference, 16).0
    };
    let ris = measure(Mode::Ris, &[]);
    let restir = measure(Mode::Restir, &[]);
    let unscaled = measure(Mode::Restir, &[&common::radius_px(30.0, 96)]);
    eprintln!(
        "per-frame luma RMSE at 96×96: ris {ris:.4}, restir {restir:.4}, restir with 30 px {unscaled:.4}"
    );
    // Measured here: ris 0.410, restir 0.237 (2.7 px), 30 px 0.307; the bench (30 frames,
    // 1024 spp reference) agrees: restir 0.227–0.246 at 2–4 px. 0.8× leaves
    // room for the shorter run and the noisier 512-spp reference used here.
    assert!(restir < 0.8 * ris, "restir {restir} vs ris {ris}");
    // The detector: without the rule the lead shrinks by well over run-to-run noise.
    assert!(
        unscaled > 1.1 * restir,
        "30 px {unscaled} vs scaled {restir}"
    );
}

/// Reservoir age (docs/src/ris.md, "Conventions"): frames since the surviving sample was first
/// drawn, packed above AGE_SHIFT in `source`. It grows by one per frame a history sample survives,
/// never beyond the frames rendered, and stays 0 without temporal reuse.
#[test]
fn reservoir_age_counts_frames_of_survival() {
    let frames = 6u32;
    let ages = |assign: &[&str]| {
        let mut r = common::renderer(
            "builtin:cornell",
            32,
            24,
            Mode::Restir,
            common::settings(&[&["jitter=false"][..], assign].concat()),
        );
        for _ in 0..frames {
            r.render_frame().unwrap();
        }
        r.read_final_reservoirs()
            .iter()
            .filter(|res| res.light != restir_render::gpu_types::NO_LIGHT)
            .map(|res| (res.source & SOURCE_MASK, res.source >> AGE_SHIFT))
            .collect::<Vec<_>>()
    };
    let with_history = ages(&[]);
    assert!(with_history.iter().all(|&(_, age)| age < frames));
    let old = with_history.iter().filter(|&&(_, age)| age >= 2).count();
    assert!(
        old > with_history.len() / 10,
        "{old} of {} pixels keep a sample ≥ 2 frames",
        with_history.len()
    );
    // A fresh initial survivor is age 0.
    assert!(
        with_history
            .iter()
            .filter(|&&(s, _)| s == SOURCE_INITIAL)
            .all(|&(_, a)| a == 0)
    );
    let without = ages(&["temporal=false"]);
    assert!(without.iter().all(|&(_, age)| age == 0));
}
