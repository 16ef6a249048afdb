//! The split screen's labels and the tour's live numbers: per side, the per-frame luma RMSE
//! and signed bias of its last frame against the reference that frame is measured against
//! (docs/src/viewer.md, "Accuracy with jitter on"). A readback per side costs, so a side is
//! scored at most every `INTERVAL`; with jitter on only on a frame whose phase has its
//! reference, keeping the last numbers meanwhile.

use std::time::{Duration, Instant};

use restir_render::LinearImage;
use restir_render::Renderer;
use restir_render::metrics::{luma_ratio, luma_rmse};
use restir_render::phase_references::{PhaseReferences, reference_for_frame};

/// A few times a second: the labels stay readable, the readbacks cheap.
pub const INTERVAL: Duration = Duration::from_millis(250);

/// Per-frame luma RMSE and signed bias ((mean luma − reference's) / reference's).
pub type Score = (f64, f64);

#[derive(Clone, Copy, Debug, Default)]
struct Side {
    scored_at: Option<Instant>,
    score: Option<Score>,
}

/// Side A (the viewer's renderer) and side B (the split screen's other one).
#[derive(Clone, Copy, Debug, Default)]
pub struct SideScores {
    sides: [Side; 2],
}

/// What a side's frame is measured against: the reference and whether the view's jitter
/// (what the references were rendered for) is the side's own.
pub struct References<'a> {
    pub plain: &'a LinearImage,
    pub phases: &'a PhaseReferences,
    pub jitter: bool,
}

impl SideScores {
    /// Scores side `side` (0: A, 1: B) if due and its last frame has its reference;
    /// returns its latest numbers (None: nothing comparable yet).
    pub fn update(
        &mut self,
        side: usize,
        renderer: &Renderer,
        references: &References,
        now: Instant,
    ) -> Option<Score> {
        let s = &mut self.sides[side];
        // A side rendering with the other jitter setting has no reference of its frames.
        if renderer.settings().jitter != references.jitter {
            *s = Side::default();
            return None;
        }
        if s.scored_at.is_some_and(|t| now - t < INTERVAL) {
            return s.score;
        }
        // `render_frame` has moved the index past the frame just rendered.
        let frame = renderer.frame_index().saturating_sub(1);
        let plain = references.plain;
        let Some(reference) =
            reference_for_frame(references.jitter, frame, plain, references.phases)
        else {
            return s.score;
        };
        let image = renderer.read_radiance();
        let score = luma_rmse(&image, reference)
            .and_then(|rmse| Ok((rmse, luma_ratio(&image, reference)? - 1.0)))
            .ok();
        *s = Side {
            scored_at: Some(now),
            score,
        };
        score
    }

    /// Forgets both sides (a new view: their numbers measured another image).
    pub fn clear(&mut self) {
        *self = SideScores::default();
    }
}
