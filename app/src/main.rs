//! restir-viewer: the ReSTIR lab's viewer and its headless commands, for ReSTIR DI (direct
//! light from many lights), ReSTIR GI (one bounce of indirect light with its own reservoirs)
//! and ReSTIR PT (multi-bounce indirect light by path reuse).
//!
//! `restir-viewer` (or `view`) opens the interactive viewer; `render` renders frames
//! headless to EXR/PNG with statistics; `bench` and the `bench-*` commands measure;
//! `params` lists every pipeline parameter; `scenes` lists the built-in scenes.

mod bench;
mod bias_matrix;
mod cli;
mod compare;
mod probe;
mod recording;
mod tour;
mod viewer;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "restir-viewer",
    version,
    about = "The ReSTIR lab: watch, tune and measure ReSTIR: direct light (DI), indirect light \
             (GI) and path reuse (PT)"
)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
struct Args {
    #[command(subcommand)]
    command: Option<Command>,
    /// Without a command: the viewer's own arguments (`restir-viewer FILE.gltf`,
    /// `restir-viewer --scene builtin:NAME`, as after `view`).
    #[command(flatten)]
    view: viewer::ViewArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Open the interactive viewer (the default without a command).
    View(viewer::ViewArgs),
    /// Render frames headless and write an image (and statistics).
    Render(cli::render::RenderArgs),
    /// Measure configurations against a cached reference: times, errors, CSV/Markdown/plots.
    Bench(bench::BenchArgs),
    /// Every scene × every estimator over seeds against a high-spp reference: signed bias
    /// with its interval and a verdict per cell (`--list-jobs` / `--merge` for a sweep run
    /// as independent jobs).
    BiasMatrix(bias_matrix::BiasMatrixArgs),
    /// List every pipeline parameter with its stage, default, range and meaning
    /// (`--markdown`: the book's parameters page).
    Params(cli::params::ParamsArgs),
    /// List the built-in scenes (one `builtin:...` name per line).
    Scenes,
    /// Time building an environment's sampling distribution (default: a 4096×2048 sky).
    BenchEnv(bench::costs::env_cost::EnvCostArgs),
    /// Compare refit, rebuild and a two-level BVH on an animated scene over time.
    BenchBvh(bench::costs::bvh_cost::BvhCostArgs),
    /// Rays per second of each tracing backend (software BVH, hardware ray queries).
    BenchRays(bench::costs::ray_cost::RayCostArgs),
    /// How long each phase from file to first frame takes (load, upload, pipelines).
    BenchLoad(bench::costs::load_cost::LoadCostArgs),
    /// ReSTIR PT's path shifts on the CPU toy scene: bias, variance, how shifts fail.
    BenchShifts(bench::costs::shift_cost::ShiftCostArgs),
    /// The crossover map from a folder of `--knob` bench runs, one per (scene, size,
    /// camera): each configuration's cost to reach denoised RIS's best error (map.md,
    /// map.csv, map.png).
    BenchMap(bench::MapArgs),
    /// Redraw the pictures of bench folders from their tables without rerunning: every
    /// cost_curves.png and map.png at or under DIR, from the CSV beside it.
    BenchPlot(bench::PlotArgs),
}

fn main() {
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).init();
    let args = Args::parse();
    // The words after the program name: what `command.txt` says made an output folder.
    let command: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.command {
        Some(Command::View(a)) => viewer::run(a),
        Some(Command::Render(a)) => cli::render::run(a),
        Some(Command::Bench(a)) => bench::run(a, &command),
        Some(Command::BiasMatrix(a)) => bias_matrix::run(a),
        Some(Command::Params(a)) => {
            cli::params::run(a);
            Ok(())
        }
        Some(Command::BenchEnv(a)) => bench::costs::env_cost::run(a),
        Some(Command::BenchBvh(a)) => bench::costs::bvh_cost::run(a),
        Some(Command::BenchRays(a)) => bench::costs::ray_cost::run(a, &command),
        Some(Command::BenchLoad(a)) => bench::costs::load_cost::run(a),
        Some(Command::BenchShifts(a)) => bench::costs::shift_cost::run(a),
        Some(Command::BenchMap(a)) => bench::map(a, &command),
        Some(Command::BenchPlot(a)) => bench::plot(a),
        Some(Command::Scenes) => {
            cli::params::print_scenes();
            Ok(())
        }
        None => viewer::run(args.view),
    };
    if let Err(e) = result {
        // One line, naming the file or argument and the problem.
        let msg = format!("{e:#}").replace('\n', " ");
        eprintln!("error: {msg}");
        std::process::exit(1);
    }
}
