//! With jitter on, the references of the jitter phases (docs/src/viewer.md, "Accuracy with
//! jitter on"): once the antialiased reference is there, one background job after another
//! renders the reference of one sub-pixel offset (jitter off, rasterised at that offset),
//! starting with the phase of the frames about to be drawn. Each frame is scored against
//! its own phase's reference, so its error is the estimator's, not the pixel footprint's.

use restir_render::phase_references::PhaseReferences;
use restir_render::reference_cache::{JobState, ReferenceJob, ReferenceRequest};

use super::PhaseStatus;

#[derive(Default)]
pub struct PhaseJobs {
    pub references: PhaseReferences,
    /// The phase being rendered and its job.
    job: Option<(u32, ReferenceJob)>,
    failed: Option<String>,
}

impl PhaseJobs {
    /// Polls the job in flight; when none is, starts the first phase without a reference
    /// at or after `next_phase` (if `wanted`) with `spawn`. `base` is the antialiased
    /// reference's request: each phase's is the same view at that phase.
    pub fn update(
        &mut self,
        base: &ReferenceRequest,
        next_phase: u32,
        wanted: bool,
        spawn: impl FnOnce(ReferenceRequest) -> ReferenceJob,
    ) {
        if let Some((phase, job)) = &mut self.job {
            let phase = *phase;
            match job.poll() {
                JobState::Starting | JobState::Rendering(_) => return,
                JobState::Failed(e) => self.failed = Some(format!("phase {phase}: {e}")),
                JobState::Cancelled => self.failed = Some(format!("phase {phase}: cancelled")),
                JobState::Done(_) => match self.job.take().map(|(_, j)| j.wait()) {
                    Some(Ok(reference)) => self.references.insert(phase, reference.image),
                    Some(Err(e)) => self.failed = Some(format!("phase {phase}: {e:#}")),
                    None => unreachable!("polled above"),
                },
            }
            self.job = None;
        }
        if !wanted || self.failed.is_some() {
            return;
        }
        if let Some(phase) = self.references.next_missing(next_phase) {
            self.job = Some((phase, spawn(base.clone().at_jitter_phase(phase))));
        }
    }

    pub fn status(&self) -> PhaseStatus {
        PhaseStatus {
            ready: self.references.ready(),
            rendering: self
                .job
                .as_ref()
                .and_then(|(phase, job)| Some((*phase, job.last_progress()?))),
            failed: self.failed.clone(),
        }
    }
}
