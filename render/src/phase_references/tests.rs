//! The phase references on a synthetic image whose footprint is known: every pixel holds a
//! straight edge between 0 and 2, so a frame at offset o sees one side (I(o)), the
//! antialiased reference the average over the 64 offsets (R). Two "estimators" add
//! independent noise of a known standard deviation to I(o) of each frame.

use super::*;
use crate::metrics::luma_rmse;
use crate::renderer::jitter_offset;
use crate::test_hash::hash;

const W: u32 = 32;
const H: u32 = 24;

/// What a frame at jitter phase `phase` sees without noise: the side of pixel (x, y)'s edge
/// its sample point lies on (edges of every slope and position, one per pixel).
fn footprint_image(phase: u32) -> LinearImage {
    let o = jitter_offset(phase);
    LinearImage::from_fn(W, H, |x, y| {
        let i = y * W + x;
        let angle = hash(i, 1) * std::f32::consts::TAU;
        let c = hash(i, 2) - 0.5;
        let v = if o.x * angle.cos() + o.y * angle.sin() < c * 0.7 {
            0.0
        } else {
            2.0
        };
        [v, v, v, 1.0]
    })
}

/// The pixel average over the period: what the antialiased reference converges to.
fn antialiased() -> LinearImage {
    let frames: Vec<LinearImage> = (0..JITTER_PERIOD as u32).map(footprint_image).collect();
    LinearImage::from_fn(W, H, |x, y| {
        let v = frames.iter().map(|f| f.get(x, y)[0]).sum::<f32>() / frames.len() as f32;
        [v, v, v, 1.0]
    })
}

/// Frame `frame` of an estimator with per-pixel noise of standard deviation `sigma`
/// (uniform, so the numbers are exact to the hash's quality).
fn noisy_frame(frame: u64, sigma: f32, stream: u32) -> LinearImage {
    let clean = footprint_image(jitter_phase(frame));
    LinearImage::from_fn(W, H, |x, y| {
        let n = (hash(y * W + x + frame as u32 * W * H, stream) - 0.5) * 12f32.sqrt() * sigma;
        let v = clean.get(x, y)[0] + n;
        [v, v, v, 1.0]
    })
}

fn all_phases() -> PhaseReferences {
    let mut phases = PhaseReferences::default();
    for p in 0..JITTER_PERIOD as u32 {
        phases.insert(p, footprint_image(p));
    }
    phases
}

/// Mean per-frame luma RMSE over one period of frames, each against `reference(frame)`.
fn mean_rmse(sigma: f32, stream: u32, reference: impl Fn(u64) -> LinearImage) -> f64 {
    let frames = 0..JITTER_PERIOD;
    let sum: f64 = frames
        .clone()
        .map(|f| luma_rmse(&noisy_frame(f, sigma, stream), &reference(f)).unwrap())
        .sum();
    sum / frames.count() as f64
}

#[test]
fn scored_against_its_phase_a_frame_measures_the_estimator_alone() {
    let (plain, phases) = (antialiased(), all_phases());
    let matched = |f: u64| {
        reference_for_frame(true, f, &plain, &phases)
            .expect("every phase is there")
            .clone()
    };
    let (good, bad) = (0.03, 0.1);
    let a = mean_rmse(good, 3, matched);
    let b = mean_rmse(bad, 4, matched);
    // 768 pixels × 64 frames of uniform noise: the RMSE is σ to about 0.2 % (relative sd of
    // one frame's MSE √(0.8/768) ≈ 3 %, /√64); 5 % leaves room for the hash.
    assert!((a / good as f64 - 1.0).abs() < 0.05, "good estimator: {a}");
    assert!((b / bad as f64 - 1.0).abs() < 0.05, "bad estimator: {b}");

    // Planted: the same frames against the antialiased reference are dominated by the
    // footprint (RMSE √(σ² + F), F ≈ 0.5 here): the two estimators read nearly alike.
    let a_plain = mean_rmse(good, 3, |_| plain.clone());
    let b_plain = mean_rmse(bad, 4, |_| plain.clone());
    let footprint: f64 = (0..JITTER_PERIOD as u32)
        .map(|p| luma_rmse(&footprint_image(p), &plain).unwrap().powi(2))
        .sum::<f64>()
        / JITTER_PERIOD as f64;
    assert!(
        footprint > 0.1,
        "the model has a footprint: F = {footprint}"
    );
    assert!(a_plain / b_plain > 0.9, "plain: {a_plain} vs {b_plain}");
    assert!(a / b < 0.4, "matched: {a} vs {b}");
}

#[test]
fn jitter_off_uses_the_one_reference_and_a_missing_phase_scores_nothing() {
    let plain = antialiased();
    let mut phases = PhaseReferences::default();
    assert_eq!(phases.ready(), 0);
    assert!(reference_for_frame(true, 5, &plain, &phases).is_none());
    assert!(std::ptr::eq(
        reference_for_frame(false, 5, &plain, &phases).unwrap(),
        &plain
    ));
    phases.insert(5, footprint_image(5));
    assert_eq!(phases.ready(), 1);
    // Frame 5 and frame 5 + 64 share phase 5; frame 6 has none yet.
    assert!(reference_for_frame(true, 5 + JITTER_PERIOD, &plain, &phases).is_some());
    assert!(reference_for_frame(true, 6, &plain, &phases).is_none());
}

#[test]
fn the_next_phase_to_render_is_the_next_frames_first() {
    let mut phases = PhaseReferences::default();
    assert_eq!(phases.next_missing(10), Some(10));
    phases.insert(10, LinearImage::new(1, 1));
    assert_eq!(phases.next_missing(10), Some(11));
    // Wraps past the last phase.
    phases.insert(63, LinearImage::new(1, 1));
    assert_eq!(phases.next_missing(63), Some(0));
    let full = all_phases();
    assert_eq!(full.ready(), JITTER_PERIOD as usize);
    assert_eq!(full.next_missing(7), None);
}
