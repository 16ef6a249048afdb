//! Bringing each frame's report together: counters, pass times and the inspected pixel
//! come back through separate readbacks and are matched by frame index.

use super::Renderer;
use super::stats::{FrameCounters, FrameReport};

impl Renderer {
    /// Reports (counters and pass timings) of frames whose readbacks have arrived.
    /// With `wait`, blocks until every submitted frame's report is in.
    pub fn collect_reports(&mut self, wait: bool) -> Vec<FrameReport> {
        if wait {
            self.gpu.wait_idle();
        } else {
            let _ = self.gpu.device.poll(wgpu::PollType::Poll);
        }
        for (frame, bytes) in self.readbacks.stats_ring.collect() {
            self.readbacks
                .pending_counters
                .insert(frame, FrameCounters(bytemuck::pod_collect_to_vec(&bytes)));
        }
        self.readbacks
            .pending_times
            .extend(self.readbacks.timer.collect());
        for (frame, bytes) in self.readbacks.inspect_ring.collect() {
            if let Some(pending) = self.readbacks.pending_inspections.remove(&frame) {
                let scene = &self.scene;
                if let Some(i) = pending.finish(
                    frame,
                    &bytes,
                    |light, uv| scene.sample_point(light, uv),
                    |light, uv| scene.environment_direction(light, uv),
                ) {
                    let mut i = i;
                    i.light_pdfs = i.stages.last().and_then(|stage| {
                        let light = stage.reservoir.light;
                        (light != crate::gpu_types::NO_LIGHT).then(|| {
                            self.buffers.light_sampler.selection_pdfs(
                                scene,
                                light,
                                glam::Vec3::from(i.surface.position),
                                crate::denoise::model::oct_decode(i.surface.normal),
                            )
                        })
                    });
                    self.readbacks.arrived_inspections.insert(frame, i);
                }
            }
        }
        // Counters, timings and the inspection of a frame travel in the same submission
        // but come back separately: a report is complete when all are in (timings only
        // when timestamps are on).
        let mut ready: Vec<u64> = self
            .readbacks
            .pending_counters
            .keys()
            .copied()
            .filter(|f| {
                !self.readbacks.timer.enabled()
                    || wait
                    || self.readbacks.pending_times.contains_key(f)
            })
            .filter(|f| !self.readbacks.pending_inspections.contains_key(f))
            .collect();
        ready.sort_unstable();
        let reports = ready
            .into_iter()
            .map(|frame| FrameReport {
                frame,
                counters: self
                    .readbacks
                    .pending_counters
                    .remove(&frame)
                    .unwrap_or_default(),
                pass_ms: self
                    .readbacks
                    .pending_times
                    .remove(&frame)
                    .unwrap_or_default(),
                inspection: self.readbacks.arrived_inspections.remove(&frame),
            })
            .collect();
        // Timings whose counters were dropped (ring full) would otherwise pile up.
        let oldest = self.frame_index.saturating_sub(16);
        self.readbacks.pending_times.retain(|f, _| *f >= oldest);
        self.readbacks
            .pending_inspections
            .retain(|f, _| *f >= oldest);
        self.readbacks
            .arrived_inspections
            .retain(|f, _| *f >= oldest);
        reports
    }
}
