//! The accuracy logic on a real renderer without a window (lavapipe in CI): the
//! reference arrives through the background job and the cache, every frame after it
//! gets a point with finite, positive errors, and a second run loads the cached
//! reference; with jitter on, frames are scored against their own phase's reference.
//! Fails with a clear message when there is no adapter.

use std::sync::Arc;
use std::time::{Duration, Instant};

use restir_render::gpu::timing::TimingMode;
use restir_render::reference_cache::ReferenceCache;
use restir_render::{Gpu, Renderer, Settings, load_scene};

use super::tracker::{AccuracyTracker, SceneSource};
use super::*;

const SCENE: &str = "builtin:cornell";
const FRAMES: usize = 6;

fn gpu() -> Gpu {
    Gpu::new_headless().unwrap_or_else(|e| {
        panic!(
            "this test needs a wgpu adapter (lavapipe: apt-get install mesa-vulkan-drivers): {e}"
        )
    })
}

/// A tracker with no settle time and the panel open, measuring every frame against
/// references of `spp`.
fn measuring(cache: &ReferenceCache, spp: u32) -> (AccuracyTracker, AccuracyState) {
    let mut state = AccuracyState::new(true);
    state.panel_open = true;
    state.every_frame = true;
    state.reference_spp = spp;
    (AccuracyTracker::new(cache.clone(), Duration::ZERO), state)
}

/// Renders frames, handing each to the tracker as the viewer does, until the reference
/// is there and `FRAMES` frames were measured against it; also says how passes were timed.
fn measure(cache: &ReferenceCache) -> (AccuracyState, TimingMode) {
    let scene = Arc::new(load_scene(SCENE).unwrap_or_else(|e| panic!("{e:#}")));
    // Jitter off, as the bench measures: the reference shades the rasterised surfaces.
    let settings = Settings {
        jitter: false,
        ..Settings::default()
    };
    let mut renderer =
        Renderer::new(gpu(), &scene, 24, 16, settings).unwrap_or_else(|e| panic!("{e:#}"));
    let source = SceneSource {
        spec: SCENE,
        scene: &scene,
    };
    let (mut tracker, mut state) = measuring(cache, 4);
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut measured = 0;
    while measured < FRAMES {
        renderer.render_frame().unwrap_or_else(|e| panic!("{e}"));
        tracker.update(&mut renderer, &source, &mut state, true);
        tracker.measure(&renderer, &mut state);
        for report in renderer.collect_reports(false) {
            state.curves.record_report(&report);
        }
        match &state.reference {
            ReferenceStatus::Ready(_) => measured += 1,
            ReferenceStatus::Failed(e) => panic!("the reference failed: {e}"),
            _ => {
                assert!(Instant::now() < deadline, "no reference after 60 s");
                std::thread::sleep(Duration::from_millis(5));
            }
        }
    }
    for report in renderer.collect_reports(true) {
        state.curves.record_report(&report);
    }
    (state, renderer.timing_mode())
}

fn info(state: &AccuracyState) -> &ReferenceInfo {
    match &state.reference {
        ReferenceStatus::Ready(info) => info,
        other => panic!("no reference: {other:?}"),
    }
}

