//! The denoiser's passes, an SVGF-class filter after shading (docs/src/denoiser.md):
//! temporal accumulation → variance estimate → à-trous × N → remodulation, and its debug
//! views. Each module owns its shader (shaders/denoise/) and the declaration of its
//! bindings; the buffers the family shares are declared here. `denoise::model` is the same
//! computation in plain Rust.

use crate::gpu_types::GpuDenoiseHistory;
use crate::passes::resources::{Chain, PixelBuffer};

pub mod atrous;
pub mod gradient;
pub mod modulate;
pub mod temporal;
pub mod variance;
pub mod view;

/// The temporal history: accumulated demodulated illumination, its length and luminance
/// moments. Last frame's final buffer is this frame's history.
pub const HISTORY: Chain = Chain {
    name: "denoise history",
    stride: std::mem::size_of::<GpuDenoiseHistory>(),
};

/// Illumination and variance (w) handed from the variance estimate through each à-trous
/// pass to the remodulation.
pub const FILTERED: Chain = Chain {
    name: "denoise filtered",
    stride: 16,
};

/// The temporal gradient: (λ, Σ shading last frame, Σ shading now, 0) per pixel, λ the
/// share of the neighbourhood's shading that changed.
pub const GRADIENT: PixelBuffer = PixelBuffer::full("denoise gradient", 16);

/// The frame's radiance before denoising (the `denoise-input` view; the remodulation
/// copies it here before it writes the denoised radiance in its place).
pub const INPUT: PixelBuffer = PixelBuffer::full("denoise input", 16);
