//! `denoise_auto_depth`: the renderer's side of the depth probe (`denoise::depth_probe`,
//! docs/src/denoiser.md "Choosing the depth"). Once the denoiser's history has been valid
//! for `DEPTH_PROBE_FRAMES` frames in a row, the probe reads the G-buffer and the history
//! back and keeps them; after the next frame it reads that frame's raw radiance, filters
//! the kept history at every depth on the CPU and keeps the depth closest to the new
//! frame. The frames after it filter at that depth. The choice holds until the settings,
//! the mode or the size change (a new estimator is a new noise level); camera motion and
//! cuts keep it.

use super::Renderer;
use crate::denoise::depth_probe::{
    DEPTH_PROBE_FRAMES, DepthChoice, choose_depth, crop, probe_window,
};
use crate::denoise::model::{Frame, Params, Pixel, luminance, same_surface};
use crate::gpu_types::GpuDenoiseHistory;
use crate::settings::Settings;

#[derive(Default)]
pub(super) struct DepthProbeState {
    /// Frames in a row that denoised on a valid history.
    warm_frames: u32,
    /// The history and surfaces kept for the next frame to be compared with.
    kept: Option<Kept>,
    choice: Option<DepthChoice>,
}

struct Kept {
    window: (u32, u32, u32, u32),
    pixels: Vec<Pixel>,
    history: Vec<GpuDenoiseHistory>,
    /// What keeping it cost (its readbacks).
    ms: f64,
}

impl Renderer {
    /// The probe's choice for the current settings: `None` before it has run (the frames
    /// then filter at `denoise_iterations`) or with `denoise_auto_depth` off.
    pub fn denoise_depth_choice(&self) -> Option<&DepthChoice> {
        self.settings
            .denoise_auto_depth
            .then_some(self.depth_probe.choice.as_ref())
            .flatten()
    }

    /// The depth this frame filters at when the probe has chosen one.
    pub(super) fn apply_depth_choice(&self, settings: &mut Settings) {
        if settings.denoise_auto_depth
            && let Some(choice) = &self.depth_probe.choice
        {
            settings.denoise_iterations = choice.iterations;
        }
    }

    /// New settings, mode or size: the next choice waits for a history of the new
    /// estimator.
    pub(super) fn forget_depth_choice(&mut self) {
        self.depth_probe = DepthProbeState::default();
    }

    /// After a frame: counts the warm frames, keeps the history when due, and compares the
    /// kept one with this frame.
    pub(super) fn after_frame_depth_probe(&mut self, denoised_on_history: bool) {
        if !denoised_on_history {
            self.depth_probe.warm_frames = 0;
            self.depth_probe.kept = None;
            return;
        }
        self.depth_probe.warm_frames += 1;
        let due =
            self.depth_probe.kept.is_some() || self.depth_probe.warm_frames >= DEPTH_PROBE_FRAMES;
        if !self.settings.denoise_auto_depth || self.depth_probe.choice.is_some() || !due {
            return;
        }
        let settings = self.effective_settings();
        let start = std::time::Instant::now();
        if let Some(kept) = self.depth_probe.kept.take() {
            self.depth_probe.choice =
                self.compare_with_this_frame(&kept, &settings)
                    .map(|choice| DepthChoice {
                        probe_ms: kept.ms + start.elapsed().as_secs_f64() * 1e3,
                        ..choice
                    });
        } else {
            self.depth_probe.kept = self.keep_history().map(|kept| Kept {
                ms: start.elapsed().as_secs_f64() * 1e3,
                ..kept
            });
        }
    }

    fn keep_history(&self) -> Option<Kept> {
        let history = self.read_denoise_history();
        let surfaces = self.read_surfaces();
        let (width, height) = self.size();
        let pixels = (width * height) as usize;
        if history.len() < pixels || surfaces.len() < pixels {
            return None;
        }
        let window = probe_window(width, height);
        Some(Kept {
            window,
            pixels: crop(&surfaces, width, window)
                .iter()
                .map(Pixel::from_surface)
                .collect(),
            history: crop(&history, width, window),
            ms: 0.0,
        })
    }

    /// This frame's illumination at the kept frame's pixels (through the motion vectors,
    /// where the same surface is seen), then the probe.
    fn compare_with_this_frame(&self, kept: &Kept, settings: &Settings) -> Option<DepthChoice> {
        let height = self.size().1;
        let (x0, y0, w, h) = kept.window;
        let surfaces = self.read_surfaces();
        let radiance = self.read_denoise_input();
        let mut held_out = vec![None; (w * h) as usize];
        for (s, r) in surfaces.iter().zip(&radiance.pixels) {
            let now = Pixel::from_surface(s);
            // Where the point was last frame, in the kept window.
            let (px, py) = (now.motion.x.floor(), now.motion.y.floor());
            if !now.valid || !now.motion.is_finite() || px < x0 as f32 || py < y0 as f32 {
                continue;
            }
            let (kx, ky) = (px as u32 - x0, py as u32 - y0);
            if kx >= w || ky >= h {
                continue;
            }
            let k = (ky * w + kx) as usize;
            if held_out[k].is_some() || !same_surface(&now, &kept.pixels[k]) {
                continue;
            }
            let illumination = (glam::Vec3::new(r[0], r[1], r[2]) - now.emission)
                .max(glam::Vec3::ZERO)
                / now.demodulation();
            held_out[k] = Some(luminance(illumination));
        }
        // The probe reads neither last frame's surfaces nor the radiance: it filters the
        // kept history (`model::variance`, `model::atrous`).
        let frame = Frame {
            width: w,
            height: h,
            pixels: &kept.pixels,
            previous: &kept.pixels,
            radiance: &[],
        };
        let params = crate::denoise::settings::model_params(
            settings,
            Params::pixel_angle(self.camera.yfov, height),
        );
        let choice = choose_depth(&frame, &kept.history, &held_out, &params)?;
        log::info!(
            "denoise_auto_depth: {} iterations (held-out error by depth {:?}, {} pixels)",
            choice.iterations,
            choice.held_out_error,
            choice.pixels
        );
        Some(choice)
    }
}
