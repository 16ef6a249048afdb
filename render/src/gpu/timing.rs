//! GPU timestamp queries around each pass, when the adapter supports them. Results come
//! back through a `ReadbackRing`, so the viewer never waits on the GPU for them.

use std::collections::HashMap;

use super::readback::ReadbackRing;

const MAX_PASSES: u32 = 24;

/// Per-pass GPU milliseconds of one frame, in recording order.
pub type PassTimes = Vec<(&'static str, f64)>;

pub struct PassTimer {
    query_set: Option<wgpu::QuerySet>,
    resolve: wgpu::Buffer,
    ring: ReadbackRing,
    device: wgpu::Device,
    labels: Vec<&'static str>,
    in_flight: HashMap<u64, Vec<&'static str>>,
    /// Nanoseconds per timestamp tick.
    period: f64,
}

impl PassTimer {
    pub fn new(gpu: &super::Gpu) -> PassTimer {
        let size = (MAX_PASSES * 2) as u64 * 8;
        let query_set = gpu.timestamps.then(|| {
            gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: MAX_PASSES * 2,
            })
        });
        let resolve = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamp resolve"),
            size,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        PassTimer {
            query_set,
            resolve,
            ring: ReadbackRing::new(&gpu.device, size, 4, "timestamp readback"),
            device: gpu.device.clone(),
            labels: Vec::new(),
            in_flight: HashMap::new(),
            period: gpu.queue.get_timestamp_period() as f64,
        }
    }

    pub fn enabled(&self) -> bool {
        self.query_set.is_some()
    }

    fn allocate(&mut self, label: &'static str) -> Option<(&wgpu::QuerySet, u32)> {
        let qs = self.query_set.as_ref()?;
        if self.labels.len() as u32 >= MAX_PASSES {
            return None;
        }
        let index = self.labels.len() as u32 * 2;
        self.labels.push(label);
        Some((qs, index))
    }

    pub fn compute_writes(
        &mut self,
        label: &'static str,
    ) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        self.allocate(label)
            .map(|(qs, i)| wgpu::ComputePassTimestampWrites {
                query_set: qs,
                beginning_of_pass_write_index: Some(i),
                end_of_pass_write_index: Some(i + 1),
            })
    }

    pub fn render_writes(
        &mut self,
        label: &'static str,
    ) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        self.allocate(label)
            .map(|(qs, i)| wgpu::RenderPassTimestampWrites {
                query_set: qs,
                beginning_of_pass_write_index: Some(i),
                end_of_pass_write_index: Some(i + 1),
            })
    }

    /// Forgets the queries allocated since the last resolve (work that is not a frame).
    pub fn discard(&mut self) {
        self.labels.clear();
    }

    /// Resolves this frame's queries (tagged with the frame index) for later collection.
    pub fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder, frame: u64) {
        let labels = std::mem::take(&mut self.labels);
        let Some(qs) = &self.query_set else { return };
        if labels.is_empty() {
            return;
        }
        let count = labels.len() as u32 * 2;
        encoder.resolve_query_set(qs, 0..count, &self.resolve, 0);
        if self.ring.copy_from(
            &self.device,
            encoder,
            &self.resolve,
            count as u64 * 8,
            frame,
        ) {
            self.in_flight.insert(frame, labels);
        }
    }

    pub fn after_submit(&mut self) {
        self.ring.after_submit();
    }

    /// (frame, per-pass times) of every frame whose timings have arrived, oldest first.
    pub fn collect(&mut self) -> Vec<(u64, PassTimes)> {
        let period = self.period;
        self.ring
            .collect()
            .into_iter()
            .filter_map(|(frame, bytes)| {
                let labels = self.in_flight.remove(&frame)?;
                let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
                let times = labels
                    .iter()
                    .zip(ticks.chunks_exact(2))
                    .map(|(label, t)| (*label, t[1].saturating_sub(t[0]) as f64 * period * 1e-6))
                    .collect();
                Some((frame, times))
            })
            .collect()
    }

    pub fn in_flight(&self) -> bool {
        self.ring.in_flight()
    }
}

