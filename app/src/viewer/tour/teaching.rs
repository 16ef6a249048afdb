//! What the viewer keeps between frames for its teaching tools (`driver.rs` does the
//! work): the facts of frames whose pixel inspection has not come back yet, and the
//! recording in progress.

use std::collections::VecDeque;

use crate::recording::Recorder;

/// What the frame loop keeps for the teaching tools.
#[derive(Default)]
pub struct Teaching {
    /// Scene time and "a light event came before it" per rendered frame, until the
    /// frame's inspection comes back (reports arrive a frame or two later).
    frames: VecDeque<(u64, Option<f32>, bool)>,
    /// The recording in progress (the View section's Record).
    pub(super) recorder: Option<Recorder>,
}

/// How many frames' facts wait for their inspection at most.
const PENDING_FRAMES: usize = 32;

impl Teaching {
    /// A frame just rendered: its scene time and whether a light event came before it.
    pub fn push_frame(&mut self, frame: u64, time: Option<f32>, event: bool) {
        self.frames.push_back((frame, time, event));
        while self.frames.len() > PENDING_FRAMES {
            self.frames.pop_front();
        }
    }

    /// The time and event of `frame`, once its inspection has arrived.
    pub fn facts_of(&self, frame: u64) -> (Option<f32>, bool) {
        self.frames
            .iter()
            .find(|(f, ..)| *f == frame)
            .map_or((None, false), |(_, t, e)| (*t, *e))
    }
}
