//! FLIP, the perceptual difference of two images as a viewer flipping between them sees it
//! (Andersson et al. 2020), through NVIDIA's own implementation (the `nv-flip` crate, which
//! wgpu's tests use) rather than a port: per pixel, 0 (no visible difference) to 1. It sees
//! what a mean error hides on small shadow detail — a stripe blurred into grey is a large
//! FLIP error at its edges, while zero-mean noise of the same RMSE reads smaller where it is
//! fine-grained (docs/src/measured/how-the-bench-measures.md, "Shadow detail").
//!
//! FLIP compares what a display shows (LDR, sRGB). Both images go through one display made
//! from the reference: an exposure that puts the reference's [`WHITE_PERCENTILE`] luminance
//! at white, then clamped and sRGB-encoded. The frame is judged on the display the reference
//! would be shown on, never on one fitted to the frame itself.

use crate::image::{LinearImage, luminance};

/// The reference's luminance at this quantile is the display's white: its brightest 1 %
/// (light fixtures, highlights) clips, as on a screen, and the shadows keep their steps.
pub const WHITE_PERCENTILE: f64 = 0.99;

/// FLIP's observer: 67 pixels per degree, a 31.6" 4K monitor seen from 70 cm (the
/// implementation's default). The figures are comparisons between estimators at one size,
/// not an absolute visibility claim.
pub const PIXELS_PER_DEGREE: f32 = nv_flip::DEFAULT_PIXELS_PER_DEGREE;

/// The display both images are judged on: linear radiance × `exposure`, clamped to [0, 1],
/// sRGB-encoded to 8 bits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlipDisplay {
    pub exposure: f32,
}

impl FlipDisplay {
    /// White at the reference's [`WHITE_PERCENTILE`] luminance (finite pixels); a black
    /// reference gets exposure 1.
    pub fn for_reference(reference: &LinearImage) -> FlipDisplay {
        let mut luma: Vec<f32> = reference
            .pixels
            .iter()
            .map(|p| luminance([p[0], p[1], p[2]]))
            .filter(|l| l.is_finite() && *l > 0.0)
            .collect();
        if luma.is_empty() {
            return FlipDisplay { exposure: 1.0 };
        }
        let at = ((luma.len() - 1) as f64 * WHITE_PERCENTILE).round() as usize;
        let (_, white, _) = luma.select_nth_unstable_by(at, f32::total_cmp);
        FlipDisplay {
            exposure: 1.0 / *white,
        }
    }

    /// The image as the display shows it, RGB 8 bits per channel; a non-finite channel
    /// shows black (it is counted elsewhere: `metrics::non_finite_pixels`).
    pub fn encode(&self, image: &LinearImage) -> Vec<u8> {
        image
            .pixels
            .iter()
            .flat_map(|p| [p[0], p[1], p[2]])
            .map(|c| {
                let v = if c.is_finite() {
                    (c * self.exposure).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (srgb_encode(v) * 255.0).round() as u8
            })
            .collect()
    }
}

fn srgb_encode(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// Per pixel, FLIP's error of `frame` against `reference`, both shown on `display`; None
/// for images of different sizes or an empty one.
pub fn error_map(
    frame: &LinearImage,
    reference: &LinearImage,
    display: FlipDisplay,
) -> Option<Vec<f32>> {
    let (w, h) = (reference.width, reference.height);
    if (frame.width, frame.height) != (w, h) || w == 0 || h == 0 {
        return None;
    }
    let shown = |img| nv_flip::FlipImageRgb8::with_data(w, h, &display.encode(img));
    let map = nv_flip::flip(shown(reference), shown(frame), PIXELS_PER_DEGREE);
    Some(map.to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stripes two pixels wide, 1.0 and 0.1, blurred by a horizontal box of `taps` pixels
    /// (1: sharp).
    fn stripes(taps: i64) -> LinearImage {
        let sharp = |x: i64| if (x.rem_euclid(4)) < 2 { 1.0 } else { 0.1 };
        LinearImage::from_fn(64, 32, |x, _| {
            let r = taps / 2;
            let v = (-r..=r).map(|d| sharp(x as i64 + d)).sum::<f32>() / (2 * r + 1) as f32;
            [v, v, v, 1.0]
        })
    }

    fn mean(v: &[f32]) -> f64 {
        v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64
    }

    /// The same image has no error, a blurred one has, and more blur more; a frame shown
    /// twice as bright is an error too (the display is the reference's, not the frame's).
    /// Planted: a display fitted to each image separately hides the brightness change.
    #[test]
    fn flip_sees_blur_and_brightness_on_the_reference_display() {
        let reference = stripes(1);
        let display = FlipDisplay::for_reference(&reference);
        assert!(
            (display.exposure - 1.0).abs() < 1e-6,
            "white is the stripes' 1.0"
        );
        let same = mean(&error_map(&reference, &reference, display).unwrap());
        assert_eq!(same, 0.0);
        let (light, heavy) = (
            mean(&error_map(&stripes(3), &reference, display).unwrap()),
            mean(&error_map(&stripes(5), &reference, display).unwrap()),
        );
        assert!(
            light > 0.05 && heavy > light,
            "blur 3: {light}, blur 5: {heavy}"
        );
        let dim = LinearImage::from_fn(64, 32, |x, y| {
            let p = reference.get(x, y);
            [p[0] * 0.5, p[1] * 0.5, p[2] * 0.5, 1.0]
        });
        let seen = mean(&error_map(&dim, &reference, display).unwrap());
        assert!(seen > 0.05, "half as bright: {seen}");
        let own = FlipDisplay::for_reference(&dim);
        let hidden = nv_flip::flip(
            nv_flip::FlipImageRgb8::with_data(64, 32, &display.encode(&reference)),
            nv_flip::FlipImageRgb8::with_data(64, 32, &own.encode(&dim)),
            PIXELS_PER_DEGREE,
        );
        assert!(
            mean(&hidden.to_vec()) < 0.01 * seen,
            "a display per image hides it"
        );
    }

    /// Bad input stays finite: NaN and infinite pixels show black, a black reference gets
    /// a unit exposure, and images of different sizes give no map.
    #[test]
    fn bad_pixels_and_sizes_give_finite_maps_or_none() {
        let black = LinearImage::from_fn(16, 16, |_, _| [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(FlipDisplay::for_reference(&black).exposure, 1.0);
        let broken = LinearImage::from_fn(16, 16, |x, _| match x % 3 {
            0 => [f32::NAN; 4],
            1 => [f32::INFINITY, 0.0, -1.0, 1.0],
            _ => [0.5, 0.5, 0.5, 1.0],
        });
        let map = error_map(&broken, &black, FlipDisplay::for_reference(&black)).unwrap();
        assert!(map.iter().all(|e| e.is_finite() && (0.0..=1.0).contains(e)));
        assert!(error_map(&stripes(1), &black, FlipDisplay { exposure: 1.0 }).is_none());
    }
}
