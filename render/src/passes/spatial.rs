//! Spatial reuse (spatial.wgsl): one dispatch per pass, reading one reservoir buffer and
//! writing another.

use super::{pass_info_entry, storage};

pub const SHADER: &str = "spatial.wgsl";

/// 0 surfaces, 1 reservoirs in, 2 reservoirs out, 3 debug, 4 pass info.
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        storage(0, true),
        storage(1, true),
        storage(2, false),
        storage(3, false),
        pass_info_entry(4),
    ]
}
