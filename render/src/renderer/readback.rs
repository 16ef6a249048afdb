//! Blocking reads of the last frame's outputs (headless rendering, tests, the inspector).

use super::Renderer;
use crate::gi::passes::initial::GI_RESERVOIRS;
use crate::gpu::readback::{read_buffer, read_rgba8_texture};
use crate::gpu_types::{GpuPixelDebug, GpuReservoir, GpuSurface};
use crate::image::LinearImage;
use crate::passes::resources::{ACCUMULATION, DEBUG, RADIANCE, RESERVOIRS};

impl Renderer {
    fn read_image(&self, buffer: &wgpu::Buffer, scale: f32) -> LinearImage {
        let (w, h) = self.size();
        let mut pixels: Vec<[f32; 4]> = read_buffer(&self.gpu, buffer, 0, w as u64 * h as u64 * 16);
        pixels.resize((w * h) as usize, [0.0; 4]);
        if scale != 1.0 {
            for p in &mut pixels {
                for c in &mut p[..3] {
                    *c *= scale;
                }
                p[3] = 1.0;
            }
        }
        LinearImage {
            width: w,
            height: h,
            pixels,
        }
    }

    /// Linear radiance of the last frame.
    pub fn read_radiance(&self) -> LinearImage {
        self.read_image(self.targets.pixels(&RADIANCE), 1.0)
    }

    /// The average of all frames since the last accumulation reset.
    pub fn read_accumulated(&self) -> LinearImage {
        self.read_image(
            self.targets.pixels(&ACCUMULATION),
            1.0 / self.accumulated_frames.max(1) as f32,
        )
    }

    /// What the display pass produced (tonemapped image or debug view), sRGB RGBA8.
    pub fn read_display_rgba8(&self) -> Vec<u8> {
        read_rgba8_texture(&self.gpu, &self.targets.display)
    }

    pub(super) fn pixel_records<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer) -> Vec<T> {
        read_buffer(
            &self.gpu,
            buffer,
            0,
            self.targets.pixel_count() * std::mem::size_of::<T>() as u64,
        )
    }

    /// Per-pixel debug records of the last frame.
    pub fn read_debug(&self) -> Vec<GpuPixelDebug> {
        self.pixel_records(self.targets.pixels(&DEBUG))
    }

    /// The reservoirs the last frame shaded with (empty after a reference frame).
    pub fn read_final_reservoirs(&self) -> Vec<GpuReservoir> {
        match self.history.last_final {
            Some(i) => self.pixel_records(self.targets.chain(&RESERVOIRS, i)),
            None => Vec::new(),
        }
    }

    /// The last frame's final ReSTIR GI reservoirs (empty unless the last frame ran GI).
    pub fn read_gi_reservoirs(&self) -> Vec<crate::gpu_types::GpuGiReservoir> {
        if !self.history.carried.has_history(&GI_RESERVOIRS) {
            return Vec::new();
        }
        let final_buffer = self.history.carried.history(&GI_RESERVOIRS);
        self.pixel_records(self.targets.chain(&GI_RESERVOIRS, final_buffer))
    }

    /// The last frame's final ReSTIR PT path reservoirs (empty unless the last frame ran PT).
    pub fn read_pt_reservoirs(&self) -> Vec<crate::gpu_types::GpuPtReservoir> {
        use crate::pt::passes::initial::PT_RESERVOIRS;
        if !self.history.carried.has_history(&PT_RESERVOIRS) {
            return Vec::new();
        }
        let final_buffer = self.history.carried.history(&PT_RESERVOIRS);
        self.pixel_records(self.targets.chain(&PT_RESERVOIRS, final_buffer))
    }

    /// The last frame's ReSTIR PT debug records (the PT views' data; meaningful only after a
    /// frame that ran PT).
    pub fn read_pt_debug(&self) -> Vec<crate::gpu_types::GpuPtPixelDebug> {
        self.pixel_records(self.targets.pixels(&crate::pt::passes::initial::PT_DEBUG))
    }

    /// The last frame's G-buffer surfaces.
    pub fn read_surfaces(&self) -> Vec<GpuSurface> {
        self.pixel_records(&self.targets.surfaces[self.history.carried.surfaces])
    }
}

impl Renderer {
    /// The last frame's radiance before the denoiser (its `denoise-input` view); meaningful
    /// only after a frame that denoised.
    pub fn read_denoise_input(&self) -> LinearImage {
        self.read_image(self.targets.pixels(&crate::denoise::passes::INPUT), 1.0)
    }

    /// The denoiser's temporal history after the last frame (empty unless it denoised).
    pub fn read_denoise_history(&self) -> Vec<crate::gpu_types::GpuDenoiseHistory> {
        use crate::denoise::passes::HISTORY;
        if !self.history.carried.has_history(&HISTORY) {
            return Vec::new();
        }
        self.pixel_records(
            self.targets
                .chain(&HISTORY, self.history.carried.history(&HISTORY)),
        )
    }
}
