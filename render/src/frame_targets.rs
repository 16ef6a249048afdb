//! Everything whose size follows the output size: the visibility and depth targets, the
//! display texture, the surface buffers (current / previous), and every per-pixel buffer
//! and reservoir chain the passes declare (`passes::resources`). Re-created on resize;
//! history starts invalid.
//!
//! Buffers exist when a frame needs them: the standard ones from the start (readbacks and
//! uploads can come before any frame), others when a frame's plan first names them
//! (`ensure`). Without temporal reuse nothing needs last frame's data: one surface buffer
//! and two reservoir buffers suffice; the second surface buffer and the third reservoir
//! buffer (the history) appear the first time temporal reuse runs.

use std::collections::HashMap;

use crate::gpu::{Gpu, texture_2d};
use crate::gpu_types::GpuSurface;
use crate::passes::resources::{Allocation, Chain, PixelBuffer, RESERVOIRS, STANDARD};
use crate::passes::{display, gbuffer};

pub struct FrameTargets {
    pub width: u32,
    pub height: u32,
    pub visibility: wgpu::TextureView,
    pub depth: wgpu::TextureView,
    /// One, or two once a pass has read the previous surfaces (current and previous).
    pub surfaces: Vec<wgpu::Buffer>,
    pixels: HashMap<&'static str, wgpu::Buffer>,
    chains: HashMap<&'static str, Vec<wgpu::Buffer>>,
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

/// What a frame needs allocated: per chain the number of buffers, whether the previous
/// surfaces are read, and the per-pixel buffers it names.
#[derive(Default, Debug)]
pub struct Needs {
    pub chains: Vec<(&'static Chain, usize)>,
    pub previous_surfaces: bool,
    pub pixels: Vec<&'static PixelBuffer>,
}

impl FrameTargets {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> FrameTargets {
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
        let mut targets = FrameTargets {
            width,
            height,
            visibility: visibility.create_view(&Default::default()),
            depth: depth.create_view(&Default::default()),
            surfaces: Vec::new(),
            pixels: HashMap::new(),
            chains: HashMap::new(),
            display,
            display_view,
            display_srgb_view,
        };
        targets.ensure(
            gpu,
            &Needs {
                chains: vec![(&RESERVOIRS, 2)],
                previous_surfaces: false,
                pixels: STANDARD.to_vec(),
            },
        );
        targets
    }

    /// Allocates what `needs` names and is missing (nothing is ever re-created here, so
    /// cached bind groups stay valid).
    pub fn ensure(&mut self, gpu: &Gpu, needs: &Needs) {
        let pixels = self.pixel_count();
        let surface_count = if needs.previous_surfaces { 2 } else { 1 };
        while self.surfaces.len() < surface_count {
            let label = format!("surfaces {}", self.surfaces.len());
            let stride = std::mem::size_of::<GpuSurface>();
            self.surfaces
                .push(pixel_buffer(gpu, &label, pixels, stride));
        }
        for &(chain, count) in &needs.chains {
            let buffers = self.chains.entry(chain.name).or_default();
            while buffers.len() < count {
                let label = format!("{} {}", chain.name, buffers.len());
                buffers.push(pixel_buffer(gpu, &label, pixels, chain.stride));
            }
        }
        for &buffer in &needs.pixels {
            self.pixels.entry(buffer.name).or_insert_with(|| {
                let count = match buffer.allocation {
                    Allocation::Full => pixels,
                    Allocation::Placeholder => 0,
                    Allocation::Fixed(count) => count,
                };
                pixel_buffer(gpu, buffer.name, count, buffer.stride)
            });
        }
    }

    /// The buffer `buffer` (allocated: standard, or named by an earlier `ensure`).
    pub fn pixels(&self, buffer: &PixelBuffer) -> &wgpu::Buffer {
        self.pixels_named(buffer.name)
    }

    pub fn pixels_named(&self, name: &str) -> &wgpu::Buffer {
        self.pixels
            .get(name)
            .unwrap_or_else(|| panic!("{name} was never allocated"))
    }

    /// Buffer `index` of `chain`.
    pub fn chain(&self, chain: &Chain, index: usize) -> &wgpu::Buffer {
        self.chain_named(chain.name, index)
    }

    pub fn chain_named(&self, name: &str, index: usize) -> &wgpu::Buffer {
        &self.chains[name][index]
    }

    pub fn chain_len(&self, chain: &Chain) -> usize {
        self.chains.get(chain.name).map_or(0, Vec::len)
    }

    /// Allocates a placeholder buffer at full size; true if it was re-created (bind
    /// groups that hold the placeholder must be rebuilt).
    pub fn ensure_full(&mut self, gpu: &Gpu, buffer: &'static PixelBuffer) -> bool {
        let size = self.pixel_count() * buffer.stride as u64;
        if self
            .pixels
            .get(buffer.name)
            .is_some_and(|b| b.size() >= size)
        {
            return false;
        }
        let full = pixel_buffer(gpu, buffer.name, self.pixel_count(), buffer.stride);
        self.pixels.insert(buffer.name, full);
        true
    }

    /// Whether the previous-frame surfaces and the history reservoirs exist.
    pub fn has_history(&self) -> bool {
        self.surfaces.len() == 2 && self.chain_len(&RESERVOIRS) == 3
    }

    pub fn pixel_count(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}
