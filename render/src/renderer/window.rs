//! The temporal window of the boiling and survivor-change views, host side: when it
//! restarts (a camera cut, a resize, a new scene or mode, or a frame without it), and
//! its figures read back for `render --stats` and the tests.

use super::Renderer;
use crate::gpu_types::GpuWindowPixel;
use crate::passes::temporal_window::WINDOW;
use crate::shader_constants::{BOILING_THRESHOLD, TEMPORAL_WINDOW_FRAMES};

/// Whether the window buffer holds an unbroken run of frames, and how many.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct WindowState {
    /// False: the next frame that keeps the window clears it first.
    valid: bool,
    /// Frames pushed since it was last cleared.
    frames: u32,
}

impl WindowState {
    /// The next frame starts a new window (the frames so far show another image).
    pub(super) fn restart(&mut self) {
        self.valid = false;
    }

    /// Called for every frame: whether this frame must clear the window before pushing.
    pub(super) fn begin_frame(&mut self, kept: bool) -> bool {
        let clear = kept && !self.valid;
        self.frames = match (kept, clear) {
            (false, _) => 0,
            (true, true) => 1,
            (true, false) => self.frames + 1,
        };
        // A frame without the window breaks the run: the next one starts afresh.
        self.valid = kept;
        clear
    }
}

/// The window's figures per pixel, as the views paint them.
#[derive(Clone, Debug, PartialEq)]
pub struct TemporalWindow {
    pub width: u32,
    pub height: u32,
    /// Frames in the window (at most `TEMPORAL_WINDOW_FRAMES`).
    pub frames: u32,
    /// σ / mean of each pixel's luminance over the window (the boiling view).
    pub rel_std: Vec<f32>,
    /// Fraction of the window's transitions in which the survivor's light changed (the
    /// survivor-change view).
    pub change_fraction: Vec<f32>,
}

impl TemporalWindow {
    /// The share of the pixels where `mask` holds whose σ/mean exceeds
    /// `BOILING_THRESHOLD`: how much of the image boils. (A mean over pixels hides it: a
    /// high M cap with permutation calms most pixels and makes a few boil hard.)
    pub fn boiling_share(&self, mask: Option<&[bool]>) -> f64 {
        let boils: Vec<f32> = self
            .rel_std
            .iter()
            .map(|&v| if v > BOILING_THRESHOLD { 1.0 } else { 0.0 })
            .collect();
        Self::mean(&boils, mask)
    }

    /// The mean over pixels of `values` where `mask` holds (all pixels when `None`).
    pub fn mean(values: &[f32], mask: Option<&[bool]>) -> f64 {
        let (sum, n) = values
            .iter()
            .enumerate()
            .filter(|(i, _)| mask.is_none_or(|m| m[*i]))
            .fold((0.0f64, 0usize), |(s, n), (_, v)| (s + *v as f64, n + 1));
        if n == 0 { 0.0 } else { sum / n as f64 }
    }
}

impl Renderer {
    /// Frames in the temporal window now (0 unless a boiling view was shown last frame).
    pub fn temporal_window_frames(&self) -> u32 {
        self.window.frames.min(TEMPORAL_WINDOW_FRAMES)
    }

    /// Every frame draws the random numbers frame 0 drew (on: a still scene renders the
    /// same image every frame, the boiling view's zero; off: a new draw per frame).
    pub fn freeze_noise(&mut self, frozen: bool) {
        self.frozen_noise = frozen;
    }

    /// The boiling and survivor-change figures of the last frame (`None` before a frame
    /// has kept the window).
    pub fn read_temporal_window(&self) -> Option<TemporalWindow> {
        if self.window.frames == 0 {
            return None;
        }
        let pixels: Vec<GpuWindowPixel> = self.pixel_records(self.targets.pixels(&WINDOW));
        let (width, height) = self.size();
        Some(TemporalWindow {
            width,
            height,
            frames: self.temporal_window_frames(),
            rel_std: pixels.iter().map(|p| p.rel_std).collect(),
            change_fraction: pixels.iter().map(|p| p.change_fraction).collect(),
        })
    }
}

/// Before a frame's passes: clears the window buffer when this frame starts a new window
/// (`kept`: the frame plan keeps the window, so its buffer is allocated).
pub(super) fn begin_window_frame(
    window: &mut WindowState,
    gpu: &crate::Gpu,
    targets: &crate::frame_targets::FrameTargets,
    kept: bool,
) {
    if window.begin_frame(kept) {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.clear_buffer(targets.pixels(&WINDOW), 0, None);
        gpu.queue.submit([encoder.finish()]);
    }
}

#[cfg(test)]
mod tests {
    use super::WindowState;

    #[test]
    fn the_window_restarts_after_a_break_or_a_restart() {
        let mut w = WindowState::default();
        assert!(w.begin_frame(true), "the first frame clears");
        assert!(!w.begin_frame(true));
        assert_eq!(w.frames, 2);
        w.restart();
        assert!(w.begin_frame(true), "a cut clears");
        assert_eq!(w.frames, 1);
        assert!(!w.begin_frame(false));
        assert_eq!(w.frames, 0);
        assert!(
            w.begin_frame(true),
            "a frame without the window breaks the run"
        );
    }
}