/// How a frame's passes are timed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimingMode {
    /// GPU timestamp queries around each pass (real GPUs).
    Timestamps,
    /// Each pass submitted alone and waited for, timed by the CPU clock. For CPU adapters
    /// (lavapipe), whose compute timestamps do not bracket the dispatch's execution: the
    /// numbers are then CPU times, meaningful as ratios within one run.
    WallClock,
    Off,
}

/// Records a frame's passes into command encoders and times them per `TimingMode`.
pub struct FrameRecorder<'a> {
    gpu: &'a super::Gpu,
    timer: &'a mut PassTimer,
    mode: TimingMode,
    encoder: Option<wgpu::CommandEncoder>,
    wall_times: PassTimes,
}

impl<'a> FrameRecorder<'a> {
    pub fn new(
        gpu: &'a super::Gpu,
        timer: &'a mut PassTimer,
        mode: TimingMode,
    ) -> FrameRecorder<'a> {
        FrameRecorder {
            gpu,
            timer,
            mode,
            encoder: Some(new_encoder(gpu)),
            wall_times: Vec::new(),
        }
    }

    /// The encoder for work that is not a timed pass (clears, copies).
    pub fn encoder(&mut self) -> &mut wgpu::CommandEncoder {
        self.encoder.get_or_insert_with(|| new_encoder(self.gpu))
    }

    /// Records one compute pass through `body`, timed.
    pub fn compute_pass(
        &mut self,
        label: &'static str,
        body: impl FnOnce(&mut wgpu::ComputePass<'_>),
    ) {
        let start = std::time::Instant::now();
        {
            let writes = match self.mode {
                TimingMode::Timestamps => self.timer.compute_writes(label),
                _ => None,
            };
            let encoder = self.encoder.get_or_insert_with(|| new_encoder(self.gpu));
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes: writes,
            });
            body(&mut pass);
        }
        self.finish_pass(label, start);
    }

    /// Records one render pass: `body` gets the encoder and the timestamp writes to use.
    pub fn render_pass(
        &mut self,
        label: &'static str,
        body: impl FnOnce(&mut wgpu::CommandEncoder, Option<wgpu::RenderPassTimestampWrites<'_>>),
    ) {
        let start = std::time::Instant::now();
        let writes = match self.mode {
            TimingMode::Timestamps => self.timer.render_writes(label),
            _ => None,
        };
        let encoder = self.encoder.get_or_insert_with(|| new_encoder(self.gpu));
        body(encoder, writes);
        self.finish_pass(label, start);
    }

    fn finish_pass(&mut self, label: &'static str, start: std::time::Instant) {
        if self.mode == TimingMode::WallClock {
            // Everything recorded so far (uploads, earlier passes) was already waited for,
            // so this measures the pass itself.
            let encoder = self.encoder.take().expect("encoder");
            self.gpu.queue.submit([encoder.finish()]);
            self.gpu.wait_idle();
            self.wall_times
                .push((label, start.elapsed().as_secs_f64() * 1e3));
        }
    }

    /// Submits what is left; returns the wall-clock times (empty unless `WallClock`).
    pub fn submit(
        mut self,
        frame: u64,
        extra: impl FnOnce(&mut wgpu::CommandEncoder),
    ) -> PassTimes {
        let mut encoder = self.encoder.take().unwrap_or_else(|| new_encoder(self.gpu));
        if self.mode == TimingMode::Timestamps {
            self.timer.resolve(&mut encoder, frame);
        } else {
            self.timer.discard();
        }
        extra(&mut encoder);
        self.gpu.queue.submit([encoder.finish()]);
        self.timer.after_submit();
        std::mem::take(&mut self.wall_times)
    }
}

fn new_encoder(gpu: &super::Gpu) -> wgpu::CommandEncoder {
    gpu.device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame"),
        })
}
