//! Metric tests on synthetic images whose answers are known in closed form.

use super::*;

fn constant(w: u32, h: u32, rgb: [f32; 3]) -> LinearImage {
    LinearImage::from_fn(w, h, |_, _| [rgb[0], rgb[1], rgb[2], 1.0])
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * b.abs().max(1.0)
}

#[test]
fn known_values_on_constant_images() {
    let grey = constant(4, 3, [1.0; 3]);
    let half = constant(4, 3, [0.5; 3]);
    let red = constant(4, 3, [1.0, 0.0, 0.0]);
    let black = constant(4, 3, [0.0; 3]);
    assert!(close(luma_rmse(&grey, &half).unwrap(), 0.5));
    assert!(close(rgb_rmse(&grey, &half).unwrap(), 0.5));
    assert!(close(luma_rmse(&red, &black).unwrap(), 0.2126));
    assert!(close(
        rgb_rmse(&red, &black).unwrap(),
        (1.0f64 / 3.0).sqrt()
    ));
    assert!(close(luma_ratio(&half, &grey).unwrap(), 0.5));
    assert_eq!(luma_ratio(&black, &black).unwrap(), 1.0);
    assert_eq!(luma_ratio(&grey, &black).unwrap(), f64::INFINITY);
    let a = constant(4, 3, [1.1; 3]);
    assert!(close(
        rel_mse(&a, &grey).unwrap(),
        0.01 / (1.0 + REL_MSE_EPSILON)
    ));
    assert!(close(
        rel_mse(&half, &black).unwrap(),
        0.25 / REL_MSE_EPSILON
    ));
    assert_eq!(luma_rmse(&grey, &grey).unwrap(), 0.0);
}

#[test]
fn mismatched_sizes_are_errors() {
    let (a, b) = (constant(4, 3, [1.0; 3]), constant(3, 4, [1.0; 3]));
    let expected = Err(MetricsError::SizeMismatch(4, 3, 3, 4));
    assert_eq!(luma_rmse(&a, &b), expected);
    assert_eq!(rgb_rmse(&a, &b), expected);
    assert_eq!(luma_ratio(&a, &b), expected);
    assert_eq!(rel_mse(&a, &b), expected);
    assert!(error_heatmap(&a, &b).is_err() && non_finite_pixels(&a, &b).is_err());
    let mut sequence = SequenceMetrics::new(a);
    assert!(sequence.push(&b).is_err());
    assert_eq!(sequence.frames(), 0);
}

#[test]
fn non_finite_pixels_are_skipped_and_counted() {
    let reference = constant(10, 1, [1.0; 3]);
    let mut a = constant(10, 1, [0.5; 3]);
    a.pixels[2] = [f32::NAN, 0.0, 0.0, 1.0];
    a.pixels[7] = [0.0, f32::INFINITY, 0.0, 1.0];
    assert_eq!(non_finite_pixels(&a, &reference), Ok(2));
    assert!(close(luma_rmse(&a, &reference).unwrap(), 0.5));
    assert!(close(rgb_rmse(&a, &reference).unwrap(), 0.5));
    assert!(close(luma_ratio(&a, &reference).unwrap(), 0.5));
    // A NaN in the reference is skipped the same way.
    assert_eq!(non_finite_pixels(&reference, &a), Ok(2));
    let all_nan = constant(2, 2, [f32::NAN; 3]);
    assert_eq!(luma_rmse(&all_nan, &all_nan), Ok(0.0));
}

#[test]
fn heatmap_uses_inferno_and_the_99th_percentile() {
    // A NaN pixel, then |Δ luma| = 1, 2, …, 100: the 99th percentile is 99.
    let reference = constant(101, 1, [0.0; 3]);
    let a = LinearImage::from_fn(101, 1, |x, _| [if x == 0 { f32::NAN } else { x as f32 }; 4]);
    assert_eq!(heatmap_scale(&a, &reference), Ok(99.0));
    let heatmap = error_heatmap(&a, &reference).unwrap();
    assert_eq!((heatmap.width, heatmap.height), (101, 1));
    assert_eq!(
        heatmap.pixels[0],
        [0.0, 1.0, 1.0, 1.0],
        "non-finite pixels are cyan"
    );
    let top = [0xfc as f32 / 255.0, 1.0, 0xa4 as f32 / 255.0, 1.0];
    assert_eq!(heatmap.pixels[99], top);
    assert_eq!(heatmap.pixels[100], top, "values above the scale saturate");
    assert!(
        heatmap
            .pixels
            .iter()
            .flatten()
            .all(|c| (0.0..=1.0).contains(c))
    );
    // Brighter with more error: inferno's luminance grows monotonically.
    let lum = |p: [f32; 4]| luminance([p[0], p[1], p[2]]);
    assert!(
        heatmap.pixels[1..]
            .windows(2)
            .all(|w| lum(w[0]) <= lum(w[1]))
    );
    assert_eq!(inferno(0.0), [0.0, 0.0, 4.0 / 255.0]);
    assert_eq!(
        inferno(0.5),
        [
            0xbc as f32 / 255.0,
            0x37 as f32 / 255.0,
            0x54 as f32 / 255.0
        ]
    );
    // Identical images: scale 0, everything at the bottom of the map.
    let same = error_heatmap(&reference, &reference).unwrap();
    assert!(same.pixels.iter().all(|p| p[..3] == inferno(0.0)));
}

