//! The window's swapchain: creation, the adapter that can present to it, resizing, and
//! recovery when the surface is lost or outdated (every frame may find it so after a
//! resize, a display change or a minimise).

use std::sync::Arc;

use anyhow::Context;
use restir_render::{Gpu, GpuError};
use winit::window::Window;

pub struct GpuSurface {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// False while the window has no area (minimised): nothing is configured or drawn.
    configured: bool,
}

/// A surface texture to draw into this frame.
pub struct Frame {
    pub texture: wgpu::SurfaceTexture,
    pub view: wgpu::TextureView,
    /// The surface no longer matches the window exactly: reconfigure after presenting.
    pub suboptimal: bool,
}

impl GpuSurface {
    /// Creates the surface and a device on an adapter that can present to it.
    pub fn new(window: Arc<Window>) -> anyhow::Result<(GpuSurface, Gpu)> {
        let instance = restir_render::gpu::context::new_instance();
        // Without a Vulkan loader and driver (no GPU driver, no lavapipe) wgpu has no
        // backend to make a surface with; say what to install rather than wgpu's
        // "Failed to create surface for any enabled backend".
        let surface = instance.create_surface(window.clone()).map_err(|e| {
            GpuError::NoAdapter(format!("no graphics backend can draw into a window: {e}"))
        })?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }))
        .map_err(|e| GpuError::NoAdapter(format!("none can present to this window: {e}")))?;
        let gpu = Gpu::from_adapter(instance, adapter)?;
        let caps = surface.get_capabilities(&gpu.adapter);
        // egui-wgpu blends in gamma space: it wants a non-sRGB target.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .context("the surface supports no texture format")?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let mut s = GpuSurface {
            window,
            surface,
            config,
            configured: false,
        };
        s.resize(&gpu, size.width, size.height);
        Ok((s, gpu))
    }

    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Whether there is anything to draw into (false while minimised).
    pub fn is_drawable(&self) -> bool {
        self.configured
    }

    /// Reconfigures for a new window size; a zero size leaves the surface unconfigured.
    pub fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) {
        if width == 0 || height == 0 {
            self.configured = false;
            return;
        }
        let max = gpu.device.limits().max_texture_dimension_2d;
        self.config.width = width.min(max);
        self.config.height = height.min(max);
        self.surface.configure(&gpu.device, &self.config);
        self.configured = true;
    }

    /// The next surface texture, recovering from a lost or outdated surface. `None`
    /// means "skip this frame" (minimised, occluded, timed out, or just recovered).
    pub fn acquire(&mut self, gpu: &Gpu) -> Option<Frame> {
        if !self.configured {
            return None;
        }
        use wgpu::CurrentSurfaceTexture as T;
        let (texture, suboptimal) = match self.surface.get_current_texture() {
            T::Success(t) => (t, false),
            T::Suboptimal(t) => (t, true),
            T::Timeout | T::Occluded => return None,
            T::Outdated => {
                let size = self.window.inner_size();
                self.resize(gpu, size.width, size.height);
                return None;
            }
            T::Lost => {
                log::warn!("surface lost: re-creating it");
                self.recreate(gpu);
                return None;
            }
            T::Validation => {
                log::error!("surface validation error: {:?}", gpu.take_error());
                return None;
            }
        };
        let view = texture
            .texture
            .create_view(&wgpu::TextureViewDescriptor::default());
        Some(Frame {
            texture,
            view,
            suboptimal,
        })
    }

    fn recreate(&mut self, gpu: &Gpu) {
        match gpu.instance.create_surface(self.window.clone()) {
            Ok(surface) => {
                self.surface = surface;
                let size = self.window.inner_size();
                self.resize(gpu, size.width, size.height);
            }
            Err(e) => log::error!("cannot re-create the surface: {e}"),
        }
    }

    /// Presents the frame; reconfigures afterwards when it was suboptimal.
    pub fn present(&mut self, gpu: &Gpu, frame: Frame) {
        self.window.pre_present_notify();
        let suboptimal = frame.suboptimal;
        drop(frame.view);
        gpu.queue.present(frame.texture);
        if suboptimal {
            let size = self.window.inner_size();
            self.resize(gpu, size.width, size.height);
        }
    }
}
