//! The GPU side of the accuracy measurement: follows the view, gets its reference with a
//! background `ReferenceJob` (cached on disk), uploads it for the error view, and scores
//! displayed frames against it with `SequenceMetrics`. With jitter on, each frame's
//! per-frame error is measured against its jitter phase's reference instead (`phases.rs`;
//! docs/src/viewer.md, "Accuracy with jitter on"). Owned by the viewer's frame loop, never
//! by the UI; it writes what the panel shows into `AccuracyState`.

use std::sync::Arc;
use std::time::{Duration, Instant};

use restir_render::LinearImage;
use restir_render::metrics::{SequenceMetrics, luma_rmse};
use restir_render::phase_references::reference_for_frame;
use restir_render::reference_cache::{
    JobState, Reference, ReferenceCache, ReferenceJob, ReferenceRequest,
};
use restir_render::renderer::jitter_phase;
use restir_render::{Camera, Gpu, Renderer, Scene};

use super::phases::PhaseJobs;
use super::side_scores::{References, Score, SideScores};
use super::{AccuracyState, Config, CurvePoint, ReferenceInfo, ReferenceStatus};

/// The scene the renderer shows, as a reference job needs it.
pub struct SceneSource<'a> {
    /// `builtin:NAME` or the file it was loaded from (part of the cache key).
    pub spec: &'a str,
    pub scene: &'a Arc<Scene>,
}

/// What the reference depends on that the viewer can change.
#[derive(Clone, Debug, PartialEq)]
struct ViewKey {
    scene: String,
    camera: Camera,
    size: (u32, u32),
    jitter: bool,
    spp: u32,
    /// The reference follows `max_bounces` (1: direct light only).
    max_bounces: u32,
}

impl ViewKey {
    /// The same image: curves measured against either reference stay comparable.
    fn same_image(&self, other: &ViewKey) -> bool {
        (&self.scene, self.camera, self.size) == (&other.scene, other.camera, other.size)
    }
}

/// Keeps measuring to about a quarter of the viewer's time: after a measurement that
/// took `c`, the next waits `3c`. On lavapipe at the default render size a measurement
/// takes a few ms against frames of ~100 ms, so every frame is measured; on a GPU at
/// 1080p a 33 MB readback plus metrics over 2 Mpixels (tens of ms) would otherwise cut
/// the frame rate several times over.
#[derive(Clone, Copy, Debug, Default)]
pub struct Throttle {
    next: Option<Instant>,
}

impl Throttle {
    /// The share of wall time measuring may take.
    const SHARE: f64 = 0.25;

    pub fn due(&self, now: Instant) -> bool {
        self.next.is_none_or(|t| now >= t)
    }

    pub fn measured(&mut self, end: Instant, cost: Duration) {
        self.next = Some(end + cost.mul_f64((1.0 - Self::SHARE) / Self::SHARE));
    }
}

pub struct AccuracyTracker {
    cache: ReferenceCache,
    /// How long the view must stay unchanged before a reference starts (a fly-through
    /// would otherwise start and cancel a job every frame).
    settle: Duration,
    /// A second device on the viewer's adapter for the reference jobs. Sharing the
    /// viewer's, each viewer pass (timed by waiting for the device on CPU adapters) waits
    /// for the reference frame in flight: on lavapipe (2 cores, `builtin:many-lights`)
    /// the viewer drew 3 frames in 25 s that way, 10 with a device of its own.
    device: Option<Gpu>,
    view: Option<ViewKey>,
    view_since: Instant,
    job: Option<ReferenceJob>,
    reference: Option<LinearImage>,
    /// The metrics of the current curve (its id) against `reference`.
    metrics: Option<(u64, SequenceMetrics)>,
    throttle: Throttle,
    last_measured: Option<u64>,
    /// Whether the renderer holds an uploaded reference (to clear when it goes stale).
    uploaded: bool,
    /// With jitter on: the jitter phases' references, rendered after `reference`.
    phases: PhaseJobs,
    /// The split screen's and the tour's numbers per side.
    sides: SideScores,
}

impl AccuracyTracker {
    /// Half a second of stillness: longer than a pause between key presses while flying.
    pub const SETTLE: Duration = Duration::from_millis(500);

    pub fn new(cache: ReferenceCache, settle: Duration) -> AccuracyTracker {
        AccuracyTracker {
            cache,
            settle,
            device: None,
            view: None,
            view_since: Instant::now(),
            job: None,
            reference: None,
            metrics: None,
            throttle: Throttle::default(),
            last_measured: None,
            uploaded: false,
            phases: PhaseJobs::default(),
            sides: SideScores::default(),
        }
    }

