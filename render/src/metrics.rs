//! Image metrics against a converged reference (docs/src/measured/how-the-bench-measures.md, "How
//! it measures"): per-frame accuracy, frame-to-frame stability, accumulated accuracy and energy
//! bias (luma ratio), plus an error heatmap.
//!
//! Non-finite pixels (NaN or ±∞ in any colour channel of either image) are skipped by every
//! metric rather than turning it into NaN; [`non_finite_pixels`] and
//! [`SequenceReport::non_finite_pixels`] report how many there were, so a skipped pixel is
//! never silent. Alpha is ignored throughout.

pub mod detail;
pub mod flip;
pub mod motion_masks;
pub mod pixel_moments;
pub mod seeds;

use crate::image::{LinearImage, luminance};

#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum MetricsError {
    #[error("image sizes differ: {0}×{1} vs {2}×{3}")]
    SizeMismatch(u32, u32, u32, u32),
}

type Result<T> = std::result::Result<T, MetricsError>;

/// Added to r² in [`rel_mse`]: keeps black reference pixels from dividing by zero while
/// leaving pixels brighter than ~0.1 measured relative to themselves.
pub const REL_MSE_EPSILON: f64 = 1e-2;

/// Root mean square of the luminance difference.
pub fn luma_rmse(a: &LinearImage, b: &LinearImage) -> Result<f64> {
    Ok(mean_over_pixels(a, b, |x, y| (luma(x) - luma(y)).powi(2))?.sqrt())
}

/// Side of the tiles [`low_frequency_rmse`] averages the error over.
pub const LOW_FREQUENCY_TILE: u32 = 8;

/// The error's energy at low spatial frequencies: the luminance error (a − b) averaged over
/// 8 × 8 tiles, then its root mean square over the tiles (partial tiles at the borders and
/// non-finite pixels left out). Per-frame RMSE cannot tell blotches from grain (Sawhney et
/// al. 2024: decorrelating ReSTIR leaves MSE unchanged while the blotches go); this can.
/// Independent per-pixel errors of RMS σ leave σ / 8 (a tile averages 64 of them); error
/// that is constant over a tile (a blotch, a bias) keeps its full size. Hence
/// [`error_correlation`].
pub fn low_frequency_rmse(a: &LinearImage, b: &LinearImage) -> Result<f64> {
    check_sizes(a, b)?;
    let t = LOW_FREQUENCY_TILE;
    let (mut sum, mut tiles) = (0.0f64, 0usize);
    for ty in 0..a.height / t {
        for tx in 0..a.width / t {
            let (mut e, mut n) = (0.0f64, 0usize);
            for y in ty * t..(ty + 1) * t {
                for x in tx * t..(tx + 1) * t {
                    let i = (y * a.width + x) as usize;
                    let (p, q) = (&a.pixels[i], &b.pixels[i]);
                    if finite(p) && finite(q) {
                        e += luma(p) - luma(q);
                        n += 1;
                    }
                }
            }
            if n > 0 {
                sum += (e / n as f64).powi(2);
                tiles += 1;
            }
        }
    }
    Ok(if tiles == 0 {
        0.0
    } else {
        (sum / tiles as f64).sqrt()
    })
}

/// How correlated an error is at the scale of a tile: 8 × low-frequency RMSE / RMSE, 1 for
/// independent per-pixel errors, 8 for error constant over each tile (0 without error).
pub fn error_correlation(a: &LinearImage, b: &LinearImage) -> Result<f64> {
    let rmse = luma_rmse(a, b)?;
    Ok(if rmse > 0.0 {
        LOW_FREQUENCY_TILE as f64 * low_frequency_rmse(a, b)? / rmse
    } else {
        0.0
    })
}

/// Root mean square over all pixels and the three colour channels.
pub fn rgb_rmse(a: &LinearImage, b: &LinearImage) -> Result<f64> {
    Ok(mean_over_pixels(a, b, |x, y| {
        channels(x, y).map(|(p, q)| (p - q).powi(2)).sum::<f64>() / 3.0
    })?
    .sqrt())
}

