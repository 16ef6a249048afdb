//! Small detail, measured (docs/src/measured/how-the-bench-measures.md, "Shadow detail"): the
//! reference's strong local edges — shadow boundaries and silhouettes — and how much of each a
//! frame keeps. A frame's mean error hides a blurred stripe pattern (its pixels are a few among
//! many, and blur lowers their noise); these two figures do not:
//! - the luma RMSE within the edge pixels;
//! - **detail kept**: the frame's luminance step across each reference edge, projected on
//!   the reference's step, over the reference's steps: Σ s·(f_p − f_q) / Σ |r_p − r_q| with
//!   s = sign(r_p − r_q). 1 where the edges are as sharp as the reference's, below 1 where
//!   they are blurred (a denoiser's), and unmoved by zero-mean noise, which adds as much
//!   across an edge in one direction as in the other;
//! - FLIP within the edge pixels (`metrics::flip`): how visible the difference there is.

use super::flip::{self, FlipDisplay};
use crate::image::{LinearImage, luminance};

/// A neighbour pair is an edge when the reference's luminance changes across it by more
/// than this share of the brighter side: a shadow's stripe against the lit floor, not the
/// gentle falloff of distance and cosine (a few % from one pixel to the next).
pub const EDGE_CONTRAST: f32 = 0.25;

/// Below this luminance neither side of a pair counts as lit (no edge in the black).
const LIT: f32 = 1e-4;

/// A step must also stand this many standard deviations above the reference's own noise
/// (of a difference of two pixels, √2 × the per-pixel noise): a noisy reference's grain is
/// not detail.
pub const EDGE_NOISE_SIGMAS: f32 = 3.0;

/// The reference's edges: horizontal and vertical neighbour pairs (p, q) whose luminance
/// differs by more than [`EDGE_CONTRAST`] of the brighter and by more than
/// [`EDGE_NOISE_SIGMAS`] of the noise of a difference, each with the reference's step.
#[derive(Clone, Debug, PartialEq)]
pub struct Edges {
    pub width: u32,
    pub height: u32,
    pairs: Vec<(usize, usize, f32)>,
    /// The pixels that belong to any edge pair.
    pub pixels: Vec<bool>,
    /// The display FLIP judges frames on, the reference's.
    display: FlipDisplay,
}

impl Edges {
    /// `noise`: the reference's own per-pixel luma noise (RMSE), 0 if unknown.
    pub fn of(reference: &LinearImage, noise: f64) -> Edges {
        let floor = EDGE_NOISE_SIGMAS * std::f32::consts::SQRT_2 * noise as f32;
        let (w, h) = (reference.width as usize, reference.height as usize);
        let luma: Vec<f32> = reference
            .pixels
            .iter()
            .map(|p| luminance([p[0], p[1], p[2]]))
            .collect();
        let mut pairs = Vec::new();
        let mut pixels = vec![false; w * h];
        let mut consider = |p: usize, q: usize| {
            let (a, b) = (luma[p], luma[q]);
            if !(a.is_finite() && b.is_finite()) {
                return;
            }
            let brighter = a.max(b);
            if brighter > LIT && (a - b).abs() > (EDGE_CONTRAST * brighter).max(floor) {
                pairs.push((p, q, a - b));
                pixels[p] = true;
                pixels[q] = true;
            }
        };
        for y in 0..h {
            for x in 0..w {
                let p = y * w + x;
                if x + 1 < w {
                    consider(p, p + 1);
                }
                if y + 1 < h {
                    consider(p, p + w);
                }
            }
        }
        Edges {
            width: reference.width,
            height: reference.height,
            pairs,
            pixels,
            display: FlipDisplay::for_reference(reference),
        }
    }

    /// Share of the image's pixels on an edge.
    pub fn share(&self) -> f64 {
        let n = self.pixels.len().max(1);
        self.pixels.iter().filter(|&&e| e).count() as f64 / n as f64
    }

