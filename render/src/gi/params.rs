//! ReSTIR GI's GPU fields; its switches are the `PARAM_FLAG_GI_*` bits of `GpuParams::flags`.

use bytemuck::{Pod, Zeroable};

/// ReSTIR GI's fields of the `Params` uniform (`GpuParams::gi`), filled from the
/// settings by `settings.rs` beside this file. The WGSL twin is `GiParams` in shaders/gi/params.wgsl; a
/// test compares sizes and offsets. Its size is a multiple of 16 bytes, as a struct member
/// of a uniform must be.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuGiParams {
    /// Setting `gi_m_cap`; each field is its setting without the `gi_` prefix.
    pub m_cap: f32,
    pub spatial_neighbours: u32,
    /// In pixels of this image (scaled from the 1080p value).
    pub spatial_radius: f32,
    /// The Jacobian window [1/max, max], max ≥ 1.
    pub jacobian_max: f32,
    /// Light candidates at GI's secondary vertex (resolved: never 0 unless DI's is).
    pub light_candidates: u32,
    pub _pad: [u32; 3],
}
