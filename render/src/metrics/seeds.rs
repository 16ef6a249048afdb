//! Figures over seeds (docs/src/measured/how-the-bench-measures.md, "Error bars"): one seed's
//! figure is a guess, so the bench runs K seeds and states every number as a mean with a 95 %
//! interval over them, splits the accumulated image's error into squared bias and variance per
//! pixel, and says how many independent frames the accumulated image is worth.
//!
//! The seeds are independent runs of the same estimator (every random stream is keyed by
//! the seed), so their per-seed figures are i.i.d. and Student's t gives an honest interval
//! even for K = 4; the frames *within* one seed are not independent (reuse correlates them),
//! which is why no interval here is built from frames.

use super::pixel_moments::PixelMoments;
use crate::image::LinearImage;

/// Confidence of every interval the lab prints.
pub const CONFIDENCE: f64 = 0.95;

/// |signed bias| the bias matrix resolves (docs/src/measured/unbiased-reuse.md, "The bias matrix"):
/// an estimator whose interval lies inside ±0.5 % is consistent with no bias at that resolution,
/// one whose interval lies wholly outside is biased.
pub const BIAS_TOLERANCE: f64 = 0.005;

/// Two-sided 95 % quantile of Student's t with `df` degrees of freedom (t such that
/// P(|T| ≤ t) = 0.95); the normal's 1.96 for df = ∞. Tabulated to 30, then the
/// Cornish–Fisher expansion in 1/df, exact to 1e-3 there.
pub fn t95(df: usize) -> f64 {
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    match df {
        0 => f64::INFINITY,
        1..=30 => TABLE[df - 1],
        _ => {
            let z: f64 = 1.959_964;
            let n = df as f64;
            z + (z.powi(3) + z) / (4.0 * n)
                + (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / (96.0 * n * n)
        }
    }
}

/// A mean over independent samples with its 95 % interval, `mean ± half_width`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Interval {
    /// NaN without a finite sample (written as null in JSON, which has no NaN).
    #[serde(with = "null_is_nan")]
    pub mean: f64,
    /// Half the interval's width; infinite with one sample (no spread to measure; null in
    /// JSON).
    #[serde(with = "null_is_infinite")]
    pub half_width: f64,
    /// How many samples (seeds) it rests on.
    pub samples: usize,
}

impl Interval {
    /// The t interval of the mean of `samples` (non-finite samples are left out: a seed
    /// that produced NaN is reported by the non-finite counts, not averaged).
    pub fn of(samples: &[f64]) -> Interval {
        let finite: Vec<f64> = samples.iter().copied().filter(|x| x.is_finite()).collect();
        let n = finite.len();
        if n == 0 {
            return Interval {
                mean: f64::NAN,
                half_width: f64::INFINITY,
                samples: 0,
            };
        }
        let mean = finite.iter().sum::<f64>() / n as f64;
        let half_width = if n < 2 {
            f64::INFINITY
        } else {
            let var = finite.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            t95(n - 1) * (var / n as f64).sqrt()
        };
        Interval {
            mean,
            half_width,
            samples: n,
        }
    }

    /// The same interval with an independent, known uncertainty of standard deviation `sd`
    /// added (the reference's own noise in its mean): the half-widths add in quadrature,
    /// the seeds' at their t, the known one at the normal's 1.96.
    pub fn widened_by(self, sd: f64) -> Interval {
        if self.samples < 2 || !(sd > 0.0) {
            return self;
        }
        Interval {
            half_width: self.half_width.hypot(1.959_964 * sd),
            ..self
        }
    }

    pub fn low(&self) -> f64 {
        self.mean - self.half_width
    }

    pub fn high(&self) -> f64 {
        self.mean + self.half_width
    }

    pub fn contains(&self, x: f64) -> bool {
        self.low() <= x && x <= self.high()
    }

    /// The interval minus a constant (a ratio's interval as a bias's: `ratio.shifted(1.0)`).
    pub fn shifted(self, by: f64) -> Interval {
        Interval {
            mean: self.mean - by,
            ..self
        }
    }