    /// The frame's luma RMSE within the edge pixels, the detail it keeps and FLIP there
    /// (above); None without edges or for images of another size. Non-finite pixels are
    /// left out of the RMSE and the steps (FLIP shows them black).
    pub fn figures(&self, frame: &LinearImage, reference: &LinearImage) -> Option<DetailFigures> {
        let size = (self.width, self.height);
        if self.pairs.is_empty()
            || (frame.width, frame.height) != size
            || (reference.width, reference.height) != size
        {
            return None;
        }
        let luma = |img: &LinearImage, p: usize| {
            let px = img.pixels[p];
            luminance([px[0], px[1], px[2]]) as f64
        };
        let (mut squared, mut count) = (0.0, 0usize);
        for (p, &on) in self.pixels.iter().enumerate() {
            let (f, r) = (luma(frame, p), luma(reference, p));
            if on && f.is_finite() && r.is_finite() {
                squared += (f - r) * (f - r);
                count += 1;
            }
        }
        let (mut kept, mut steps) = (0.0, 0.0);
        for &(p, q, step) in &self.pairs {
            let d = luma(frame, p) - luma(frame, q);
            if d.is_finite() {
                kept += (step as f64).signum() * d;
                steps += (step as f64).abs();
            }
        }
        if count == 0 || steps <= 0.0 {
            return None;
        }
        let map = flip::error_map(frame, reference, self.display)?;
        let on_edges = self.pixels.iter().zip(&map).filter(|(on, _)| **on);
        let flip = on_edges.clone().map(|(_, &e)| e as f64).sum::<f64>() / on_edges.count() as f64;
        Some(DetailFigures {
            luma_rmse: (squared / count as f64).sqrt(),
            kept: kept / steps,
            flip,
        })
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DetailFigures {
    pub luma_rmse: f64,
    pub kept: f64,
    /// Mean FLIP over the edge pixels (0 identical, 1 as different as can be).
    pub flip: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stripes two pixels wide: 1.0 and 0.2, along x.
    fn stripes(w: u32, h: u32) -> LinearImage {
        LinearImage::from_fn(w, h, |x, _| {
            let v = if (x / 2) % 2 == 0 { 1.0 } else { 0.2 };
            [v, v, v, 1.0]
        })
    }

    /// A 3-tap horizontal box blur: what a denoiser does to a stripe pattern.
    fn blurred(img: &LinearImage) -> LinearImage {
        LinearImage::from_fn(img.width, img.height, |x, y| {
            let at = |x: i64| {
                let x = x.clamp(0, img.width as i64 - 1) as u32;
                img.pixels[(y * img.width + x) as usize][0]
            };
            let v = (at(x as i64 - 1) + at(x as i64) + at(x as i64 + 1)) / 3.0;
            [v, v, v, 1.0]
        })
    }

    #[test]
    fn a_perfect_frame_keeps_all_detail_and_a_blurred_one_loses_some() {
        let r = stripes(16, 4);
        let edges = Edges::of(&r, 0.0);
        // Every column boundary between stripes is an edge: 7 per row.
        assert_eq!(edges.pairs.len(), 7 * 4);
        let same = edges.figures(&r, &r).unwrap();
        assert!((same.kept - 1.0).abs() < 1e-6, "{}", same.kept);
        assert_eq!(same.luma_rmse, 0.0);
        assert_eq!(same.flip, 0.0);
        let blur = edges.figures(&blurred(&r), &r).unwrap();
        assert!(blur.kept < 0.5 && blur.kept > 0.0, "{}", blur.kept);
        assert!(blur.luma_rmse > 0.1);
        assert!(blur.flip > 0.1, "FLIP on the blurred edges: {}", blur.flip);
    }

    #[test]
    fn zero_mean_noise_leaves_the_detail_kept_at_one() {
        let r = stripes(64, 64);
        let edges = Edges::of(&r, 0.0);
        // Deterministic ±0.3 noise, alternating in a pattern uncorrelated with the stripes.
        let noisy = LinearImage::from_fn(64, 64, |x, y| {
            let base = r.pixels[(y * 64 + x) as usize][0];
            let h = (x.wrapping_mul(2_654_435_761) ^ y.wrapping_mul(40_503)) >> 7;
            let v = base + if h % 2 == 0 { 0.3 } else { -0.3 };
            [v, v, v, 1.0]
        });
        let f = edges.figures(&noisy, &r).unwrap();
        assert!((f.kept - 1.0).abs() < 0.1, "{}", f.kept);
        assert!(f.luma_rmse > 0.25, "the noise shows in the RMSE");
    }

    #[test]
    fn a_flat_or_black_reference_has_no_edges() {
        let flat = LinearImage::from_fn(8, 8, |_, _| [0.5, 0.5, 0.5, 1.0]);
        assert!(Edges::of(&flat, 0.0).figures(&flat, &flat).is_none());
        let r = stripes(16, 4);
        assert!(
            Edges::of(&r, 0.0).figures(&flat, &r).is_none(),
            "another size"
        );
        let black = LinearImage::from_fn(8, 8, |x, _| {
            let v = if x % 2 == 0 { 0.0 } else { 1e-6 };
            [v, v, v, 1.0]
        });
        assert_eq!(Edges::of(&black, 0.0).share(), 0.0);
    }

    #[test]
    fn steps_within_the_references_noise_are_not_edges() {
        let r = stripes(16, 4);
        // Steps of 0.8: edges against noise 0.1 (floor 0.42), not against noise 0.3 (1.27).
        assert_eq!(Edges::of(&r, 0.1).pairs.len(), 7 * 4);
        assert!(Edges::of(&r, 0.3).pairs.is_empty());
    }
}
