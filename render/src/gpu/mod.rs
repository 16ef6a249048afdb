//! Device set-up and small GPU helpers shared by the passes.

pub mod context;
pub mod readback;
pub mod timing;

pub use context::{Gpu, GpuError, NO_RAY_QUERY_ENV};

/// A single-sampled, single-mip 2-D texture (render targets, storage images, captures).
pub fn texture_2d(
    gpu: &Gpu,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}