    /// `1.002 ± 0.006`, or `1.002 (one seed)` where no interval exists.
    pub fn display(&self, decimals: usize) -> String {
        if self.half_width.is_finite() {
            format!(
                "{:.*} ± {:.*}",
                decimals, self.mean, decimals, self.half_width
            )
        } else {
            format!("{:.*} (one seed)", decimals, self.mean)
        }
    }
}

/// JSON has no NaN or infinity: a non-finite mean is written as null and read back as NaN.
mod null_is_nan {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        super::finite_or_null(*x, s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
    }
}

/// … and a non-finite half-width (one seed) as null, read back as infinite.
mod null_is_infinite {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        super::finite_or_null(*x, s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::INFINITY))
    }
}

fn finite_or_null<S: serde::Serializer>(x: f64, s: S) -> Result<S::Ok, S::Error> {
    if x.is_finite() {
        s.serialize_f64(x)
    } else {
        s.serialize_none()
    }
}

/// What the bias matrix concludes from a signed bias's interval (an equivalence test at
/// ±[`BIAS_TOLERANCE`]; docs/src/measured/unbiased-reuse.md, "The bias matrix").
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Verdict {
    /// The whole interval lies within ±0.5 %: no bias the matrix can resolve.
    Unbiased,
    /// The whole interval lies beyond +0.5 % or below −0.5 %.
    Biased,
    /// The interval straddles ±0.5 %: more seeds or frames needed.
    Undecided,
    /// One seed: no interval.
    OneSeed,
    /// The reference is black (no light reaches the camera): a ratio means nothing; the
    /// estimator must be black too.
    NoLight,
}

impl Verdict {
    pub fn of(signed_bias: &Interval) -> Verdict {
        if signed_bias.samples < 2 {
            Verdict::OneSeed
        } else if signed_bias.low() >= -BIAS_TOLERANCE && signed_bias.high() <= BIAS_TOLERANCE {
            Verdict::Unbiased
        } else if signed_bias.low() > BIAS_TOLERANCE || signed_bias.high() < -BIAS_TOLERANCE {
            Verdict::Biased
        } else {
            Verdict::Undecided
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Verdict::Unbiased => "consistent with 0",
            Verdict::Biased => "biased",
            Verdict::Undecided => "undecided",
            Verdict::OneSeed => "one seed",
            Verdict::NoLight => "no light",
        }
    }
}

/// An estimate with a jackknife 95 % half-width over seeds (`None` below three seeds).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Estimate {
    pub value: f64,
    pub half_width: Option<f64>,
}

impl Estimate {
    pub fn display(&self, digits: usize) -> String {
        match self.half_width {
            Some(h) => format!("{:.*e} ± {:.1e}", digits, self.value, h),
            None => format!("{:.*e}", digits, self.value),
        }
    }
}

/// The accumulated image's error over K seeds, split per pixel
/// (docs/src/measured/how-the-bench-measures.md, "Error bars"): with m_p,k the accumulated
/// luminance of pixel p in seed k, m̄_p their mean and s²_p their sample variance,
/// - `variance` = mean over pixels of s²_p: how far one seed's accumulated image strays;
/// - `squared_bias` = mean over pixels of (m̄_p − r_p)² − s²_p/K − σ²_ref: the part of the
///   error no number of frames removes, with the noise of the mean over seeds and of the
///   reference taken out (so it can come out slightly negative when there is none);
/// - `frame_variance` = mean over pixels of one frame's variance (within a seed, over time);
/// - `effective_frames` = frame_variance / variance: how many *independent* frames the
///   accumulated image is worth (= the frame count for an estimator without reuse).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PixelSpread {
    pub squared_bias: Estimate,
    pub variance: Estimate,
    pub frame_variance: f64,
    pub effective_frames: Option<f64>,
}

