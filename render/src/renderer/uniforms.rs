//! The per-frame uniforms: camera matrices and sub-pixel jitter, and the display settings.

use glam::Vec2;

use super::Renderer;
use crate::gpu_types::{GpuDisplay, GpuFrame};
use crate::settings::Settings;
use crate::shader_constants::{MAX_SPATIAL_NEIGHBOURS, MAX_SPATIAL_PASSES, NO_INSPECT_PIXEL};
use crate::view::Mode;

/// Frames before the sub-pixel offsets repeat: frame `i` and frame `i + JITTER_PERIOD` are
/// rasterised at the same offset (docs/src/viewer.md, "Accuracy with jitter on").
pub const JITTER_PERIOD: u64 = 64;

/// The jitter phase of a frame: which of the `JITTER_PERIOD` sub-pixel offsets it uses.
pub fn jitter_phase(frame_index: u64) -> u32 {
    (frame_index % JITTER_PERIOD) as u32
}

/// The sub-pixel offset (pixels, each axis in [−½, ½)) of jitter phase `phase`:
/// Halton(2, 3). Pixel p of such a frame samples the point p + ½ − offset.
pub fn jitter_offset(phase: u32) -> Vec2 {
    let i = phase % JITTER_PERIOD as u32 + 1;
    Vec2::new(halton(i, 2), halton(i, 3)) - 0.5
}

/// Radical inverse in base b (Halton sequence) for sub-pixel jitter.
fn halton(mut index: u32, base: u32) -> f32 {
    let mut f = 1.0;
    let mut r = 0.0;
    while index > 0 {
        f /= base as f32;
        r += f * (index % base) as f32;
        index /= base;
    }
    r
}

impl Renderer {
    /// Writes the frame uniform; returns (unjittered view-projection, jitter).
    pub(super) fn write_frame_uniform(&mut self, settings: &Settings) -> (glam::Mat4, Vec2) {
        let (width, height) = self.size();
        let camera = self.camera;
        let aspect = width as f32 / height as f32;
        let near = (self.scene.scale * 1e-5).max(1e-30);
        let view_proj = camera.projection_matrix(aspect, near) * camera.view_matrix();
        let jitter = match (self.mode, self.reference_phase) {
            // A reference of one jitter phase rasterises the surfaces that phase's frames
            // see (docs/src/viewer.md, "Accuracy with jitter on").
            (Mode::Reference, Some(phase)) => jitter_offset(phase),
            (Mode::Reference, None) => Vec2::ZERO,
            _ if settings.jitter => jitter_offset(jitter_phase(self.frame_index)),
            _ => Vec2::ZERO,
        };
        let frame = GpuFrame {
            view_proj: view_proj.to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            prev_view_proj: self
                .history
                .prev_view_proj
                .unwrap_or(view_proj)
                .to_cols_array_2d(),
            camera_position: camera.position.into(),
            // Frozen noise: every frame seeds its random streams as frame 0 did.
            frame_index: if self.frozen_noise {
                0
            } else {
                self.frame_index as u32
            },
            prev_camera_position: self
                .history
                .prev_camera
                .map_or(camera.position, |c| c.position)
                .into(),
            seed: self.seed,
            jitter: jitter.into(),
            size: [width, height],
            scene_scale: self.scene.scale,
            history_valid: self.history.history_valid as u32,
            light_count: self.scene.sampled_light_count(),
            punctual_count: self.scene.punctual_count,
            prev_jitter: self.history.prev_jitter.into(),
            inspect_pixel: self
                .inspected_pixel
                .filter(|&(x, y)| x < width && y < height)
                .map_or(NO_INSPECT_PIXEL, |(x, y)| y * width + x),
            finite_light_share: self.scene.finite_light_share(),
        };
        self.gpu
            .queue
            .write_buffer(&self.buffers.frame_uniform, 0, bytemuck::bytes_of(&frame));
        (view_proj, jitter)
    }

    pub(super) fn write_display_uniform(&self, settings: &Settings) {
        let display = GpuDisplay {
            scale: if self.shows_accumulation() {
                1.0 / self.accumulated_frames.max(1) as f32
            } else {
                1.0
            },
            exposure: 2f32.powf(self.view.exposure_ev.clamp(-60.0, 60.0)),
            tonemapper: self.view.tonemapper.gpu_code(),
            view: self.view.view.gpu_code(),
            reason_mask: self.view.reason_mask,
            m_scale: settings.m_cap,
            // The uploaded reference is already an average.
            reference_scale: 1.0,
            spatial_tries: if self.view.spatial_count && settings.spatial {
                settings.spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS)
                    * settings.spatial_passes.min(MAX_SPATIAL_PASSES)
            } else {
                0
            },
            comparison_scale: self.comparison_scale,
            reference_noise: self.reference_noise,
            _pad: [0; 2],
        };
        self.gpu.queue.write_buffer(
            &self.buffers.display_uniform,
            0,
            bytemuck::bytes_of(&display),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halton_is_in_unit_interval_and_low_discrepancy() {
        let xs: Vec<f32> = (1..=64).map(|i| halton(i, 2)).collect();
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = xs.iter().sum::<f32>() / 64.0;
        assert!((mean - 0.5).abs() < 0.02);
        assert_eq!(halton(1, 2), 0.5);
        assert_eq!(halton(2, 3), 2.0 / 3.0);
    }

    /// The phase of a frame repeats with the period, and its offset is the one frames
    /// have always used (frame 0: Halton index 1 = (½, ⅓) − ½).
    #[test]
    fn a_frame_and_its_phase_share_one_offset() {
        assert_eq!(jitter_phase(0), 0);
        assert_eq!(jitter_phase(JITTER_PERIOD + 5), 5);
        assert_eq!(jitter_offset(0), Vec2::new(0.0, 1.0 / 3.0 - 0.5));
        let offsets: Vec<Vec2> = (0..JITTER_PERIOD as u32).map(jitter_offset).collect();
        assert!(offsets.iter().all(|o| o.abs().max_element() <= 0.5));
        // 64 distinct offsets: a reference of one phase serves only that phase's frames.
        for (i, a) in offsets.iter().enumerate() {
            assert!(offsets[..i].iter().all(|b| b != a), "phase {i} repeats");
        }
    }
}
