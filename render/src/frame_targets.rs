//! Everything whose size follows the output size: the visibility and depth targets, the
//! surface buffers (current / previous), the reservoir buffers that the stages hand around
//! (notes §2.6: ping-pong), the debug records, radiance, accumulation and the display
//! texture. Re-created on resize; history starts invalid.
//!
//! Without temporal reuse nothing needs last frame's data: one surface buffer and two
//! reservoir buffers suffice. The second surface buffer and the third reservoir buffer
//! (the history) are allocated the first time temporal reuse runs.

use crate::gpu::{Gpu, texture_2d};
use crate::gpu_types::{GpuPixelDebug, GpuReservoir, GpuSurface};
use crate::passes::{display, gbuffer};

pub struct FrameTargets {
    pub width: u32,
    pub height: u32,
    pub visibility: wgpu::TextureView,
    pub depth: wgpu::TextureView,
    /// One, or two once temporal reuse has run (current and previous).
    pub surfaces: Vec<wgpu::Buffer>,
    /// Two, or three once temporal reuse has run (the third keeps the history).
    pub reservoirs: Vec<wgpu::Buffer>,
    pub debug: wgpu::Buffer,
    pub radiance: wgpu::Buffer,
    pub accumulation: wgpu::Buffer,
    /// A reference image for the error view (zeros until one is uploaded).
    pub reference: wgpu::Buffer,
    /// The other side of a split-screen comparison for the difference view: a 16-byte
    /// placeholder until one is set (`ensure_comparison`).
    pub comparison: wgpu::Buffer,
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

impl FrameTargets {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> FrameTargets {
        let pixels = width as u64 * height as u64;
        let surface = std::mem::size_of::<GpuSurface>();
        let reservoir = std::mem::size_of::<GpuReservoir>();
        let color = std::mem::size_of::<[f32; 4]>();
        let visibility = texture_2d(
            gpu,
            "visibility",
            width,
            height,
            gbuffer::VISIBILITY_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            &[],
        );
        let depth = texture_2d(
            gpu,
            "depth",
            width,
            height,
            gbuffer::DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
            &[],
        );
        let display = texture_2d(
            gpu,
            "display",
            width,
            height,
            display::OUTPUT_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            // The viewer samples it through an sRGB view.
            &[wgpu::TextureFormat::Rgba8UnormSrgb],
        );
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
            surfaces: vec![pixel_buffer(gpu, "surfaces 0", pixels, surface)],
            reservoirs: (0..2)
                .map(|i| pixel_buffer(gpu, &format!("reservoirs {i}"), pixels, reservoir))
                .collect(),
            debug: pixel_buffer(
                gpu,
                "pixel debug",
                pixels,
                std::mem::size_of::<GpuPixelDebug>(),
            ),
            radiance: pixel_buffer(gpu, "radiance", pixels, color),
            accumulation: pixel_buffer(gpu, "accumulation", pixels, color),
            reference: pixel_buffer(gpu, "reference", pixels, color),
            comparison: pixel_buffer(gpu, "comparison", 0, color),
            display,
            display_view,
            display_srgb_view,
        }
    }

    /// Allocates the previous-frame surfaces and the history reservoirs (first temporal frame).
    pub fn ensure_history(&mut self, gpu: &Gpu) {
        let pixels = self.pixel_count();
        if self.surfaces.len() < 2 {
            self.surfaces.push(pixel_buffer(
                gpu,
                "surfaces 1",
                pixels,
                std::mem::size_of::<GpuSurface>(),
            ));
        }
        if self.reservoirs.len() < 3 {
            self.reservoirs.push(pixel_buffer(
                gpu,
                "reservoirs 2",
                pixels,
                std::mem::size_of::<GpuReservoir>(),
            ));
        }
    }

    /// Allocates the comparison image at full size; true if it was re-created (bind
    /// groups that hold the placeholder must be rebuilt).
    pub fn ensure_comparison(&mut self, gpu: &Gpu) -> bool {
        let size = self.pixel_count() * std::mem::size_of::<[f32; 4]>() as u64;
        if self.comparison.size() >= size {
            return false;
        }
        self.comparison = pixel_buffer(
            gpu,
            "comparison",
            self.pixel_count(),
            std::mem::size_of::<[f32; 4]>(),
        );
        true
    }

    pub fn has_history(&self) -> bool {
        self.surfaces.len() == 2 && self.reservoirs.len() == 3
    }

    pub fn pixel_count(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}
