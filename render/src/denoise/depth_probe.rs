//! The à-trous depth chosen per scene by a held-out frame (docs/src/denoiser.md,
//! "Choosing the depth"): how many iterations a frame wants depends on the scene (one
//! where small shadows must survive, four where light is hard to sample), and no
//! reference is at hand while rendering. A later frame's raw illumination x is an
//! estimate of the same truth μ with noise of its own, independent of the history y the
//! filter reads (new random numbers), so for the filtered history F(y)
//!
//! E‖F(y) − x‖² = E‖F(y) − μ‖² + E‖x − μ‖²:
//!
//! the error against the held-out frame is the true error plus a constant that does not
//! depend on the depth, and the depth with the least held-out error is the depth with the
//! least true error. The denoiser's model (`model.rs`, pass for pass the WGSL) filters the
//! GPU's own history at every depth; no noise model is needed. Stein's unbiased risk
//! estimate, tried first, needs one: it took the moments' variance, which comes from the
//! same few samples as the history, and with fireflies it read 2–8× the true error and
//! chose too shallow a filter (measured on simulated histories in the tests).
//!
//! What it cannot see, named: noise the held-out frame shares with the history (temporal
//! reuse carries samples from frame to frame, so `restir` and the `restir-denoised`
//! preset hold out a frame that is not fully independent: the shallow depths look better
//! than they are), and the history's own lag behind a change.

use glam::Vec4;

use super::constants::MAX_DENOISE_ITERATIONS;
use super::model::{self, Frame, Params, Planted, luminance};
use crate::gpu_types::GpuDenoiseHistory;

/// The probe keeps the history once it has been valid for this many frames in a row (the
/// moments the filter's gate reads need a few frames, `DENOISE_MIN_HISTORY`) and compares
/// it with the next frame: with the bench's eight warm-up frames, the measured frames
/// filter at the chosen depth.
pub const DEPTH_PROBE_FRAMES: u32 = 6;

/// The probe filters at most this window at the image's centre (the crossover map's size:
/// there it sees every pixel). The model runs on the CPU, five à-trous passes: at 1080p
/// the whole frame would stall the viewer for seconds.
pub const DEPTH_PROBE_WINDOW: (u32, u32) = (384, 256);

/// The probe's answer: the error against the held-out frame at each depth (index 0: no
/// à-trous pass) and the depth it chose.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DepthChoice {
    pub iterations: u32,
    /// Mean squared difference of the filtered history's luminance and the held-out
    /// frame's, by depth 0..=MAX_DENOISE_ITERATIONS (radiance units²: the illumination's
    /// difference times the surface colour's luminance squared). The held-out frame's own
    /// noise is in every entry alike.
    pub held_out_error: Vec<f32>,
    /// Pixels compared (surfaces seen in both frames).
    pub pixels: u32,
    /// What the probe cost on the CPU: the readbacks and the model's passes (filled in by
    /// the renderer).
    pub probe_ms: f64,
}

/// The held-out error at every depth 0..=MAX_DENOISE_ITERATIONS for frame `f` and its
/// temporal history `h`, against `held_out`: each pixel's illumination luminance in a
/// later frame whose noise is independent of the history (`None` where that frame does
/// not see this pixel's surface); then the depth of least error among 1..=MAX. `None`
/// when no pixel can be compared.
pub fn choose_depth(
    f: &Frame,
    h: &[GpuDenoiseHistory],
    held_out: &[Option<f32>],
    p: &Params,
) -> Option<DepthChoice> {
    let compared: Vec<(usize, f32, f32)> = (0..f.pixels.len())
        .filter(|&i| f.pixels[i].valid)
        .filter_map(|i| {
            let x = held_out[i]?;
            // Error is counted in radiance: the illumination's times the surface colour's
            // luminance squared.
            let weight = luminance(f.pixels[i].demodulation()).powi(2);
            (x.is_finite() && weight.is_finite()).then_some((i, x, weight))
        })
        .collect();
    if compared.is_empty() {
        return None;
    }
    let error = |img: &[Vec4]| -> f32 {
        let sum: f64 = compared
            .iter()
            .map(|&(i, x, w)| {
                let e = luminance(img[i].truncate()) - x;
                (w * e * e) as f64
            })
            .sum();
        (sum / compared.len() as f64) as f32
    };
    let mut filtered = model::variance(f, h, p);
    let mut held_out_error = vec![error(&filtered)];
    for k in 0..MAX_DENOISE_ITERATIONS {
        filtered = model::atrous(f, &filtered, 1 << k, p, Planted::default());
        held_out_error.push(error(&filtered));
    }
    let iterations = (1..held_out_error.len())
        .filter(|&k| held_out_error[k].is_finite())
        .min_by(|&a, &b| held_out_error[a].total_cmp(&held_out_error[b]))?
        as u32;
    Some(DepthChoice {
        iterations,
        held_out_error,
        pixels: compared.len() as u32,
        probe_ms: 0.0,
    })
}

/// The centre window of at most `DEPTH_PROBE_WINDOW` of a `width × height` image:
/// (x0, y0, w, h).
pub fn probe_window(width: u32, height: u32) -> (u32, u32, u32, u32) {
    let (w, h) = (
        width.min(DEPTH_PROBE_WINDOW.0),
        height.min(DEPTH_PROBE_WINDOW.1),
    );
    ((width - w) / 2, (height - h) / 2, w, h)
}

/// Rows `y0..y0 + h`, columns `x0..x0 + w` of a row-major `width`-wide image.
pub fn crop<T: Copy>(data: &[T], width: u32, window: (u32, u32, u32, u32)) -> Vec<T> {
    let (x0, y0, w, h) = window;
    (y0..y0 + h)
        .flat_map(|y| {
            let row = (y * width + x0) as usize;
            data[row..row + w as usize].iter().copied()
        })
        .collect()
}
