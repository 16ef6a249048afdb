//! Everything whose size follows the output size: the visibility and depth targets, two
//! surface buffers (current / previous), three reservoir buffers that the stages hand
//! around (notes §2.6: ping-pong), the debug records, radiance, accumulation and the
//! display texture. Re-created on resize; history starts invalid.

use crate::gpu::Gpu;
use crate::gpu_types::{GpuPixelDebug, GpuReservoir, GpuSurface};
use crate::passes::{display, gbuffer};

pub struct FrameTargets {
    pub width: u32,
    pub height: u32,
    pub visibility: wgpu::TextureView,
    pub depth: wgpu::TextureView,
    pub surfaces: [wgpu::Buffer; 2],
    pub reservoirs: [wgpu::Buffer; 3],
    pub debug: wgpu::Buffer,
    pub radiance: wgpu::Buffer,
    pub accumulation: wgpu::Buffer,
    /// A reference image for the error view (zeros until one is uploaded).
    pub reference: wgpu::Buffer,
    pub display: wgpu::Texture,
    pub display_view: wgpu::TextureView,
    /// The same texture seen as sRGB, for samplers (the viewer).
    pub display_srgb_view: wgpu::TextureView,
}

fn pixel_buffer(gpu: &Gpu, label: &str, pixels: u64, stride: usize) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: (pixels * stride as u64).max(16),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn target(
    gpu: &Gpu,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
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
        view_formats: &[],
    })
}

impl FrameTargets {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> FrameTargets {
        let pixels = width as u64 * height as u64;
        let surface = std::mem::size_of::<GpuSurface>();
        let reservoir = std::mem::size_of::<GpuReservoir>();
        let color = std::mem::size_of::<[f32; 4]>();
        let visibility = target(
            gpu,
            "visibility",
            width,
            height,
            gbuffer::VISIBILITY_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let depth = target(
            gpu,
            "depth",
            width,
            height,
            gbuffer::DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let display = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("display"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: display::OUTPUT_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[wgpu::TextureFormat::Rgba8UnormSrgb],
        });
        let display_view = display.create_view(&Default::default());
        let display_srgb_view = display.create_view(&wgpu::TextureViewDescriptor {
            format: Some(wgpu::TextureFormat::Rgba8UnormSrgb),
            // sRGB formats cannot be storage-bound; this view is only sampled.
            usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
            ..Default::default()
        });
        FrameTargets {
            width,
            height,
            visibility: visibility.create_view(&Default::default()),
            depth: depth.create_view(&Default::default()),
            surfaces: [0, 1].map(|i| pixel_buffer(gpu, &format!("surfaces {i}"), pixels, surface)),
            reservoirs: [0, 1, 2]
                .map(|i| pixel_buffer(gpu, &format!("reservoirs {i}"), pixels, reservoir)),
            debug: pixel_buffer(
                gpu,
                "pixel debug",
                pixels,
                std::mem::size_of::<GpuPixelDebug>(),
            ),
            radiance: pixel_buffer(gpu, "radiance", pixels, color),
            accumulation: pixel_buffer(gpu, "accumulation", pixels, color),
            reference: pixel_buffer(gpu, "reference", pixels, color),
            display,
            display_view,
            display_srgb_view,
        }
    }

    pub fn pixel_count(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}
