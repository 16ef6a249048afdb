//! The figures over seeds on synthetic estimators whose mean, bias and variance are known,
//! each with a planted twin (docs/src/measured/how-the-bench-measures.md, "Error bars").

use super::*;
use crate::test_hash::hash;

/// A standard normal number per (index, stream) (Box–Muller on two hashed uniforms).
fn normal(i: u32, stream: u32) -> f64 {
    let u1 = (hash(i, 2 * stream) as f64 + 0.5 / 16_777_216.0).min(1.0);
    let u2 = hash(i, 2 * stream + 1) as f64;
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[test]
fn t_quantiles_match_the_tables() {
    assert_eq!(t95(3), 3.182);
    assert_eq!(t95(30), 2.042);
    // Past the table the expansion continues it smoothly toward the normal's 1.96.
    assert!((t95(31) - 2.040).abs() < 2e-3, "{}", t95(31));
    assert!((t95(120) - 1.980).abs() < 1e-3, "{}", t95(120));
    assert!((t95(100_000) - 1.960).abs() < 1e-3);
    assert!(t95(0).is_infinite());
}

/// Share of `trials` intervals over `k` normal samples (mean 3, sd 2) that contain 3, with
/// the half-width's t replaced by `t` when given (the planted twin).
fn coverage(k: usize, trials: u32, t: Option<f64>) -> f64 {
    let mut covered = 0;
    for trial in 0..trials {
        let samples: Vec<f64> = (0..k as u32)
            .map(|s| 3.0 + 2.0 * normal(trial * 64 + s, 7))
            .collect();
        let mut interval = Interval::of(&samples);
        if let Some(t) = t {
            interval.half_width *= t / t95(k - 1);
        }
        covered += interval.contains(3.0) as u32;
    }
    covered as f64 / trials as f64
}

#[test]
fn the_interval_covers_the_mean_at_its_nominal_rate() {
    // 4000 trials of K = 4 seeds: the binomial standard error of a 95 % rate is 0.34 %, so
    // ±1.5 % is over 4 standard errors. Measured 0.954.
    let rate = coverage(4, 4000, None);
    eprintln!("t interval, K = 4: coverage {rate:.4}");
    assert!((rate - 0.95).abs() < 0.015, "coverage {rate:.4}");
    // K = 8 as well.
    let rate = coverage(8, 4000, None);
    assert!((rate - 0.95).abs() < 0.015, "coverage {rate:.4}");
}

#[test]
fn planted_normal_quantile_under_covers_at_four_seeds() {
    // The twin: 1.96 in place of t(3) = 3.18 covers ~86 % (measured 0.856), which the
    // test above would reject.
    let rate = coverage(4, 4000, Some(1.96));
    eprintln!("z interval, K = 4: coverage {rate:.4}");
    assert!(rate < 0.92, "detector silent: coverage {rate:.4}");
}

#[test]
fn intervals_display_and_widen() {
    let i = Interval::of(&[1.0, 1.01, 0.99, 1.0]);
    assert!((i.mean - 1.0).abs() < 1e-12);
    assert!(i.display(3).contains("±"));
    let one = Interval::of(&[0.97]);
    assert_eq!(one.display(2), "0.97 (one seed)");
    assert_eq!(Verdict::of(&one.shifted(1.0)), Verdict::OneSeed);
    // Adding the reference's uncertainty in quadrature widens, never narrows.
    let wide = i.widened_by(0.01);
    assert!(wide.half_width > i.half_width);
    assert_eq!(i.widened_by(0.0), i);
    // NaN seeds are left out, not averaged.
    assert_eq!(Interval::of(&[1.0, f64::NAN, 3.0]).samples, 2);
}

#[test]
fn one_seeds_interval_survives_json() {
    // A one-seed figure (infinite half-width) and a black scene's (NaN mean) are written
    // by one job and read by the merge: JSON has neither, so they travel as null.
    for interval in [Interval::of(&[0.97]), Interval::of(&[])] {
        let text = serde_json::to_string(&interval).unwrap();
        let back: Interval = serde_json::from_str(&text).unwrap();
        assert_eq!(back.samples, interval.samples, "{text}");
        assert!(back.half_width.is_infinite(), "{text}");
        assert_eq!(back.mean.is_nan(), interval.mean.is_nan(), "{text}");
    }
    let two = Interval::of(&[1.0, 2.0]);
    assert_eq!(
        serde_json::from_str::<Interval>(&serde_json::to_string(&two).unwrap()).unwrap(),
        two
    );
}

#[test]
fn verdicts_are_an_equivalence_test_at_half_a_percent() {
    let at = |mean: f64, half_width: f64| {
        Verdict::of(&Interval {
            mean,
            half_width,
            samples: 4,
        })
    };
    assert_eq!(at(0.001, 0.003), Verdict::Unbiased);
    // A small but certain bias inside the tolerance is still "consistent with 0" at the
    // matrix's resolution.
    assert_eq!(at(0.003, 0.001), Verdict::Unbiased);
    assert_eq!(at(-0.03, 0.01), Verdict::Biased);
    assert_eq!(at(0.02, 0.01), Verdict::Biased);
    assert_eq!(at(0.0, 0.02), Verdict::Undecided);
    assert_eq!(at(0.008, 0.005), Verdict::Undecided);
}

/// K seeds of F frames of a W×H image: pixel p's truth r_p = 1 + p/100, each frame
/// r_p + bias_p + σ·noise, where the noise repeats for `run` frames in a row (correlated
/// frames, as reuse makes them).
fn seeds_of(
    k: u32,
    frames: u32,
    bias: impl Fn(usize) -> f64,
    sigma: f64,
    run: u32,
) -> Vec<PixelMoments> {
    let (w, h) = (16, 16);
    (0..k)
        .map(|seed| {
            let mut m = PixelMoments::new(w, h);
            for f in 0..frames {
                let frame = LinearImage::from_fn(w, h, |x, y| {
                    let p = (y * w + x) as usize;
                    let noise = normal(p as u32 * 4096 + f / run, 100 + seed);
                    let v = (truth(p) + bias(p) + sigma * noise) as f32;
                    [v, v, v, 1.0]
                });
                m.push(&frame);
            }
            m
        })
        .collect()
}

fn truth(p: usize) -> f64 {
    1.0 + p as f64 / 100.0
}

fn reference() -> Vec<f64> {
    (0..256).map(truth).collect()
}

fn spread(seeds: &[PixelMoments]) -> PixelSpread {
    let refs: Vec<&PixelMoments> = seeds.iter().collect();
    pixel_spread(&refs, &reference(), 0.0).unwrap()
}

#[test]
fn bias_and_variance_come_apart_with_their_known_values() {
    // Bias 0.05 on every other pixel (mean squared bias 0.00125), frame σ 0.2 over 64
    // independent frames (accumulated variance 0.04/64 = 6.25e-4), 8 seeds.
    let seeds = seeds_of(8, 64, |p| if p % 2 == 0 { 0.05 } else { 0.0 }, 0.2, 1);
    let s = spread(&seeds);
    eprintln!("{s:?}");
    // 256 pixels × 8 seeds: the variance estimate's relative error is ~√(2/(7·256)) = 3 %,
    // the squared bias's standard error ~1e-4; tolerances are 3–4 of those.
    assert!(
        (s.variance.value / 6.25e-4 - 1.0).abs() < 0.12,
        "{:?}",
        s.variance
    );
    assert!(
        (s.squared_bias.value - 0.00125).abs() < 2.5e-4,
        "{:?}",
        s.squared_bias
    );
    assert!(
        (s.frame_variance / 0.04 - 1.0).abs() < 0.05,
        "{}",
        s.frame_variance
    );
    // Independent frames: worth as many as there are (±15 %: the ratio of two estimates).
    let eff = s.effective_frames.unwrap();
    assert!((eff / 64.0 - 1.0).abs() < 0.15, "effective frames {eff}");
    // The jackknife intervals contain the truth.
    let h = s.squared_bias.half_width.unwrap();
    assert!(
        (s.squared_bias.value - 0.00125).abs() < h,
        "{:?}",
        s.squared_bias
    );
    // Without bias, the squared bias is ~0 (the mean's noise is taken out).
    let unbiased = spread(&seeds_of(8, 64, |_| 0.0, 0.2, 1));
    assert!(
        unbiased.squared_bias.value.abs() < 1.5e-4,
        "{:?}",
        unbiased.squared_bias
    );
}

#[test]
fn planted_correlated_frames_are_worth_fewer_frames() {
    // The twin for the effective-sample figure: the same noise for 8 frames in a row (as a
    // reservoir that keeps its sample) leaves 64 frames worth ~8 independent ones.
    let s = spread(&seeds_of(8, 64, |_| 0.0, 0.2, 8));
    let eff = s.effective_frames.unwrap();
    eprintln!("correlated runs of 8: effective frames {eff:.1}");
    assert!(eff > 5.0 && eff < 11.0, "effective frames {eff}");
}

#[test]
fn the_bias_view_rule_flags_biased_pixels_only() {
    // 128 frames = 8 batches of 16; σ 0.2 per frame. Unbiased: a pixel is flagged only by
    // chance, |t| > 3 with 7 degrees of freedom: 2 % (256 pixels: ±0.9 %), less with the
    // 1 % floor.
    let clean = &seeds_of(1, 128, |_| 0.0, 0.2, 1)[0];
    let share = clean.flagged_share(&reference(), 0.0);
    assert!(share < 0.05, "clean share {share}");
    // Planted: +20 % on the first half of the pixels, 8 standard errors out.
    let biased = &seeds_of(
        1,
        64,
        |p| if p < 128 { 0.2 * truth(p) } else { 0.0 },
        0.2,
        1,
    )[0];
    let share = biased.flagged_share(&reference(), 0.0);
    assert!(share > 0.45 && share < 0.6, "biased share {share}");
    // Before two batches nothing is flagged.
    let early = &seeds_of(1, 31, |_| 1.0, 0.2, 1)[0];
    assert_eq!(early.flagged_share(&reference(), 0.0), 0.0);
}

#[test]
fn frames_to_tolerance_scales_with_the_spread() {
    // Ratios with sd 0.01 at 100 frames: ±0.5 % at 95 % needs (1.96·0.01/0.005)² = 15.4
    // times as many frames.
    let ratios = [0.99, 1.01, 0.99, 1.01];
    let sd = (4.0f64 * 1e-4 / 3.0).sqrt();
    let n = frames_to_tolerance(&ratios, 100, 0.005).unwrap();
    let expected = 100.0 * (1.959_964 * sd / 0.005).powi(2);
    assert!((n / expected - 1.0).abs() < 1e-3, "{n} vs {expected}");
    assert!(frames_to_tolerance(&[1.0], 100, 0.005).is_none());
}
