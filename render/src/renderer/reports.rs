//! Bringing each frame's report together: counters, pass times and the inspected pixel
//! come back through separate readbacks and are matched by frame index.

use super::Renderer;
use crate::stats::{FrameCounters, FrameReport};

impl Renderer {
    /// Reports (counters and pass timings) of frames whose readbacks have arrived.
    /// With `wait`, blocks until every submitted frame's report is in.
    pub fn collect_reports(&mut self, wait: bool) -> Vec<FrameReport> {
        if wait {
            self.gpu.wait_idle();
        } else {
            let _ = self.gpu.device.poll(wgpu::PollType::Poll);
        }
        for (frame, bytes) in self.stats_ring.collect() {
            self.pending_counters
                .insert(frame, FrameCounters(bytemuck::pod_collect_to_vec(&bytes)));
        }
        self.pending_times.extend(self.timer.collect());
        for (frame, bytes) in self.inspect_ring.collect() {
            if let Some(pending) = self.pending_inspections.remove(&frame) {
                let scene = &self.scene;
                if let Some(i) = pending.finish(
                    frame,
                    &bytes,
                    |light, uv| scene.sample_point(light, uv),
                    |light, uv| scene.environment_direction(light, uv),
                ) {
                    self.arrived_inspections.insert(frame, i);
                }
            }
        }
        // Counters, timings and the inspection of a frame travel in the same submission
        // but come back separately: a report is complete when all are in (timings only
        // when timestamps are on).
        let mut ready: Vec<u64> = self
            .pending_counters
            .keys()
            .copied()
            .filter(|f| !self.timer.enabled() || wait || self.pending_times.contains_key(f))
            .filter(|f| !self.pending_inspections.contains_key(f))
            .collect();
        ready.sort_unstable();
        let reports = ready
            .into_iter()
            .map(|frame| FrameReport {
                frame,
                counters: self.pending_counters.remove(&frame).unwrap_or_default(),
                pass_ms: self.pending_times.remove(&frame).unwrap_or_default(),
                inspection: self.arrived_inspections.remove(&frame),
            })
            .collect();
        // Timings whose counters were dropped (ring full) would otherwise pile up.
        let oldest = self.frame_index.saturating_sub(16);
        self.pending_times.retain(|f, _| *f >= oldest);
        self.pending_inspections.retain(|f, _| *f >= oldest);
        self.arrived_inspections.retain(|f, _| *f >= oldest);
        reports
    }
}