/// mean luminance(avg) / mean luminance(reference): 1 means no energy bias. 1 when both are
/// black, +∞ when only the reference is.
pub fn luma_ratio(avg: &LinearImage, reference: &LinearImage) -> Result<f64> {
    let num = mean_over_pixels(avg, reference, |x, _| luma(x))?;
    let den = mean_over_pixels(avg, reference, |_, y| luma(y))?;
    Ok(if den == 0.0 && num == 0.0 {
        1.0
    } else {
        num / den
    })
}

/// (mean luminance(frame) − mean luminance(reference)) / mean luminance(reference): the
/// signed energy bias of one frame (or of an average), 0 = none, negative = too dark. 0 when
/// both are black.
pub fn signed_bias(frame: &LinearImage, reference: &LinearImage) -> Result<f64> {
    Ok(luma_ratio(frame, reference)? - 1.0)
}

/// A reference pixel counts as lit above this fraction of the reference's mean luminance.
pub const LIT_FLOOR: f64 = 0.01;
/// A frame pixel is black where its luminance is below this fraction of the reference's.
pub const BLACK_FRACTION: f64 = 0.05;

/// The fraction of all pixels that are black in `frame` (luminance below
/// [`BLACK_FRACTION`] of the reference's) where the reference is lit (above [`LIT_FLOOR`] of
/// its mean): the speckles of a pixel that picked a sample it cannot see
/// (docs/src/mis-and-bias.md, "Visibility in every term").
pub fn black_pixel_fraction(frame: &LinearImage, reference: &LinearImage) -> Result<f64> {
    let lit = LIT_FLOOR * mean_over_pixels(frame, reference, |_, r| luma(r))?;
    mean_over_pixels(frame, reference, |x, r| {
        let truth = luma(r);
        (truth > lit && luma(x) < BLACK_FRACTION * truth) as u8 as f64
    })
}

/// Relative MSE: mean over pixels and channels of (a − r)² / (r² + [`REL_MSE_EPSILON`]).
pub fn rel_mse(a: &LinearImage, reference: &LinearImage) -> Result<f64> {
    mean_over_pixels(a, reference, |x, r| {
        channels(x, r)
            .map(|(p, q)| (p - q).powi(2) / (q * q + REL_MSE_EPSILON))
            .sum::<f64>()
            / 3.0
    })
}

/// Pixels skipped by the metrics of `a` against `b`: non-finite in either image.
pub fn non_finite_pixels(a: &LinearImage, b: &LinearImage) -> Result<usize> {
    check_sizes(a, b)?;
    Ok(a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(x, y)| !finite(x) || !finite(y))
        .count())
}

/// |Δ luminance| per pixel through the inferno colour map, normalised by
/// [`heatmap_scale`] (the 99th percentile, so a few fireflies do not flatten the rest).
pub fn error_heatmap(a: &LinearImage, reference: &LinearImage) -> Result<LinearImage> {
    error_heatmap_scaled(a, reference, heatmap_scale(a, reference)?)
}

/// The 99th percentile of the finite |Δ luminance| values (0 for identical images).
pub fn heatmap_scale(a: &LinearImage, reference: &LinearImage) -> Result<f64> {
    let mut diffs: Vec<f64> = abs_luma_diffs(a, reference)?
        .into_iter()
        .flatten()
        .collect();
    if diffs.is_empty() {
        return Ok(0.0);
    }
    let k = (diffs.len() * 99).div_ceil(100) - 1;
    Ok(*diffs.select_nth_unstable_by(k, f64::total_cmp).1)
}

/// Heatmap with an explicit scale (|Δ| = scale maps to the top of the colour map), so that
/// several configurations can share one. Pixels are display-ready sRGB-encoded values in
/// [0, 1] with alpha 1: write them out as 8-bit without another transfer function.
/// Non-finite pixels are cyan, a colour inferno never uses.
pub fn error_heatmap_scaled(
    a: &LinearImage,
    reference: &LinearImage,
    scale: f64,
) -> Result<LinearImage> {
    let pixels = abs_luma_diffs(a, reference)?
        .into_iter()
        .map(|d| match d {
            None => [0.0, 1.0, 1.0, 1.0],
            Some(d) => {
                let t = if scale > 0.0 {
                    (d / scale).min(1.0)
                } else {
                    0.0
                };
                let [r, g, b] = inferno(t as f32);
                [r, g, b, 1.0]
            }
        })
        .collect();
    Ok(LinearImage {
        width: a.width,
        height: a.height,
        pixels,
    })
}