    /// Every redraw: follows the view, starts the reference job once the view is still
    /// (if `wanted`), polls it and uploads its image when it arrives.
    pub fn update(
        &mut self,
        renderer: &mut Renderer,
        scene: &SceneSource,
        state: &mut AccuracyState,
        wanted: bool,
    ) {
        let now = Instant::now();
        let key = ViewKey {
            scene: scene.spec.to_string(),
            camera: renderer.camera(),
            size: renderer.size(),
            jitter: renderer.settings().jitter,
            spp: state.reference_spp,
            max_bounces: renderer.settings().reference_bounces(),
        };
        if self.view.as_ref() != Some(&key) {
            self.view_changed(renderer, state, key, now);
        }
        if self.reference.is_some() {
            if self.view.as_ref().is_some_and(|v| v.jitter) {
                self.update_phases(
                    renderer.gpu(),
                    scene,
                    jitter_phase(renderer.frame_index()),
                    wanted,
                );
                state.phases = Some(self.phases.status());
            }
            return;
        }
        let Some(job) = &mut self.job else {
            state.reference = if !wanted {
                ReferenceStatus::Idle
            } else if now - self.view_since < self.settle {
                ReferenceStatus::WaitingForStill
            } else {
                let request = self.request(scene);
                self.job = Some(self.spawn(renderer.gpu(), scene, request));
                ReferenceStatus::Starting
            };
            return;
        };
        state.reference = match job.poll() {
            JobState::Starting => ReferenceStatus::Starting,
            JobState::Rendering(p) => ReferenceStatus::Rendering(*p),
            // The failed job stays, so it is not retried every frame; a view change does.
            JobState::Failed(e) => ReferenceStatus::Failed(e.clone()),
            JobState::Cancelled => ReferenceStatus::Failed("cancelled".into()),
            JobState::Done(_) => match self.job.take().map(ReferenceJob::wait) {
                Some(Ok(reference)) => self.accept(renderer, reference),
                Some(Err(e)) => ReferenceStatus::Failed(format!("{e:#}")),
                None => unreachable!("polled above"),
            },
        };
    }

    /// The live numbers of side `side` (0: A, 1: B) rendered by `renderer`: per-frame luma
    /// RMSE and signed bias of a recent frame (see `side_scores.rs`).
    pub fn side_score(&mut self, side: usize, renderer: &Renderer) -> Option<Score> {
        let (Some(plain), Some(view)) = (&self.reference, &self.view) else {
            self.sides.clear();
            return None;
        };
        let references = References {
            plain,
            phases: &self.phases.references,
            jitter: view.jitter,
        };
        self.sides
            .update(side, renderer, &references, Instant::now())
    }

    /// The reference's luminance at `pixel` (the pixel history's reference line).
    pub fn reference_luminance(&self, pixel: (u32, u32)) -> Option<f32> {
        let reference = self.reference.as_ref()?;
        (pixel.0 < reference.width && pixel.1 < reference.height)
            .then(|| reference.luminance_at(pixel.0, pixel.1))
    }

    /// After a rendered frame: scores it against the reference when the panel is open
    /// and the throttle allows (or `every_frame`).
    pub fn measure(&mut self, renderer: &Renderer, state: &mut AccuracyState) {
        let start = Instant::now();
        let Some(reference) = &self.reference else {
            return;
        };
        // `render_frame` has moved the index past the frame just rendered.
        let frame = renderer.frame_index().saturating_sub(1);
        let jitter = renderer.settings().jitter;
        // With jitter on a frame is measured against its phase's reference (None until it
        // is rendered): docs/src/viewer.md, "Accuracy with jitter on".
        let own = reference_for_frame(jitter, frame, reference, &self.phases.references);
        let due = state.every_frame || self.throttle.due(start);
        // A frame whose phase has its reference is always scored: while few phases have
        // one, the throttle would otherwise rarely meet them.
        if !state.panel_open || !(due || (jitter && own.is_some())) {
            return;
        }
        let config = Config {
            mode: renderer.mode(),
            settings: renderer.settings().clone(),
        };
        let id = state.curves.curve_for(&config, frame);
        if self.metrics.as_ref().is_none_or(|(m, _)| *m != id) {
            self.metrics = Some((id, SequenceMetrics::new(reference.clone())));
        }
        let Some((_, metrics)) = &mut self.metrics else {
            unreachable!("set above")
        };
        let image = renderer.read_radiance();
        // The accumulated figures average the throttled frames, whatever their phase.
        if due && let Err(e) = metrics.push(&image) {
            // Cannot happen while the view key holds the size; never worth a panic.
            log::warn!("accuracy: {e}");
            return;
        }
        let report = metrics.report();
        let per_frame = match own {
            Some(own) if jitter => luma_rmse(&image, own).ok(),
            Some(_) => report.per_frame_luma_rmse.last().copied(),
            None => None,
        };
        // No point before the accumulated figures have a frame, nor for a frame whose
        // phase has no reference yet (its error would be mostly the pixel footprint).
        let (Some(per_frame_rmse), true) = (per_frame, report.frames > 0) else {
            return;
        };
        let first = state
            .curves
            .current
            .as_ref()
            .map_or(frame, |c| c.first_frame);
        state.curves.push(CurvePoint {
            x: frame - first + 1,
            frame,
            luma_rmse: per_frame_rmse,
            stability: report
                .per_frame_stability_rmse
                .last()
                .copied()
                .filter(|_| due),
            accumulated_rgb_rmse: report.accumulated_rgb_rmse,
            luma_ratio: report.accumulated_luma_ratio,
            signed_bias: report.mean_signed_bias,
            pass_ms: Vec::new(),
        });
        let end = Instant::now();
        self.throttle.measured(end, end - start);
        state.measure_ms = Some((end - start).as_secs_f64() * 1e3);
        state.frames_skipped = self
            .last_measured
            .map_or(0, |last| frame.saturating_sub(last + 1));
        self.last_measured = Some(frame);
    }