#[test]
fn sequence_metrics_accuracy_stability_and_accumulation() {
    let reference = constant(3, 2, [1.0; 3]);
    let mut sequence = SequenceMetrics::new(reference.clone());
    assert_eq!(sequence.report().frames, 0);
    let mut frames: Vec<LinearImage> = (0..4)
        .map(|i| constant(3, 2, [if i % 2 == 0 { 0.75 } else { 1.25 }; 3]))
        .collect();
    // One NaN pixel: skipped in that frame's metrics, its pixel averaged over the others.
    frames[1].pixels[5] = [f32::NAN, 1.0, 1.0, 1.0];
    for frame in &frames {
        sequence.push(frame).unwrap();
    }
    let report = sequence.report();
    assert_eq!(report.frames, 4);
    assert_eq!(report.per_frame_luma_rmse, vec![0.25; 4]);
    assert_eq!(report.per_frame_stability_rmse, vec![0.5; 3]);
    assert_eq!(
        (report.mean_luma_rmse, report.mean_stability_rmse),
        (0.25, 0.5)
    );
    assert_eq!(report.non_finite_pixels, 1);
    let accumulated = sequence.accumulated();
    assert_eq!(accumulated.pixels[0], [1.0, 1.0, 1.0, 1.0]);
    // Pixel 5 saw 0.75, 0.75, 1.25: mean 11/12.
    assert!(close(accumulated.pixels[5][0] as f64, 11.0 / 12.0));
    let off = 1.0f64 / 12.0;
    assert!(close(report.accumulated_rgb_rmse, (off * off / 6.0).sqrt()));
    assert!(close(report.accumulated_luma_ratio, 1.0 - off / 6.0));
}

#[test]
fn signed_bias_and_black_pixels_on_known_images() {
    let grey = constant(4, 3, [1.0; 3]);
    let half = constant(4, 3, [0.5; 3]);
    assert!(close(signed_bias(&half, &grey).unwrap(), -0.5));
    assert!(close(signed_bias(&grey, &half).unwrap(), 1.0));
    assert_eq!(signed_bias(&grey, &grey).unwrap(), 0.0);
    // Three of twelve pixels black (one just above the 5 % line, which is not black),
    // one pixel of the reference unlit (black there is no speckle).
    let reference = LinearImage::from_fn(4, 3, |x, y| {
        let v = if (x, y) == (3, 2) { 0.0 } else { 1.0 };
        [v, v, v, 1.0]
    });
    let frame = LinearImage::from_fn(4, 3, |x, y| {
        let v = match (x, y) {
            (0, 0) | (1, 0) | (2, 0) => 0.01,
            (3, 0) => 1.2 * BLACK_FRACTION as f32,
            (3, 2) => 0.0,
            _ => 0.9,
        };
        [v, v, v, 1.0]
    });
    assert!(close(
        black_pixel_fraction(&frame, &reference).unwrap(),
        3.0 / 12.0
    ));
    assert_eq!(black_pixel_fraction(&reference, &reference).unwrap(), 0.0);
    // Through the sequence: per-frame figures averaged.
    let mut m = SequenceMetrics::new(reference.clone());
    m.push(&frame).unwrap();
    m.push(&reference).unwrap();
    let r = m.report();
    assert!(close(r.mean_black_pixel_fraction, 3.0 / 24.0));
    assert!(close(
        r.mean_signed_bias,
        0.5 * signed_bias(&frame, &reference).unwrap()
    ));
}

/// Equal per-pixel RMSE, different structure: grain (each pixel its own error) reads about
/// 1, blotches (one error per 8 × 8 tile) read 8. The low-frequency figure is the one that
/// tells them apart.
#[test]
fn low_frequency_error_tells_blotches_from_grain() {
    let (w, h) = (64u32, 48u32);
    let image = |value: &dyn Fn(u32, u32) -> f32| LinearImage {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|i| {
                let v = 1.0 + value(i % w, i / w);
                [v, v, v, 1.0]
            })
            .collect(),
    };
    let sign = |x: u32, y: u32| {
        let mut k = x.wrapping_mul(0x9E37_79B9) ^ y.wrapping_mul(0x85EB_CA6B);
        k ^= k >> 15;
        k = k.wrapping_mul(0x2C1B_3C6D);
        k ^= k >> 12;
        if k & 1 == 0 { 0.1 } else { -0.1 }
    };
    let reference = image(&|_, _| 0.0);
    let grain = image(&|x, y| sign(x, y));
    let blotches = image(&|x, y| sign(x / 8, y / 8));
    let g = luma_rmse(&grain, &reference).unwrap();
    let b = luma_rmse(&blotches, &reference).unwrap();
    assert!((g - b).abs() < 1e-6, "equal RMSE: {g} {b}");
    let grain_c = error_correlation(&grain, &reference).unwrap();
    let blotch_c = error_correlation(&blotches, &reference).unwrap();
    // 48 tiles of 64 ±0.1 values: the tile means' RMS is 0.1/8 give or take ~40 %.
    assert!((0.5..2.0).contains(&grain_c), "grain {grain_c}");
    assert!((blotch_c - 8.0).abs() < 1e-3, "blotches {blotch_c}");
    assert_eq!(error_correlation(&reference, &reference).unwrap(), 0.0);
}
