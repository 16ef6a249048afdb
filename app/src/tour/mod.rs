//! Guided tours (docs/src/tours.md): a TOML file of steps, each a preset plus what to look at. A
//! step sets the scene (and its time and clip), the camera, the mode and parameters, an
//! optional split-screen B, the debug view and the exposure, and carries a caption and the
//! live numbers that prove it. The viewer walks through the steps (`--tour`, the Tour
//! section); `render --tour FILE --tour-step K` renders one headless. The file format is
//! in docs/src/tours.md ("The file format"); `parse.rs` reads it, with one-line errors
//! naming the file, the step and the problem.

mod parse;

use std::path::{Path, PathBuf};

use restir_render::{Camera, DebugView, Mode, Settings};

use crate::compare::CompareTarget;

/// A whole tour.
#[derive(Clone, Debug, PartialEq)]
pub struct Tour {
    /// The file it was read from (relative paths inside it are relative to its folder).
    pub path: PathBuf,
    pub title: String,
    pub steps: Vec<TourStep>,
}

/// Numbers a step can ask the viewer to show live (its `show` list).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LiveNumber {
    /// Per-frame luma RMSE of each side against the Accuracy reference.
    Rmse,
    /// Signed bias of each side's frame: (mean luma − reference's) / reference's.
    Bias,
    /// Frames each side takes to settle after a light event, and how far off it starts.
    Lag,
}

impl LiveNumber {
    pub const ALL: [LiveNumber; 3] = [LiveNumber::Rmse, LiveNumber::Bias, LiveNumber::Lag];

    pub fn name(self) -> &'static str {
        match self {
            LiveNumber::Rmse => "rmse",
            LiveNumber::Bias => "bias",
            LiveNumber::Lag => "lag",
        }
    }
}

/// Scene time for a step of an animated scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepTime {
    /// Where time starts (seconds); `None` keeps the scene's start (0).
    pub start: Option<f32>,
    /// One clip by name; `None` plays all together.
    pub clip: Option<String>,
    /// Time advances 1/fps per rendered frame (frame-locked, as `render --fps`) instead of
    /// with the wall clock: lag is then counted in the same frames as the bench's.
    pub fps: Option<f32>,
    /// Paused at `start` (the Accuracy reference needs time to stand still).
    pub paused: bool,
}

/// One step: everything it sets, and what it says.
#[derive(Clone, Debug, PartialEq)]
pub struct TourStep {
    pub title: String,
    pub caption: String,
    /// `builtin:NAME` or a path (resolved against the tour's folder); a step without one
    /// keeps the previous step's scene.
    pub scene: String,
    /// The environment (`builtin:sky` or a file); `None`: none.
    pub env: Option<String>,
    pub time: StepTime,
    /// `None`: the scene's own camera.
    pub camera: Option<Camera>,
    pub mode: Mode,
    /// The defaults plus the step's parameters (steps do not inherit each other's).
    pub settings: Settings,
    /// Split-screen B (an inline B is this step's settings with its own values changed).
    pub compare: Option<CompareTarget>,
    pub debug_view: DebugView,
    /// Exposure in EV; `None`: automatic.
    pub exposure: Option<f32>,
    pub show: Vec<LiveNumber>,
}

impl Tour {
    /// Reads and checks a tour file: every step's parameters, scene, view and B.
    pub fn load(path: &Path) -> anyhow::Result<Tour> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| anyhow::anyhow!("{}: cannot read tour: {e}", path.display()))?;
        parse::parse(&text, path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
    }

    /// Step `number` counted from 1 (as the viewer and `--tour-step` count).
    pub fn step(&self, number: usize) -> anyhow::Result<&TourStep> {
        number
            .checked_sub(1)
            .and_then(|i| self.steps.get(i))
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "--tour-step {number}: {} has steps 1..={}",
                    self.path.display(),
                    self.steps.len()
                )
            })
    }
}

#[cfg(test)]
mod tests;