#[test]
fn accuracy_curve_gets_a_point_per_frame_and_the_reference_is_cached() {
    let dir = std::env::temp_dir().join(format!("restir-viewer-accuracy-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let cache = ReferenceCache::new(&dir);

    let (first, timing) = measure(&cache);
    assert!(!info(&first).from_cache, "a fresh cache renders");
    assert!(info(&first).path.is_file(), "the reference is stored");
    let curve = first.curves.current.as_ref().expect("a curve");
    assert_eq!(curve.points.len(), FRAMES, "one point per frame");
    let xs: Vec<u64> = curve.points.iter().map(|p| p.x).collect();
    assert_eq!(xs, (1..=FRAMES as u64).collect::<Vec<_>>());
    for p in &curve.points {
        for (name, v) in [
            ("per-frame", p.luma_rmse),
            ("accumulated", p.accumulated_rgb_rmse),
        ] {
            assert!(v.is_finite() && v > 0.0, "{name} RMSE {v} at frame {}", p.x);
        }
        assert!(p.luma_ratio.is_finite() && p.luma_ratio > 0.0);
    }
    assert!(curve.points[1..].iter().all(|p| p.stability.is_some()));
    if timing != TimingMode::Off {
        assert!(
            curve.time_summary().frame_gpu_ms_median.is_some(),
            "pass times reached the curve"
        );
    }

    let (second, _) = measure(&cache);
    assert!(
        info(&second).from_cache,
        "the second run loads the reference"
    );
    assert_eq!(info(&second).path, info(&first).path);
    let _ = std::fs::remove_dir_all(&dir);
}

/// With jitter on (the viewer's default) no frame is scored before its jitter phase has a
/// reference, and a scored frame's per-frame error is its estimator's: far below what the
/// same frame reads against the antialiased reference (the planted twin, the measurement
/// this replaced, which the pixel footprint dominates: docs/src/viewer.md, "Accuracy with
/// jitter on").
#[test]
fn jittered_frames_are_scored_against_their_own_phase() {
    let dir = std::env::temp_dir().join(format!("restir-viewer-phases-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let cache = ReferenceCache::new(&dir);
    let scene = Arc::new(load_scene(SCENE).unwrap_or_else(|e| panic!("{e:#}")));
    let size = (24, 16);
    let mut renderer = Renderer::new(gpu(), &scene, size.0, size.1, Settings::default())
        .unwrap_or_else(|e| panic!("{e:#}"));
    assert!(renderer.settings().jitter, "the default");
    let source = SceneSource {
        spec: SCENE,
        scene: &scene,
    };
    let (mut tracker, mut state) = measuring(&cache, 64);
    let request = restir_render::reference_cache::ReferenceRequest::new(
        SCENE,
        &scene,
        renderer.camera(),
        size,
        state.reference_spp,
        true,
    );
    let deadline = Instant::now() + Duration::from_secs(90);
    let mut antialiased = None;
    let mut scored = Vec::new();
    while scored.len() < 4 {
        assert!(
            Instant::now() < deadline,
            "4 phase-scored frames not within 90 s"
        );
        renderer.render_frame().unwrap_or_else(|e| panic!("{e}"));
        tracker.update(&mut renderer, &source, &mut state, true);
        let before = state.curves.current.as_ref().map_or(0, |c| c.points.len());
        tracker.measure(&renderer, &mut state);
        let after = state.curves.current.as_ref().map_or(0, |c| c.points.len());
        if let ReferenceStatus::Failed(e) = &state.reference {
            panic!("the reference failed: {e}");
        }
        if let Some(e) = state.phases.as_ref().and_then(|p| p.failed.clone()) {
            panic!("a phase reference failed: {e}");
        }
        let ready = state.phases.as_ref().map_or(0, |p| p.ready);
        if ready == 0 {
            assert_eq!(
                after, 0,
                "a frame was scored before any phase had its reference"
            );
        }
        if after > before {
            let plain = antialiased.get_or_insert_with(|| {
                cache
                    .load(&request)
                    .unwrap()
                    .expect("the tracker cached it")
                    .image
            });
            let point = state
                .curves
                .current
                .as_ref()
                .unwrap()
                .points
                .last()
                .unwrap();
            let planted =
                restir_render::metrics::luma_rmse(&renderer.read_radiance(), plain).unwrap();
            scored.push((point.luma_rmse, planted));
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    eprintln!("per-frame luma RMSE (against its phase, against the antialiased): {scored:?}");
    for (own, planted) in scored {
        // TOLERANCE: at 24×16 the footprint is nearly all of the antialiased figure (edges
        // cover many pixels): scored against its phase a frame read 0.005-0.007 against
        // 0.47 when this was written (see the message). Half leaves a wide margin and
        // still fails a tracker that scores against the antialiased reference (ratio 1).
        assert!(own.is_finite() && own > 0.0, "{own}");
        assert!(own < 0.5 * planted, "scored {own} vs antialiased {planted}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
