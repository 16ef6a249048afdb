use super::*;

fn flat(w: u32, h: u32, v: f32) -> LinearImage {
    LinearImage::from_fn(w, h, |_, _| [v, v, v, 1.0])
}

#[test]
fn lag_curve_metrics_match_hand_computed_values() {
    // Peak 5 at the event, then 3, 2, 1.2, and the steady 1.0 (last five frames' median).
    let curve = [5.0, 3.0, 2.0, 1.2, 1.05, 1.0, 1.1, 0.9, 1.0, 1.0, 1.0, 1.0];
    let m = curve_metrics(&curve, None).unwrap();
    assert_eq!(m.steady_error, 1.0);
    assert_eq!(m.peak_error, 5.0);
    assert_eq!(m.peak_over_steady, 5.0);
    // Frames 4..9 (1.05, 1.0, 1.1, 0.9, 1.0) are all ≤ 1.1: frame 3 (1.2) is the last out.
    assert_eq!(m.recovery_frames, Some(4));
    // 4 + 2 + 1 + 0.2 + 0.05 + 0.1 (frame 6) = 7.35.
    assert!((m.lag_area - 7.35).abs() < 1e-12, "{}", m.lag_area);
}

#[test]
fn lag_a_curve_already_steady_recovers_at_once() {
    let m = curve_metrics(&[2.0; 10], None).unwrap();
    assert_eq!(m.recovery_frames, Some(0));
    assert_eq!(m.lag_area, 0.0);
    assert_eq!(m.peak_over_steady, 1.0);
    // Too short for a steady level after a recovery window.
    assert!(curve_metrics(&[2.0; 9], None).is_none());
    assert!(curve_metrics(&[f64::NAN; 12], None).is_none());
}

#[test]
fn lag_a_curve_that_never_settles_never_recovers() {
    // Test power: a planted lag (error 3 for ten frames) that ends in boiling ±30 % around
    // its level never has five frames within 10 % of the tail median: "never".
    let mut curve = vec![3.0; 10];
    curve.extend((0..11).map(|k| if k % 2 == 0 { 1.0 } else { 1.3 }));
    let m = curve_metrics(&curve, None).unwrap();
    assert_eq!(m.steady_error, 1.0);
    assert_eq!(m.recovery_frames, None);
    // 10 × 2 + 5 × 0.3 = 21.5: the lag and the boiling both count.
    assert!((m.lag_area - 21.5).abs() < 1e-9, "{}", m.lag_area);
    // A dip far below steady then back is not lag: it counts as recovered.
    let dip = [1.0, 0.2, 0.2, 0.2, 0.2, 0.2, 1.0, 1.0, 1.0, 1.0, 1.0];
    assert_eq!(curve_metrics(&dip, None).unwrap().recovery_frames, Some(0));
}

#[test]
fn lag_a_lag_that_outlasts_the_run_is_measured_against_the_level_before() {
    // Test power: a planted lag that never ends in the window (error 0.4 throughout, as a
    // huge M cap gives) looks steady from its own tail; the level carried over from before
    // the event (0.15) exposes it.
    let stuck = [0.4; 12];
    let own = curve_metrics(&stuck, None).unwrap();
    assert_eq!((own.lag_area, own.recovery_frames), (0.0, Some(0)));
    let m = curve_metrics(&stuck, Some(0.15)).unwrap();
    assert_eq!(m.steady_error, 0.15);
    assert_eq!(m.recovery_frames, None);
    assert!((m.lag_area - 12.0 * 0.25).abs() < 1e-9);
    // A run that settles lower than the carried-over level keeps its own tail.
    let settles = [0.3, 0.2, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
    let m = curve_metrics(&settles, Some(0.15)).unwrap();
    assert_eq!((m.steady_error, m.recovery_frames), (0.1, Some(2)));
}

#[test]
fn lag_signed_bias_is_positive_for_a_ghost_and_negative_for_a_dark_lag() {
    // Left half lit by a light that switches off: 1.0 → 0.2; the right half stays at 0.5.
    let scene = |left: f32| {
        LinearImage::from_fn(8, 4, move |x, _| {
            let v = if x < 4 { left } else { 0.5 };
            [v, v, v, 1.0]
        })
    };
    let (before, after) = (scene(1.0), scene(0.2));
    let mask = changed_mask(&before, &after);
    // The 3×3 filter blurs the edge: columns 0..=4 change (column 4 sees column 3).
    let changed: Vec<u32> = (0..8).filter(|&x| mask[x as usize]).collect();
    assert_eq!(changed, vec![0, 1, 2, 3, 4]);
    // A ghost: the frame still shows the left half at 0.6 (the off light's samples kept).
    let ghost = signed_bias(&scene(0.6), &after, &mask).unwrap();
    // Changed pixels: 4 left columns (ref 0.2, frame 0.6) + column 4 (0.5, 0.5), 4 rows:
    // Σ diff = 16 × 0.4 = 6.4, Σ ref = 16 × 0.2 + 4 × 0.5 = 5.2.
    assert!((ghost - 6.4 / 5.2).abs() < 1e-5, "{ghost}");
    // A dark lag: a light switching on (0.2 → 1.0) that the frame shows at 0.5.
    let mask_on = changed_mask(&after, &before);
    let dark = signed_bias(&scene(0.5), &before, &mask_on).unwrap();
    assert!(dark < -0.3, "{dark}");
    assert!(signed_bias(&after, &after, &mask).unwrap().abs() < 1e-6);
    // Nothing changed: no pixels, no bias.
    let none = changed_mask(&before, &before);
    assert!(none.iter().all(|&m| !m));
    assert_eq!(signed_bias(&before, &before, &none), None);
}

#[test]
fn lag_event_frames_follow_the_clip_time() {
    // 30 fps from 0.7 s: frame 9 is at 1.0 s (the switch-off), frame 39 at 2.0 s.
    let times: Vec<f32> = (0..45).map(|i| 0.7 + i as f32 / 30.0).collect();
    let wrap = |t: f32| t.rem_euclid(3.0);
    let frames = event_frames(&times, &[1.0, 2.0], 3.0, wrap);
    assert_eq!(frames.len(), 2);
    for (&f, e) in frames.iter().zip([1.0f32, 2.0]) {
        assert!(times[f] >= e && times[f - 1] < e, "{f}");
    }
    // Across the loop: 2.9 → 3.1 s passes the clip time 0.05.
    assert_eq!(event_frames(&[2.9, 3.1], &[0.05], 3.0, wrap), vec![1]);
    assert!(event_frames(&[0.7; 10], &[1.0], 3.0, wrap).is_empty());
}

#[test]
fn lag_detection_fires_on_a_switch_and_not_on_noise() {
    let noisy = |v: f32, seed: u32| {
        LinearImage::from_fn(32, 16, move |x, y| {
            // ±20 % per-pixel hash noise, mean 0: the block means barely move.
            let h = (x * 7919 + y * 104_729 + seed * 31).wrapping_mul(2_654_435_761) >> 16;
            let n = v * (1.0 + 0.4 * ((h % 1000) as f32 / 1000.0 - 0.5));
            [n, n, n, 1.0]
        })
    };
    let refs = [
        noisy(1.0, 0),
        noisy(1.0, 1),
        noisy(0.5, 2),
        noisy(0.5, 3),
        flat(32, 16, 0.5),
    ];
    assert_eq!(detected_event_frames(&refs), vec![2]);
}
