//! What the denoiser makes of the settings: its fields of the `Params` uniform and its
//! `Params.flags` bit (its rows are in `rows.rs`, its fields' struct in `params.rs`).

use super::constants::PARAM_FLAG_DENOISE_GRADIENTS;
use super::model;
use super::params::GpuDenoiseParams;
use crate::settings::Settings;

pub fn gpu_params(s: &Settings) -> GpuDenoiseParams {
    GpuDenoiseParams {
        alpha: s.denoise_alpha,
        moments_alpha: s.denoise_moments_alpha,
        phi_luminance: s.denoise_phi_luminance,
        phi_normal: s.denoise_phi_normal,
        phi_depth: s.denoise_phi_depth,
        history_cap: s.denoise_history_cap as f32,
        _pad: [0; 2],
    }
}

/// The CPU model's knobs, for an image whose neighbouring pixels' rays are `pixel_angle`
/// apart (`model::Params::pixel_angle`).
pub fn model_params(s: &Settings, pixel_angle: f32) -> model::Params {
    model::Params {
        uniform: gpu_params(s),
        iterations: s.denoise_iterations,
        pixel_angle,
    }
}

/// The temporal pass shortens the history by the gradient when gradients are on.
pub fn flags(s: &Settings) -> u32 {
    if s.denoise_gradients_on() {
        PARAM_FLAG_DENOISE_GRADIENTS
    } else {
        0
    }
}
