//! The denoiser's GPU fields (docs/src/denoiser.md).

use bytemuck::{Pod, Zeroable};

/// The denoiser's fields of the `Params` uniform (`GpuParams::denoise`), filled from the
/// settings by `settings.rs` beside this file. The WGSL twin is `DenoiseParams` in shaders/denoise/params.wgsl; a
/// test compares sizes and offsets. Its size is a multiple of 16 bytes, as a struct member
/// of a uniform must be.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuDenoiseParams {
    /// Setting `denoise_alpha`; each field is its setting without the `denoise_` prefix.
    pub alpha: f32,
    pub moments_alpha: f32,
    pub phi_luminance: f32,
    pub phi_normal: f32,
    pub phi_depth: f32,
    pub history_cap: f32,
    pub _pad: [u32; 2],
}
