//! The live accuracy measurement (docs/src/viewer.md, "Accuracy"): while the camera
//! stands still, the reference of the current view is loaded from the cache or rendered
//! in the background; once it is there, every displayed frame is read back and scored
//! against it (docs/src/measured/how-the-bench-measures.md, "How it measures": per-frame luma RMSE,
//! stability, accumulated RGB RMSE, luma ratio), one curve per pipeline configuration.
//!
//! - this file: the plain state the panel shows and edits (no GPU, testable);
//! - `curves.rs`: curves, points and how a change of configuration is labelled;
//! - `tracker.rs`: the GPU side: the background reference job, the upload for the
//!   error view, the per-frame readback and metrics, and their throttle;
//! - `phases.rs`: with jitter on, the reference of each jitter phase, which each frame's
//!   per-frame error is measured against (docs/src/viewer.md, "Accuracy with jitter on");
//! - `side_scores.rs`: the split screen's and the tour's live numbers per side.

pub mod curves;
pub mod phases;
pub mod side_scores;
pub mod tracker;

#[cfg(test)]
mod tests;

use std::path::PathBuf;

use restir_render::reference_cache::{Progress, ReferenceMeta};

pub use curves::{Config, Curve, CurvePoint, Curves};

/// Reference sample counts offered in the panel.
pub const SPP_CHOICES: [u32; 4] = [64, 256, 1024, 4096];

/// What the Accuracy panel shows and edits.
#[derive(Clone, Debug)]
pub struct AccuracyState {
    /// Whether the panel was drawn open this frame. Measuring costs a readback per frame,
    /// so it runs only while someone is looking (the error view alone only needs the
    /// reference).
    pub panel_open: bool,
    /// Samples per pixel of the reference (a change asks for a new one).
    pub reference_spp: u32,
    /// Measure every frame however long the readback takes (else see `tracker::Throttle`).
    pub every_frame: bool,
    pub reference: ReferenceStatus,
    pub curves: Curves,
    /// Milliseconds the last measurement took (readback + metrics).
    pub measure_ms: Option<f64>,
    /// Frames rendered between the last two measurements, minus one (0 = every frame).
    pub frames_skipped: u64,
    /// With jitter on and the reference there: the jitter phases' references (None with
    /// jitter off, where the one reference serves every frame).
    pub phases: Option<PhaseStatus>,
}

impl AccuracyState {
    /// 256 spp renders `builtin:cornell` at the default lavapipe size in about 10 s;
    /// a GPU affords the bench's default, 1024.
    pub fn new(is_cpu: bool) -> AccuracyState {
        AccuracyState {
            panel_open: false,
            reference_spp: if is_cpu { 256 } else { 1024 },
            every_frame: false,
            reference: ReferenceStatus::Idle,
            curves: Curves::default(),
            measure_ms: None,
            frames_skipped: 0,
            phases: None,
        }
    }
}

/// Where the reference of the current view stands.
#[derive(Clone, Debug, PartialEq)]
pub enum ReferenceStatus {
    /// Nobody asked for one (panel closed, error view not shown).
    Idle,
    /// The view changed a moment ago; the reference starts once it stays still.
    WaitingForStill,
    /// Looking in the cache, or preparing the reference renderer.
    Starting,
    Rendering(Progress),
    Ready(ReferenceInfo),
    Failed(String),
}

/// The reference in use: what its cache entry says, and where it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceInfo {
    /// spp, its own estimated noise, render time (see `restir_render::reference_cache`).
    pub meta: ReferenceMeta,
    pub from_cache: bool,
    pub path: PathBuf,
}

/// How far the references of the jitter phases are (docs/src/viewer.md, "Accuracy with
/// jitter on"): a frame is scored only once its phase has one.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseStatus {
    /// Phases with a reference, of `restir_render::renderer::JITTER_PERIOD`.
    pub ready: usize,
    /// The phase being rendered and its progress.
    pub rendering: Option<(u32, Progress)>,
    /// Why the last phase failed (no further phase is started until the view changes).
    pub failed: Option<String>,
}