/// The per-pixel spread of `seeds` accumulated luminance images (each a `PixelMoments` of
/// one seed's frames) against the reference's luminance `reference` whose own per-pixel
/// noise has variance `reference_noise²`. `None` under two seeds.
pub fn pixel_spread(
    seeds: &[&PixelMoments],
    reference: &[f64],
    reference_noise: f64,
) -> Option<PixelSpread> {
    if seeds.len() < 2 {
        return None;
    }
    let means: Vec<Vec<f64>> = seeds.iter().map(|m| m.mean()).collect();
    let (bias2, var) = split(&means, reference, reference_noise);
    let jackknife = |stat: &dyn Fn(&[Vec<f64>]) -> f64, full: f64| -> Estimate {
        let k = means.len();
        if k < 3 {
            return Estimate {
                value: full,
                half_width: None,
            };
        }
        let leave_one_out: Vec<f64> = (0..k)
            .map(|i| {
                let rest: Vec<Vec<f64>> = means
                    .iter()
                    .enumerate()
                    .filter(|(j, _)| *j != i)
                    .map(|(_, m)| m.clone())
                    .collect();
                stat(&rest)
            })
            .collect();
        let mean = leave_one_out.iter().sum::<f64>() / k as f64;
        let se = ((k - 1) as f64 / k as f64
            * leave_one_out
                .iter()
                .map(|x| (x - mean).powi(2))
                .sum::<f64>())
        .sqrt();
        Estimate {
            value: full,
            half_width: Some(t95(k - 1) * se),
        }
    };
    let squared_bias = jackknife(&|m| split(m, reference, reference_noise).0, bias2);
    let variance = jackknife(&|m| split(m, reference, reference_noise).1, var);
    let frame_variance = seeds
        .iter()
        .map(|m| mean_finite(&m.frame_variance()))
        .sum::<f64>()
        / seeds.len() as f64;
    let effective_frames = (var > 0.0).then(|| frame_variance / var);
    Some(PixelSpread {
        squared_bias,
        variance,
        frame_variance,
        effective_frames,
    })
}

/// (squared bias, variance) of per-seed mean images against the reference (see
/// [`PixelSpread`]); pixels non-finite in any seed are left out.
fn split(means: &[Vec<f64>], reference: &[f64], reference_noise: f64) -> (f64, f64) {
    let k = means.len() as f64;
    let (mut bias2, mut var, mut n) = (0.0, 0.0, 0usize);
    for (p, r) in reference.iter().enumerate() {
        let values: Vec<f64> = means.iter().map(|m| m[p]).collect();
        if !r.is_finite() || values.iter().any(|v| !v.is_finite()) {
            continue;
        }
        let mean = values.iter().sum::<f64>() / k;
        let s2 = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1.0);
        bias2 += (mean - r).powi(2) - s2 / k;
        var += s2;
        n += 1;
    }
    if n == 0 {
        return (0.0, 0.0);
    }
    (
        bias2 / n as f64 - reference_noise * reference_noise,
        var / n as f64,
    )
}

fn mean_finite(values: &[f64]) -> f64 {
    let (sum, n) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// The reference's luminance per pixel, the form [`pixel_spread`] and
/// `PixelMoments::flagged_share` compare with.
pub fn luminance_of(image: &LinearImage) -> Vec<f64> {
    image
        .pixels
        .iter()
        .map(|p| crate::image::luminance([p[0], p[1], p[2]]) as f64)
        .collect()
}

/// Frames one seed would need for its accumulated mean luminance to lie within ±`tolerance`
/// (relative) of the truth at 95 %, from the spread of the per-seed luma ratios measured at
/// `frames` frames (the spread falls as 1/√frames once the frames outnumber the correlation
/// length): frames · (t·sd / tolerance)². `None` under two seeds.
pub fn frames_to_tolerance(ratios: &[f64], frames: usize, tolerance: f64) -> Option<f64> {
    let interval = Interval::of(ratios);
    if interval.samples < 2 {
        return None;
    }
    let n = interval.samples as f64;
    let sd = interval.half_width / t95(interval.samples - 1) * n.sqrt();
    Some(frames as f64 * (1.959_964 * sd / tolerance).powi(2))
}

#[cfg(test)]
mod tests;
