//! `bench-rays`: rays per second of each tracing backend the device has (docs/src/ray-tracing.md,
//! "Measured"), shadow and closest-hit rays apart, on one scene and view. One renderer per backend,
//! both on the same G-buffer; their dispatches alternate round by round, so a machine's changing
//! load falls on both alike and the ratio stays meaningful. Prints a Markdown table and writes
//! `rays.csv`; never a timing assertion.

use std::path::PathBuf;

use clap::Args;
use restir_render::renderer::{RayKind, RayRate};
use restir_render::settings::RayBackendChoice;
use restir_render::shader_constants::RAY_BENCH_RAYS_PER_PIXEL;
use restir_render::{Gpu, Mode, Renderer, load_scene};

use crate::bench::write::command_line;
use crate::cli::setup::{PipelineArgs, parse_size};

#[derive(Args, Debug)]
pub struct RayCostArgs {
    /// Scene: a glTF file or `builtin:NAME`.
    #[arg(long)]
    pub scene: String,
    #[arg(long, default_value = "160x100")]
    pub size: String,
    /// Timed dispatches per backend and ray kind (the median is reported).
    #[arg(long, default_value_t = 7)]
    pub dispatches: u32,
    /// Where `rays.csv` and `rays.md` go (printed only without it).
    #[arg(long)]
    pub out: Option<PathBuf>,
    #[command(flatten)]
    pub pipeline: PipelineArgs,
}

/// The backends this device can run.
fn backends(gpu: &Gpu) -> Vec<RayBackendChoice> {
    let mut b = vec![RayBackendChoice::Software];
    if gpu.ray_query {
        b.push(RayBackendChoice::RayQuery);
    } else {
        eprintln!(
            "note: {} has no hardware ray queries: measuring the software backend only",
            gpu.adapter_name()
        );
    }
    b
}

/// `bench-rays`, from its arguments and the words of its command line after the program
/// name (written to `--out`'s `command.txt`).
pub fn run(args: RayCostArgs, command: &[String]) -> anyhow::Result<()> {
    let (w, h) = parse_size(&args.size)?;
    let scene = load_scene(&args.scene)?;
    let gpu = Gpu::new_headless()?;
    let mut renderers = Vec::new();
    for choice in backends(&gpu) {
        let started = std::time::Instant::now();
        let mut settings = args.pipeline.settings(&[])?;
        settings.ray_backend = choice;
        settings.jitter = false;
        let mut r = Renderer::new(gpu.clone(), &scene, w, h, settings)?;
        r.set_seed(args.pipeline.seed);
        r.set_mode(Mode::Restir);
        r.force_effects(args.pipeline.effects()?);
        // The G-buffer the rays start from, and the pipelines compiled.
        r.render_frame()?;
        for kind in RayKind::ALL {
            r.bench_rays(kind, 1)?;
        }
        eprintln!(
            "{}: renderer, first frame and compiles in {:.1} s",
            r.last_ray_backend().map_or("?", |b| b.name()),
            started.elapsed().as_secs_f64()
        );
        renderers.push(r);
    }
    let mut rates: Vec<Option<RayRate>> = vec![None; renderers.len() * RayKind::ALL.len()];
    for round in 0..args.dispatches.max(1) {
        for (i, r) in renderers.iter_mut().enumerate() {
            for (k, kind) in RayKind::ALL.into_iter().enumerate() {
                let rate = r.bench_rays(kind, 1)?;
                let slot = &mut rates[i * RayKind::ALL.len() + k];
                match slot {
                    Some(s) => s.dispatch_ms.extend(rate.dispatch_ms),
                    None => *slot = Some(rate),
                }
            }
        }
        eprint!("\rround {}/{}", round + 1, args.dispatches.max(1));
    }
    eprintln!();
    let rates: Vec<RayRate> = rates.into_iter().flatten().collect();
    let table = markdown(&args, &gpu, &rates, (w, h));
    print!("{table}");
    if let Some(out) = &args.out {
        std::fs::create_dir_all(out)?;
        command_line::write(out, command)?;
        std::fs::write(out.join("rays.md"), &table)?;
        std::fs::write(out.join("rays.csv"), csv(&args, &gpu, &rates))?;
    }
    Ok(())
}

/// The software backend's rate of the same kind, for the ratio column.
fn software_rate(rates: &[RayRate], kind: RayKind) -> Option<f64> {
    rates
        .iter()
        .find(|r| r.kind == kind && r.backend == restir_render::tracing::RayBackend::Software)
        .map(RayRate::mrays_per_second)
}

fn markdown(args: &RayCostArgs, gpu: &Gpu, rates: &[RayRate], size: (u32, u32)) -> String {
    let mut md = format!(
        "Rays on `{}` at {}×{} ({} rays per surface pixel and dispatch, median of {} dispatches; \
         {}, {}{})\n\n",
        args.scene,
        size.0,
        size.1,
        RAY_BENCH_RAYS_PER_PIXEL,
        args.dispatches.max(1),
        gpu.adapter_name(),
        gpu.driver_info(),
        if gpu.is_cpu() {
            "; CPU adapter: wall-clock CPU times, compare ratios only"
        } else {
            ""
        }
    );
    md.push_str(
        "| backend | ray kind | rays per dispatch | hit | ms per dispatch | Mrays/s | × software |\n",
    );
    md.push_str("| --- | --- | --- | --- | --- | --- | --- |\n");
    for r in rates {
        let vs = software_rate(rates, r.kind).map_or("n/a".into(), |s| {
            format!("{:.2}×", r.mrays_per_second() / s)
        });
        md.push_str(&format!(
            "| {} | {} | {} | {:.0} % | {:.2} | {:.2} | {vs} |\n",
            r.backend.name(),
            r.kind.name(),
            r.rays,
            100.0 * r.hits as f64 / r.rays.max(1) as f64,
            r.median_ms(),
            r.mrays_per_second(),
        ));
    }
    md
}

fn csv(args: &RayCostArgs, gpu: &Gpu, rates: &[RayRate]) -> String {
    let mut out = String::from(
        "scene,size,backend,ray_kind,rays_per_dispatch,hits,median_ms,mrays_per_second,dispatches,device,timing\n",
    );
    let timing = if gpu.is_cpu() {
        "cpu-wall-clock"
    } else {
        "gpu-wall-clock"
    };
    for r in rates {
        out.push_str(&format!(
            "{},{},{},{},{},{},{:.4},{:.4},{},\"{}, {}\",{timing}\n",
            args.scene,
            args.size,
            r.backend.name(),
            r.kind.name(),
            r.rays,
            r.hits,
            r.median_ms(),
            r.mrays_per_second(),
            r.dispatch_ms.len(),
            gpu.adapter_name(),
            gpu.driver_info(),
        ));
    }
    out
}
