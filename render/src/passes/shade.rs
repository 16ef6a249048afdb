//! Final shading (shade.wgsl): one shadow ray for the survivor plus emission; writes the
//! frame's radiance and adds it to the accumulation.

use super::storage;

pub const SHADER: &str = "shade.wgsl";

/// 0 surfaces, 1 reservoirs, 2 debug, 3 radiance, 4 accumulation.
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        storage(0, true),
        storage(1, true),
        storage(2, false),
        storage(3, false),
        storage(4, false),
    ]
}
