//! Initial RIS candidates (initial.wgsl): surfaces → reservoir (M = 1) + debug record.

use super::storage;

pub const SHADER: &str = "initial.wgsl";

/// 0 surfaces, 1 reservoirs out, 2 debug, 3 light tiles.
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        storage(0, true),
        storage(1, false),
        storage(2, false),
        storage(3, true),
    ]
}
