//! `bench-load FILE`: how long each phase from file to first frame takes
//! (docs/src/load-time.md, "The phases"): the
//! loader's (read, buffers, images, geometry), the upload's (BVH, light table, GPU
//! buffers, acceleration structures) and the first frame's pipelines. Prints the phases as
//! they finish, then a Markdown table; `--csv` writes them; `--prepare` loads as the
//! viewer does (pipelines warmed on a second device first). Never a timing assertion.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use restir_render::gpu::timing::TimingMode;
use restir_render::load_phases::{LoadEvent, LoadPhases, phase_line};
use restir_render::{Gpu, Renderer, load_scene_watched};

use super::compile_table;

use crate::cli::setup::{parse_size, settings_from};

#[derive(Args, Debug)]
pub struct LoadCostArgs {
    /// The scene: a .gltf/.glb file or builtin:NAME.
    pub scene: String,
    /// Size of the first frame, WxH.
    #[arg(long, default_value = "160x120")]
    pub size: String,
    /// Pipeline parameters, NAME=VALUE (as `render --set`).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Load as the viewer does: upload, then warm the first frames' pipelines on a second
    /// device (`warm-up`), then the first frame on the renderer's own device.
    #[arg(long)]
    pub prepare: bool,
    /// Also write the phases as CSV here.
    #[arg(long, value_name = "FILE.csv")]
    pub csv: Option<PathBuf>,
    /// Also write the compile table (by pass and effect set) as CSV here.
    #[arg(long, value_name = "FILE.csv")]
    pub compile_csv: Option<PathBuf>,
    /// Frames rendered after the first (at least 3): each pass's steady time, their median,
    /// which the compile table subtracts from its first dispatch.
    #[arg(long, default_value_t = 3)]
    pub frames: u32,
}

pub fn run(args: LoadCostArgs) -> anyhow::Result<()> {
    let size = parse_size(&args.size)?;
    let settings = settings_from(None, &args.set)?;
    let started = Instant::now();
    let print = |e: LoadEvent| print_event(&e);
    let scene = load_scene_watched(&args.scene, &print)?;
    let gpu = Gpu::new_headless()?;
    let device_ms = started.elapsed().as_secs_f64() * 1e3;
    let mut renderer = Renderer::new(gpu.clone(), &scene, size.0, size.1, settings)?;
    if args.prepare {
        // The viewer's path (the upload is repeated: `Renderer::new` needs a scene).
        let prepared = renderer.preparer().prepare(&scene, &print)?;
        renderer.set_prepared_scene(prepared);
    } else {
        for p in &renderer.scene_info().load.phases[scene.load_phases.phases.len()..] {
            eprintln!("{}", phase_line(p));
        }
    }
    renderer.set_compile_watcher(Some(std::sync::Arc::new(|e| print_event(&e))));
    renderer.render_frame()?;
    // Read back: the frame has finished on the device.
    let image = renderer.read_radiance();
    anyhow::ensure!(
        image.non_finite_count() == 0,
        "the first frame has NaN/inf pixels"
    );
    let first_frame_s = started.elapsed().as_secs_f64();
    let phases = renderer.load_phases();
    for name in ["pipelines", "first frame"] {
        if let Some(p) = phases.get(name) {
            eprintln!("{}", phase_line(p));
        }
    }
    print!("{}", markdown(&args.scene, &gpu, &phases, first_frame_s));
    println!(
        "(wall clock from the start, device creation included ({device_ms:.0} ms with the \
         load); lavapipe and most GPU drivers keep compiled shaders in an on-disk cache, so \
         a second run compiles less)"
    );
    if let Some(path) = &args.csv {
        std::fs::write(path, csv(&args.scene, &phases))?;
        eprintln!("wrote {}", path.display());
    }

    // Steady pass times, timed as the first frame was (one pass per submission), on still
    // frames. A pass first dispatched on a later frame (one that needs history) is in its
    // median once among `frames`, so the median stays a compiled dispatch.
    renderer.set_timing_mode(TimingMode::WallClock);
    let mut frames = Vec::new();
    for _ in 0..args.frames.max(3) {
        renderer.render_frame()?;
        frames.extend(renderer.collect_reports(true));
    }
    let steady: Vec<_> = frames.into_iter().map(|f| f.pass_ms).collect();
    let rows = compile_table::rows(renderer.pipeline_compiles(), &steady);
    print!("{}", compile_table::markdown(&rows));
    if let Some(path) = &args.compile_csv {
        std::fs::write(path, compile_table::csv(&args.scene, &rows))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn print_event(e: &LoadEvent) {
    match e {
        LoadEvent::Started(name) => eprintln!("{name}…"),
        LoadEvent::Progress { phase, done, total } => eprintln!("  {phase} {done}/{total}"),
        LoadEvent::Finished(p) => eprintln!("{}", phase_line(p)),
    }
}

fn markdown(scene: &str, gpu: &Gpu, phases: &LoadPhases, first_frame_s: f64) -> String {
    let mut md = format!(
        "\n{scene} on {} ({}): first frame after {first_frame_s:.1} s\n\n\
         | phase | ms | share | what |\n| --- | --- | --- | --- |\n",
        gpu.adapter_name(),
        gpu.driver_info()
    );
    let total = phases.total_ms().max(1e-9);
    for p in &phases.phases {
        md.push_str(&format!(
            "| {} | {:.1} | {:.1} % | {} |\n",
            p.name,
            p.ms,
            100.0 * p.ms / total,
            p.detail
        ));
    }
    md
}

fn csv(scene: &str, phases: &LoadPhases) -> String {
    let mut out = String::from("scene,phase,ms,detail\n");
    for p in &phases.phases {
        out.push_str(&format!(
            "{scene},{},{:.3},\"{}\"\n",
            p.name,
            p.ms,
            p.detail.replace('"', "'")
        ));
    }
    out
}
