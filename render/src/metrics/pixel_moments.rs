//! One seed's frames, per pixel: the running mean and variance of the luminance and the
//! batch means the `bias` view judges significance with (moments.wgsl, bias_view.wgsl),
//! kept on the CPU so that the bench can split error into bias and variance over seeds
//! (`seeds.rs`) and report the share of pixels the `bias` view would flag
//! (docs/src/mis-and-bias.md, "The bias view").

use crate::image::{LinearImage, luminance};
use crate::shader_constants::{BIAS_BATCH, BIAS_NEGLIGIBLE, BIAS_SIGNIFICANCE};

#[derive(Clone, Debug, PartialEq)]
pub struct PixelMoments {
    pub width: u32,
    pub height: u32,
    frames: u32,
    /// Per pixel: finite values seen, their sum and sum of squares.
    count: Vec<u32>,
    sum: Vec<f64>,
    sum_sq: Vec<f64>,
    /// Per pixel, the batch in progress: finite values and their sum.
    batch_count: Vec<u32>,
    batch_sum: Vec<f64>,
    /// Per pixel over completed batches: how many, and the sum of their means and squares.
    batches: Vec<u32>,
    batch_means: Vec<f64>,
    batch_means_sq: Vec<f64>,
    /// Non-finite pixel values seen (left out of every moment).
    pub non_finite: usize,
}

impl PixelMoments {
    pub fn new(width: u32, height: u32) -> PixelMoments {
        let n = (width * height) as usize;
        PixelMoments {
            width,
            height,
            frames: 0,
            count: vec![0; n],
            sum: vec![0.0; n],
            sum_sq: vec![0.0; n],
            batch_count: vec![0; n],
            batch_sum: vec![0.0; n],
            batches: vec![0; n],
            batch_means: vec![0.0; n],
            batch_means_sq: vec![0.0; n],
            non_finite: 0,
        }
    }

    /// Adds one frame (same size; a frame of another size is a caller's bug).
    pub fn push(&mut self, frame: &LinearImage) {
        assert_eq!(
            (frame.width, frame.height),
            (self.width, self.height),
            "PixelMoments: frame size"
        );
        self.frames += 1;
        let closes_batch = self.frames % BIAS_BATCH == 0;
        for (p, px) in frame.pixels.iter().enumerate() {
            let y = luminance([px[0], px[1], px[2]]) as f64;
            if y.is_finite() {
                self.count[p] += 1;
                self.sum[p] += y;
                self.sum_sq[p] += y * y;
                self.batch_count[p] += 1;
                self.batch_sum[p] += y;
            } else {
                self.non_finite += 1;
            }
            if closes_batch {
                if self.batch_count[p] > 0 {
                    let m = self.batch_sum[p] / self.batch_count[p] as f64;
                    self.batches[p] += 1;
                    self.batch_means[p] += m;
                    self.batch_means_sq[p] += m * m;
                }
                self.batch_count[p] = 0;
                self.batch_sum[p] = 0.0;
            }
        }
    }

    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// Per pixel, the accumulated (mean) luminance; NaN where no frame was finite.
    pub fn mean(&self) -> Vec<f64> {
        self.count
            .iter()
            .zip(&self.sum)
            .map(|(&n, &s)| if n > 0 { s / n as f64 } else { f64::NAN })
            .collect()
    }

    /// Per pixel, one frame's luminance variance over the frames (unbiased for independent
    /// frames; correlated frames make it a little low); NaN under two values.
    pub fn frame_variance(&self) -> Vec<f64> {
        (0..self.count.len())
            .map(|p| {
                let n = self.count[p] as f64;
                if n < 2.0 {
                    return f64::NAN;
                }
                let mean = self.sum[p] / n;
                ((self.sum_sq[p] / n - mean * mean) * n / (n - 1.0)).max(0.0)
            })
            .collect()
    }

    /// The share of pixels the `bias` view paints at this point (bias_view.wgsl's rule,
    /// same constants): |mean − reference| above BIAS_SIGNIFICANCE standard errors of the
    /// mean (from the spread of batch means, two batches at least) and the reference's own
    /// noise, and at least BIAS_NEGLIGIBLE of the reference. 0 before two batches.
    pub fn flagged_share(&self, reference: &[f64], reference_noise: f64) -> f64 {
        let mut flagged = 0usize;
        for p in 0..self.count.len() {
            let b = self.batches[p] as f64;
            if b < 2.0 || self.count[p] == 0 || !reference[p].is_finite() {
                continue;
            }
            let mean = self.sum[p] / self.count[p] as f64;
            let batch_mean = self.batch_means[p] / b;
            let batch_var =
                (self.batch_means_sq[p] / b - batch_mean * batch_mean).max(0.0) * b / (b - 1.0);
            let noise2 = batch_var / b + reference_noise * reference_noise;
            let d = mean - reference[p];
            if d.abs() > BIAS_SIGNIFICANCE as f64 * noise2.sqrt()
                && d.abs() >= BIAS_NEGLIGIBLE as f64 * reference[p]
            {
                flagged += 1;
            }
        }
        flagged as f64 / self.count.len().max(1) as f64
    }
}
