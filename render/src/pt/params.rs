//! ReSTIR PT's GPU fields (docs/src/restir-pt.md).

use bytemuck::{Pod, Zeroable};

/// ReSTIR PT's fields of the `Params` uniform (`GpuParams::pt`), filled from the
/// settings by `settings.rs` beside this file. The WGSL twin is `PtParams` in shaders/pt/params.wgsl; a
/// test compares sizes and offsets. Its size is a multiple of 16 bytes, as a struct member
/// of a uniform must be.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuPtParams {
    /// `PT_SHIFT_*` (setting `pt_shift`; each field is its setting without the `pt_` prefix).
    pub shift: u32,
    pub rough_threshold: f32,
    /// A fraction of `scene_scale` (the scene bounds' diagonal), not world units.
    pub min_distance: f32,
    pub spatial_neighbours: u32,
    /// In pixels of this image (scaled from the 1080p value).
    pub spatial_radius: f32,
    pub m_cap: f32,
    /// The biased Jacobian clamp [1/c, c] (0 = off).
    pub jacobian_clamp: f32,
    pub _pad: u32,
}
