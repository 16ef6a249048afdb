//! Rays per second of the tracing backend the settings select (`restir-viewer bench-rays`):
//! after a frame has filled the G-buffer, the ray-bench pass (ray_bench.wgsl) traces
//! RAY_BENCH_RAYS_PER_PIXEL shadow or closest-hit rays from every surface, each dispatch
//! submitted alone and waited for (the wall clock: on a CPU adapter the only honest clock,
//! on a GPU it adds the submission's fixed cost, small against a full-size dispatch).

use super::Renderer;
use super::frame_plan::Step;
use super::resolve::resolve;
use crate::gpu::GpuError;
use crate::gpu::readback::read_buffer;
use crate::gpu::timing::{FrameRecorder, TimingMode};
use crate::passes::PASS_INFO_STRIDE;
use crate::passes::ray_bench::{PASS, RAY_COUNTS};
use crate::shader_constants::{RAY_BENCH_CLOSEST, RAY_BENCH_SHADOW};
use crate::tracing::RayBackend;

/// Which rays the bench traces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RayKind {
    /// Toward power-sampled light points, any hit, through transparent layers.
    Shadow,
    /// Along cosine-distributed directions, the nearest hit.
    Closest,
}

impl RayKind {
    pub const ALL: [RayKind; 2] = [RayKind::Shadow, RayKind::Closest];

    pub fn name(self) -> &'static str {
        match self {
            RayKind::Shadow => "shadow",
            RayKind::Closest => "closest-hit",
        }
    }

    fn slot(self) -> u32 {
        match self {
            RayKind::Shadow => RAY_BENCH_SHADOW,
            RayKind::Closest => RAY_BENCH_CLOSEST,
        }
    }
}

/// One measurement: `rays` rays in each of the timed dispatches.
#[derive(Clone, Debug, serde::Serialize)]
pub struct RayRate {
    pub backend: RayBackend,
    pub kind: RayKind,
    /// Rays per dispatch (surface pixels × rays per pixel).
    pub rays: u64,
    /// Rays of the last dispatch that hit something (occluded shadow rays; closest-hit
    /// rays that found a surface).
    pub hits: u64,
    /// Wall-clock milliseconds of each dispatch.
    pub dispatch_ms: Vec<f64>,
}

impl RayRate {
    pub fn median_ms(&self) -> f64 {
        let mut v = self.dispatch_ms.clone();
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    }

    /// Millions of rays per second over the median dispatch.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays as f64 / (self.median_ms() * 1e3)
    }
}

impl Renderer {
    /// Traces `kind` rays from the last frame's surfaces `dispatches` times with the last
    /// frame's pipeline variant (its backend and effects). Render a frame first.
    pub fn bench_rays(&mut self, kind: RayKind, dispatches: u32) -> Result<RayRate, GpuError> {
        let Some(active) = self.pipelines.last_effects.clone() else {
            return Err(GpuError::Validation(
                "bench_rays needs a rendered frame (its G-buffer)".into(),
            ));
        };
        let slot = kind.slot();
        let plan = [Step {
            pass: &PASS,
            slots: slot..slot + 1,
            inspect: None,
            threads: None,
        }];
        let variant = self
            .pipelines
            .variants
            .entry(active.key.clone())
            .or_default();
        variant.compile(&self.gpu, &self.layouts, &active.defines, &PASS)?;
        let resolved = resolve(&plan, &self.history.carried, false, false);
        self.targets.ensure(&self.gpu, &resolved.needs);
        let uniforms = self.buffers.uniforms();
        let group = self.bind_groups.get(
            &self.gpu,
            &self.layouts,
            &self.targets,
            &uniforms,
            &PASS,
            &resolved.steps[0].bound,
        );
        let scene_group = self.scene.bind_group(active.backend).clone();
        let pass = &self.pipelines.variants[&active.key].passes[PASS.name];
        self.gpu.wait_idle();
        let mut dispatch_ms = Vec::new();
        for _ in 0..dispatches.max(1) {
            let mut rec =
                FrameRecorder::new(&self.gpu, &mut self.readbacks.timer, TimingMode::WallClock);
            pass.record(
                &mut rec,
                [&self.buffers.frame_bind_group, &scene_group, &group],
                &[slot * PASS_INFO_STRIDE],
                (self.targets.width, self.targets.height),
                None,
            );
            dispatch_ms.extend(rec.submit(self.frame_index, |_| {}).iter().map(|t| t.1));
        }
        self.gpu.check()?;
        let counts: Vec<u32> = read_buffer(
            &self.gpu,
            self.targets.pixels(&RAY_COUNTS),
            0,
            self.targets.pixel_count() * 4,
        );
        let rays = counts.iter().map(|c| (c & 0xffff) as u64).sum();
        let hits = counts.iter().map(|c| (c >> 16) as u64).sum();
        Ok(RayRate {
            backend: active.backend,
            kind,
            rays,
            hits,
            dispatch_ms,
        })
    }
}
