//! Light tiles (presample_lights.wgsl): power-sampled lights packed into tiles once per
//! frame, before the initial pass reads them.

use super::storage;

pub const SHADER: &str = "presample_lights.wgsl";
/// Invocations per workgroup of the 1-D dispatch.
pub const WORKGROUP_SIZE: u32 = 64;

/// 0 light tiles (written).
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![storage(0, false)]
}
