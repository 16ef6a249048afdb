//! Temporal reuse (temporal.wgsl): reprojection, validation with a rejection mask,
//! target re-evaluation and the merge with the previous frame's reservoir.

use super::storage;

pub const SHADER: &str = "temporal.wgsl";

/// 0 surfaces, 1 previous surfaces, 2 reservoirs in, 3 previous reservoirs,
/// 4 reservoirs out, 5 debug.
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        storage(0, true),
        storage(1, true),
        storage(2, true),
        storage(3, true),
        storage(4, false),
        storage(5, false),
    ]
}
