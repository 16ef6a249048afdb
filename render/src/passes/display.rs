//! The display pass (display.wgsl): tonemapped image or a debug view into an RGBA8
//! storage texture that the viewer shows and PNG export reads.

use super::{storage, uniform};

pub const SHADER: &str = "display.wgsl";
pub const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// 0 image, 1 surfaces, 2 debug, 3 reservoirs, 4 reference image, 5 display uniform,
/// 6 output texture, 7 comparison image (the other side of a split screen).
pub fn entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    vec![
        storage(0, true),
        storage(1, true),
        storage(2, true),
        storage(3, true),
        storage(4, true),
        uniform(5, wgpu::ShaderStages::COMPUTE),
        wgpu::BindGroupLayoutEntry {
            binding: 6,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format: OUTPUT_FORMAT,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
            count: None,
        },
        storage(7, true),
    ]
}