/// Feeds frames one at a time against a reference and reports the numbers
/// docs/src/measured/how-the-bench-measures.md defines ("How it measures").
pub struct SequenceMetrics {
    reference: LinearImage,
    previous: Option<LinearImage>,
    /// Per pixel: sum of the finite frames' RGB and how many there were.
    sum: Vec<[f64; 3]>,
    count: Vec<u32>,
    per_frame_luma_rmse: Vec<f64>,
    per_frame_stability: Vec<f64>,
    per_frame_signed_bias: Vec<f64>,
    per_frame_black_fraction: Vec<f64>,
    non_finite_pixels: usize,
}

#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct SequenceReport {
    pub frames: usize,
    /// Per-frame accuracy: luma RMSE vs the reference, averaged over frames.
    pub mean_luma_rmse: f64,
    /// Stability: luma RMSE between consecutive frames, averaged (0 with under two frames).
    pub mean_stability_rmse: f64,
    /// Accuracy of the running average (a pixel's average uses its finite frames only).
    pub accumulated_rgb_rmse: f64,
    /// Energy bias of the running average; 1.0 = none.
    pub accumulated_luma_ratio: f64,
    /// Signed bias: per frame (mean luminance − the reference's) / the reference's, averaged
    /// over frames (0 = none; the same as luma ratio − 1 of the average for a still camera,
    /// and the honest figure for a moving one, each frame against its own reference).
    pub mean_signed_bias: f64,
    /// Per frame, the fraction of pixels black where the reference is lit
    /// ([`black_pixel_fraction`]), averaged over frames.
    pub mean_black_pixel_fraction: f64,
    pub per_frame_luma_rmse: Vec<f64>,
    /// `frames − 1` entries: frame i+1 against frame i.
    pub per_frame_stability_rmse: Vec<f64>,
    /// Non-finite pixels summed over the frames fed (each skipped by the metrics).
    pub non_finite_pixels: usize,
}

impl SequenceMetrics {
    pub fn new(reference: LinearImage) -> Self {
        let n = reference.pixels.len();
        Self {
            reference,
            previous: None,
            sum: vec![[0.0; 3]; n],
            count: vec![0; n],
            per_frame_luma_rmse: Vec::new(),
            per_frame_stability: Vec::new(),
            per_frame_signed_bias: Vec::new(),
            per_frame_black_fraction: Vec::new(),
            non_finite_pixels: 0,
        }
    }

    pub fn push(&mut self, frame: &LinearImage) -> Result<()> {
        self.per_frame_luma_rmse
            .push(luma_rmse(frame, &self.reference)?);
        self.per_frame_signed_bias
            .push(signed_bias(frame, &self.reference)?);
        self.per_frame_black_fraction
            .push(black_pixel_fraction(frame, &self.reference)?);
        if let Some(previous) = &self.previous {
            self.per_frame_stability.push(luma_rmse(frame, previous)?);
        }
        for ((sum, count), p) in self.sum.iter_mut().zip(&mut self.count).zip(&frame.pixels) {
            if finite(p) {
                *sum = std::array::from_fn(|c| sum[c] + p[c] as f64);
                *count += 1;
            } else {
                self.non_finite_pixels += 1;
            }
        }
        self.previous = Some(frame.clone());
        Ok(())
    }

    pub fn frames(&self) -> usize {
        self.per_frame_luma_rmse.len()
    }

    /// The running average; NaN where a pixel never had a finite value (metrics skip it).
    pub fn accumulated(&self) -> LinearImage {
        let pixels = self
            .sum
            .iter()
            .zip(&self.count)
            .map(|(s, &n)| {
                let avg = |c: usize| {
                    if n > 0 {
                        (s[c] / n as f64) as f32
                    } else {
                        f32::NAN
                    }
                };
                [avg(0), avg(1), avg(2), 1.0]
            })
            .collect();
        LinearImage {
            width: self.reference.width,
            height: self.reference.height,
            pixels,
        }
    }