    /// A new view: the job and reference go; curves of another image are dropped, those
    /// of the same image (new spp, jitter or bounces) kept for comparison.
    fn view_changed(
        &mut self,
        renderer: &mut Renderer,
        state: &mut AccuracyState,
        key: ViewKey,
        now: Instant,
    ) {
        match &self.view {
            Some(old) if old.same_image(&key) => state.curves.end_current(Some("new reference")),
            _ => state.curves.clear(),
        }
        // Dropping a job cancels it after the frame it is rendering.
        self.job = None;
        self.reference = None;
        self.metrics = None;
        self.last_measured = None;
        self.phases = PhaseJobs::default();
        self.sides.clear();
        state.phases = None;
        if std::mem::take(&mut self.uploaded) {
            // A stale reference would draw a plausible but wrong heatmap; black makes the
            // error view show |frame| until the new reference arrives (its legend says so).
            let (w, h) = renderer.size();
            let _ = renderer.set_reference_image(&LinearImage::new(w, h), 0.0);
        }
        self.view = Some(key);
        self.view_since = now;
    }

    /// The request of the current view's (antialiased, with jitter on) reference.
    fn request(&self, scene: &SceneSource) -> ReferenceRequest {
        let key = self.view.as_ref().expect("set by update");
        ReferenceRequest::new(
            scene.spec,
            scene.scene,
            key.camera,
            key.size,
            key.spp,
            key.jitter,
        )
        .with_max_bounces(key.max_bounces)
    }

    /// Polls the jitter phase in flight and starts the next, from `next_phase` (the phase
    /// of the frame about to be rendered).
    fn update_phases(&mut self, gpu: &Gpu, scene: &SceneSource, next_phase: u32, wanted: bool) {
        let base = self.request(scene);
        let mut phases = std::mem::take(&mut self.phases);
        phases.update(&base, next_phase, wanted, |request| {
            self.spawn(gpu, scene, request)
        });
        self.phases = phases;
    }

    fn spawn(&mut self, gpu: &Gpu, scene: &SceneSource, request: ReferenceRequest) -> ReferenceJob {
        let device = self
            .device
            .get_or_insert_with(|| {
                Gpu::from_adapter(gpu.instance.clone(), gpu.adapter.clone()).unwrap_or_else(|e| {
                    log::warn!(
                        "accuracy: no second device ({e}); the reference shares the viewer's"
                    );
                    gpu.clone()
                })
            })
            .clone();
        ReferenceJob::spawn(self.cache.clone(), request, device, scene.scene.clone())
    }

    fn accept(&mut self, renderer: &mut Renderer, reference: Reference) -> ReferenceStatus {
        let noise = reference.meta.noise_luma_rmse.unwrap_or(0.0) as f32;
        if let Err(e) = renderer.set_reference_image(&reference.image, noise) {
            return ReferenceStatus::Failed(format!("{e:#}"));
        }
        self.uploaded = true;
        let info = ReferenceInfo {
            meta: reference.meta,
            from_cache: reference.from_cache,
            path: reference.path,
        };
        self.reference = Some(reference.image);
        ReferenceStatus::Ready(info)
    }
}

#[cfg(test)]
mod throttle_tests {
    use super::*;

    #[test]
    fn measuring_keeps_to_a_quarter_of_the_time() {
        let mut t = Throttle::default();
        let now = Instant::now();
        assert!(t.due(now));
        t.measured(now, Duration::from_millis(10));
        assert!(!t.due(now + Duration::from_millis(29)));
        assert!(t.due(now + Duration::from_millis(30)));
    }
}
