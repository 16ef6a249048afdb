//! The bench's temporal-stability figure (docs/src/measured/how-the-bench-measures.md, "How it
//! measures"): how much the image changes from one frame to the next, relative to how bright the
//! true image is. For consecutive frames t−1, t with references R (one per frame for a moving
//! camera or scene, else the same):
//!
//! ```text
//! flicker_t = Σ_p |e_t(p) − e_{t−1}(p)| / Σ_p luma(R_t(p)),   e = luma(frame) − luma(R)
//! ```
//!
//! For a still camera and scene e_t − e_{t−1} is the plain frame-to-frame luminance
//! change; with motion or a light event it leaves out the true change of the image (as
//! the stability RMSE does, docs/src/measured/how-the-bench-measures.md "How it measures"). It is
//! an L1 figure, unlike the stability RMSE, and dimensionless: 0.05 = the average pixel moves by
//! 5 % of the reference's mean luminance from one frame to the next. Pixels that are not finite in
//! either image are skipped (the metrics module's rule).

use crate::image::{LinearImage, luminance};

/// Accumulates `flicker_t` over a run of frames.
#[derive(Clone, Debug, Default)]
pub struct Flicker {
    previous_error: Option<Vec<f64>>,
    sum: f64,
    steps: usize,
}

impl Flicker {
    pub fn new() -> Flicker {
        Flicker::default()
    }

    /// Adds a frame and its reference; returns this step's figure (none for the first
    /// frame, or when the reference is black).
    pub fn push(
        &mut self,
        frame: &LinearImage,
        reference: &LinearImage,
    ) -> anyhow::Result<Option<f64>> {
        anyhow::ensure!(
            (frame.width, frame.height) == (reference.width, reference.height),
            "image sizes differ: {}×{} vs {}×{}",
            frame.width,
            frame.height,
            reference.width,
            reference.height
        );
        let luma = |p: &[f32; 4]| luminance([p[0], p[1], p[2]]) as f64;
        let error: Vec<f64> = frame
            .pixels
            .iter()
            .zip(&reference.pixels)
            .map(|(f, r)| luma(f) - luma(r))
            .collect();
        let brightness: f64 = reference
            .pixels
            .iter()
            .map(luma)
            .filter(|l| l.is_finite())
            .sum();
        let step = match &self.previous_error {
            Some(previous) if brightness > 0.0 => {
                let change: f64 = error
                    .iter()
                    .zip(previous)
                    .map(|(e, p)| (e - p).abs())
                    .filter(|d| d.is_finite())
                    .sum();
                Some(change / brightness)
            }
            _ => None,
        };
        if let Some(s) = step {
            self.sum += s;
            self.steps += 1;
        }
        self.previous_error = Some(error);
        Ok(step)
    }

    /// The mean over the frame pairs seen (`None` before two frames).
    pub fn mean(&self) -> Option<f64> {
        (self.steps > 0).then(|| self.sum / self.steps as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(w: u32, v: f32) -> LinearImage {
        LinearImage::from_fn(w, 2, |_, _| [v, v, v, 1.0])
    }

    #[test]
    fn flicker_is_the_mean_absolute_change_over_the_reference_brightness() {
        let reference = flat(4, 2.0);
        let mut f = Flicker::new();
        assert_eq!(f.push(&flat(4, 2.0), &reference).unwrap(), None);
        // Every pixel moves by 0.5 against a reference of 2: 0.25.
        let step = f.push(&flat(4, 2.5), &reference).unwrap().unwrap();
        assert!((step - 0.25).abs() < 1e-6, "{step}");
        // Half the pixels move by 1 more: (4 · 1) / (8 · 2).
        let half = LinearImage::from_fn(4, 2, |x, _| {
            let v = if x < 2 { 3.5 } else { 2.5 };
            [v, v, v, 1.0]
        });
        let step = f.push(&half, &reference).unwrap().unwrap();
        assert!((step - 0.25).abs() < 1e-6, "{step}");
        assert!((f.mean().unwrap() - 0.25).abs() < 1e-6);
        assert!(f.push(&flat(3, 1.0), &reference).is_err());
    }

    /// With a reference per frame the true change of the image is not flicker.
    #[test]
    fn a_change_the_reference_shares_is_not_flicker() {
        let mut f = Flicker::new();
        for v in [1.0, 2.0, 4.0] {
            f.push(&flat(4, v + 0.1), &flat(4, v)).unwrap();
        }
        assert!(f.mean().unwrap() < 1e-6);
        // A still image whose frames do not change does not flicker either, and a
        // non-finite pixel is skipped rather than poisoning the figure.
        let mut g = Flicker::new();
        let mut nan = flat(4, 1.0);
        nan.pixels[0] = [f32::NAN; 4];
        g.push(&flat(4, 1.0), &flat(4, 1.0)).unwrap();
        g.push(&nan, &flat(4, 1.0)).unwrap();
        assert_eq!(g.mean(), Some(0.0));
    }
}
