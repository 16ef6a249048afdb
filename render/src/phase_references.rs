//! Scoring frames rendered with sub-pixel jitter (docs/src/viewer.md, "Accuracy with
//! jitter on").
//!
//! A jittered frame shades the surfaces seen at one sub-pixel offset; the antialiased
//! reference averages over the whole pixel. Against that reference a frame's error is
//! mostly the pixel footprint (what the surface at this offset differs from the pixel's
//! average), the same for every estimator. So each frame is scored against the reference
//! of its own jitter phase instead: jitter off (the G-buffer's surfaces, as the bench
//! measures), rasterised at that phase's offset. Its error is then the estimator's alone.
//! The `JITTER_PERIOD` references arrive one by one; a frame whose phase has none yet is
//! not scored (never scored against the wrong reference).

use crate::image::LinearImage;
use crate::renderer::{JITTER_PERIOD, jitter_phase};

/// One reference per jitter phase, filled in as they arrive.
#[derive(Clone, Debug)]
pub struct PhaseReferences {
    images: Vec<Option<LinearImage>>,
}

impl Default for PhaseReferences {
    fn default() -> Self {
        PhaseReferences {
            images: vec![None; JITTER_PERIOD as usize],
        }
    }
}

impl PhaseReferences {
    pub fn insert(&mut self, phase: u32, image: LinearImage) {
        self.images[(phase as u64 % JITTER_PERIOD) as usize] = Some(image);
    }

    /// The reference of the frame with renderer index `frame_index`, once rendered.
    pub fn for_frame(&self, frame_index: u64) -> Option<&LinearImage> {
        self.images[jitter_phase(frame_index) as usize].as_ref()
    }

    /// How many of the `JITTER_PERIOD` phases have their reference.
    pub fn ready(&self) -> usize {
        self.images.iter().filter(|i| i.is_some()).count()
    }

    /// The phase to render next: the first without a reference at or after `from`
    /// (wrapping), so the next frames are the first to be scored. None when all are there.
    pub fn next_missing(&self, from: u32) -> Option<u32> {
        let n = JITTER_PERIOD as u32;
        (0..n)
            .map(|i| (from % n + i) % n)
            .find(|&p| self.images[p as usize].is_none())
    }
}

/// The reference a frame's per-frame error is measured against: with jitter off the one
/// reference (pixel centres), with jitter on the frame's phase's (None until rendered).
pub fn reference_for_frame<'a>(
    jitter: bool,
    frame_index: u64,
    plain: &'a LinearImage,
    phases: &'a PhaseReferences,
) -> Option<&'a LinearImage> {
    if jitter {
        phases.for_frame(frame_index)
    } else {
        Some(plain)
    }
}

#[cfg(test)]
mod tests;
