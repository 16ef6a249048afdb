//! Compiling a frame plan's pipelines: the ones a variant lacks, on as many threads as the
//! machine has (a CPU driver such as lavapipe compiles on the calling thread, and a scene's
//! first frame can need twenty pipelines), each timed. wgpu's error scopes are per thread,
//! so every worker checks its own pipelines.

use std::collections::BTreeSet;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use super::PipelineVariant;
use crate::gpu::{Gpu, GpuError};
use crate::load_phases::{LoadEvent, Phase, Watcher};
use crate::passes::gbuffer::RasterPass;
use crate::passes::pass::Dispatch;
use crate::passes::{ComputePass, PassDef, PassLayouts};

/// One compiled pipeline, how long its creation took and how long its first dispatch took.
/// A CPU driver (lavapipe) compiles a compute shader when it is first dispatched, not when
/// the pipeline is created, so on such a driver `first_dispatch_ms` less the pass's usual
/// time is the compile (docs/src/compile-time.md); other drivers compile in `ms`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PipelineCompile {
    pub pass: &'static str,
    /// The variant: its defines, comma-separated (the effect set and the ray backend).
    pub variant: String,
    /// Pipeline creation.
    pub ms: f64,
    /// The pass's first dispatch with this pipeline, submitted alone and waited for
    /// (`None` until it has run). The G-buffer raster's draw counts as its dispatch.
    pub first_dispatch_ms: Option<f64>,
}

/// A worker's result: the pass, its pipeline (or why not) and the compile's milliseconds.
type Finished = (&'static PassDef, Result<Compiled, GpuError>, f64);

enum Compiled {
    Raster(RasterPass),
    Compute(ComputePass),
}

/// The passes of `plan` that `variant` has not compiled, each once.
pub(super) fn missing(
    variant: &PipelineVariant,
    plan: impl IntoIterator<Item = &'static PassDef>,
) -> Vec<&'static PassDef> {
    let mut out: Vec<&'static PassDef> = Vec::new();
    for pass in plan {
        let have = if pass.dispatch == Dispatch::Raster {
            variant.raster.is_some()
        } else {
            variant.passes.contains_key(pass.name)
        };
        if !have && !out.iter().any(|p| p.name == pass.name) {
            out.push(pass);
        }
    }
    out
}

/// Compiles `passes` into `variant` on up to `available_parallelism` threads, telling
/// `watch` as each finishes; returns each compile's time, in the order they finished.
pub(super) fn compile_all(
    gpu: &Gpu,
    layouts: &PassLayouts,
    defines: &BTreeSet<String>,
    variant: &mut PipelineVariant,
    passes: &[&'static PassDef],
    watch: Watcher,
) -> Result<Vec<PipelineCompile>, GpuError> {
    if passes.is_empty() {
        return Ok(Vec::new());
    }
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(passes.len());
    let next = AtomicUsize::new(0);
    let done: Mutex<Vec<Finished>> = Mutex::new(Vec::new());
    let compile = |pass: &'static PassDef| {
        let start = Instant::now();
        let compiled = if pass.dispatch == Dispatch::Raster {
            RasterPass::new(gpu, layouts, defines).map(Compiled::Raster)
        } else {
            ComputePass::new(gpu, layouts, pass, defines).map(Compiled::Compute)
        };
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let mut done = done.lock().expect("no compile panics holding it");
        done.push((pass, compiled, ms));
        watch(LoadEvent::Progress {
            phase: "pipelines",
            done: done.len(),
            total: passes.len(),
        });
    };
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                while let Some(&pass) = passes.get(next.fetch_add(1, Ordering::Relaxed)) {
                    compile(pass);
                }
            });
        }
    });
    let variant_key = defines.iter().cloned().collect::<Vec<_>>().join(",");
    let mut times = Vec::new();
    for (pass, compiled, ms) in done.into_inner().expect("no compile panics holding it") {
        match compiled? {
            Compiled::Raster(r) => variant.raster = Some(r),
            Compiled::Compute(c) => {
                variant.passes.insert(pass.name, c);
            }
        }
        log::info!("compiled {} in {ms:.0} ms", pass.name);
        times.push(PipelineCompile {
            pass: pass.name,
            variant: variant_key.clone(),
            ms,
            first_dispatch_ms: None,
        });
    }
    Ok(times)
}

/// The first frame's compiles as the load phase "pipelines": their wall time (`wall_ms`,
/// shorter than the sum when threads overlap) and the slowest.
pub(super) fn phase(batch: &[PipelineCompile], wall_ms: f64) -> Phase {
    let sum: f64 = batch.iter().map(|c| c.ms).sum();
    let slowest = batch
        .iter()
        .max_by(|a, b| a.ms.total_cmp(&b.ms))
        .map_or_else(String::new, |c| {
            format!(", slowest {} {:.0} ms", c.pass, c.ms)
        });
    Phase {
        name: "pipelines",
        ms: wall_ms,
        detail: format!(
            "{} compiled, {:.0} ms of compile over the threads{slowest}",
            batch.len(),
            sum
        ),
    }
}

/// Whether some pipeline of `variant` that `plan` dispatches has not been dispatched yet:
/// that frame is timed pass by pass (`TimingMode::WallClock`) so its first dispatches can
/// be told apart.
pub(super) fn awaits_first_dispatch<'a>(
    compiles: &[PipelineCompile],
    variant: &str,
    mut plan: impl Iterator<Item = &'a str>,
) -> bool {
    plan.any(|pass| {
        compiles
            .iter()
            .any(|c| c.pass == pass && c.variant == variant && c.first_dispatch_ms.is_none())
    })
}

/// Records each pass's first dispatch from a frame timed pass by pass (`times`, in
/// recording order; a pass repeated in the frame counts its first run).
pub(super) fn record_first_dispatches(
    compiles: &mut [PipelineCompile],
    variant: &str,
    times: &[(&'static str, f64)],
) {
    for (pass, ms) in times {
        if let Some(c) = compiles
            .iter_mut()
            .find(|c| c.pass == *pass && c.variant == variant && c.first_dispatch_ms.is_none())
        {
            c.first_dispatch_ms = Some(*ms);
        }
    }
}
