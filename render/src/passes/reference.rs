//! The reference renderer (reference.wgsl): ray-traced camera rays, light and BSDF
//! sampling with MIS; writes radiance and adds it to the accumulation. With jitter off it
//! shades the rasterised G-buffer's surfaces instead of tracing its own camera rays.

use super::{pass_info_entry, storage};

pub const SHADER: &str = "reference.wgsl";

/// 0 radiance, 1 accumulation, 2 pass info (which chunk of samples this dispatch takes),
/// 3 surfaces (the primary hits when jitter is off).
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        storage(0, false),
        storage(1, false),
        pass_info_entry(2),
        storage(3, true),
    ]
}