    pub fn report(&self) -> SequenceReport {
        let accumulated = self.accumulated();
        // Sizes were checked when the frames came in, so these comparisons cannot fail.
        let same_size = "accumulated image has the reference's size";
        SequenceReport {
            frames: self.frames(),
            mean_luma_rmse: mean(&self.per_frame_luma_rmse),
            mean_stability_rmse: mean(&self.per_frame_stability),
            accumulated_rgb_rmse: rgb_rmse(&accumulated, &self.reference).expect(same_size),
            accumulated_luma_ratio: luma_ratio(&accumulated, &self.reference).expect(same_size),
            mean_signed_bias: mean(&self.per_frame_signed_bias),
            mean_black_pixel_fraction: mean(&self.per_frame_black_fraction),
            per_frame_luma_rmse: self.per_frame_luma_rmse.clone(),
            per_frame_stability_rmse: self.per_frame_stability.clone(),
            non_finite_pixels: self.non_finite_pixels,
        }
    }
}

fn mean(values: &[f64]) -> f64 {
    if values.is_empty() {
        0.0
    } else {
        values.iter().sum::<f64>() / values.len() as f64
    }
}

fn check_sizes(a: &LinearImage, b: &LinearImage) -> Result<()> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(MetricsError::SizeMismatch(
            a.width, a.height, b.width, b.height,
        ));
    }
    Ok(())
}

fn finite(p: &[f32; 4]) -> bool {
    p[..3].iter().all(|c| c.is_finite())
}

fn luma(p: &[f32; 4]) -> f64 {
    luminance([p[0], p[1], p[2]]) as f64
}

fn channels<'a>(a: &'a [f32; 4], b: &'a [f32; 4]) -> impl Iterator<Item = (f64, f64)> + 'a {
    (0..3).map(|c| (a[c] as f64, b[c] as f64))
}

/// Mean of `f` over the pixels finite in both images, in f64; 0 when there are none.
fn mean_over_pixels(
    a: &LinearImage,
    b: &LinearImage,
    f: impl Fn(&[f32; 4], &[f32; 4]) -> f64,
) -> Result<f64> {
    check_sizes(a, b)?;
    let (sum, n) = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(x, y)| finite(x) && finite(y))
        .fold((0.0, 0usize), |(sum, n), (x, y)| (sum + f(x, y), n + 1));
    Ok(if n == 0 { 0.0 } else { sum / n as f64 })
}

/// |Δ luminance| per pixel; `None` where either pixel is non-finite.
fn abs_luma_diffs(a: &LinearImage, b: &LinearImage) -> Result<Vec<Option<f64>>> {
    check_sizes(a, b)?;
    Ok(a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(x, y)| (finite(x) && finite(y)).then(|| (luma(x) - luma(y)).abs()))
        .collect())
}

/// Matplotlib's inferno (perceptually uniform, readable in greyscale), sampled at 13 evenly
/// spaced stops and interpolated linearly; sRGB-encoded.
fn inferno(t: f32) -> [f32; 3] {
    const STOPS: [u32; 13] = [
        0x000004, 0x110a30, 0x320a5e, 0x57106e, 0x781c6d, 0x9a2865, 0xbc3754, 0xd84c3e, 0xed6925,
        0xf98e09, 0xfbb61a, 0xf4df53, 0xfcffa4,
    ];
    let rgb = |hex: u32| [16, 8, 0].map(|shift| ((hex >> shift) & 0xff) as f32 / 255.0);
    let x = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f32;
    let i = (x as usize).min(STOPS.len() - 2);
    let (lo, hi, f) = (rgb(STOPS[i]), rgb(STOPS[i + 1]), x - i as f32);
    std::array::from_fn(|c| lo[c] * (1.0 - f) + hi[c] * f)
}

#[cfg(test)]
mod tests;
