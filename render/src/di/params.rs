//! ReSTIR DI's GPU fields: its part of the pipeline parameters the shaders read.

use bytemuck::{Pod, Zeroable};

/// ReSTIR DI's fields of the `Params` uniform (`GpuParams::di`), filled from the
/// settings by `settings.rs` beside this file. The WGSL twin is `DiParams` in shaders/di/params.wgsl; a
/// test compares sizes and offsets. Its size is a multiple of 16 bytes, as a struct member
/// of a uniform must be.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuDiParams {
    pub light_candidates: u32,
    pub bsdf_candidates: u32,
    pub m_cap: f32,
    /// 0 disables the target-ratio test.
    pub target_ratio_clamp: f32,
    pub spatial_neighbours: u32,
    /// In pixels of this image (scaled from the 1080p value).
    pub spatial_radius: f32,
    /// Boiling filter threshold k (0 = off): a spatial survivor whose W·p̂ exceeds k × the
    /// neighbourhood mean is dropped.
    pub boiling_filter: f32,
    /// MCMC mutations per pixel after reuse (0 = off) and the local step in barycentric
    /// units (docs/src/mcmc-mutation.md).
    pub mutations: u32,
    pub mutation_step: f32,
    pub _pad: [u32; 3],
}
