//! The command lines of `bench`, `bench-map` and `bench-plot`: what a user asks to run or
//! read. `Plan`
//! (plan/mod.rs) checks `bench`'s and turns it into what the stages read.

use std::path::PathBuf;

use clap::Args;

use super::configs::DEFAULT_CONFIGS;
use crate::cli::environment::EnvArgs;
use crate::cli::setup::PipelineArgs;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A .gltf/.glb file or a built-in scene (`builtin:many-lights`, see `scenes`).
    #[arg(long)]
    pub scene: String,
    /// Output size, WxH.
    #[arg(long)]
    pub size: String,
    /// Measured frames per configuration (not with --budget-ms).
    #[arg(long, required_unless_present = "budget_ms")]
    pub frames: Option<u32>,
    /// static; orbit:DEG (turn DEG degrees per frame about the scene centre); pan:DEG (turn
    /// in place); walk:M (move M scene units per frame along the view).
    #[arg(long, default_value = "static")]
    pub camera: String,
    /// Comma-separated configurations and preset files (.toml).
    #[arg(long, default_value = DEFAULT_CONFIGS)]
    pub configs: String,
    /// A cost curve per configuration: each runs once per value of this parameter
    /// (`light_candidates=1,2,4,8,16`), and results.md states the cost at which each
    /// reaches the target error (docs/src/measured/how-the-bench-measures.md, "Equal error").
    #[arg(long, value_name = "NAME=V1,V2,...")]
    pub knob: Option<String>,
    /// The per-frame luma RMSE the equal-error table reads costs at (default: the first
    /// configuration's at the middle knob value).
    #[arg(long, requires = "knob")]
    pub target_rmse: Option<f64>,
    /// Equal-time mode: each configuration accumulates frames until its measured time
    /// reaches this many milliseconds (still camera only).
    #[arg(long)]
    pub budget_ms: Option<f64>,
    /// Output directory (created).
    #[arg(long)]
    pub out: PathBuf,
    /// Frames rendered before measuring, so history builds up (not timed, not scored).
    #[arg(long, default_value_t = 0)]
    pub warmup: u32,
    /// Samples per pixel of the reference (per frame of an orbit).
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u32,
    /// Seed, `--set`, preset and effect set of every configuration. The bench applies
    /// `jitter=false` first (docs/src/measured/how-the-bench-measures.md, "How it
    /// measures"); `--set jitter=true` turns it back on.
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    /// `--env`, `--env-strength`, `--env-rotation` (the reference is keyed by them too).
    #[command(flatten)]
    pub env: EnvArgs,
    /// Reference cache directory (default: $RESTIR_CACHE_DIR, else target/restir-cache).
    #[arg(long)]
    pub cache_dir: Option<PathBuf>,
    /// Equal-time mode stops a configuration after this many frames whatever its time.
    #[arg(long, default_value_t = 10_000)]
    pub max_frames: u32,
    /// Light-count sweep on builtin:many-lights:N for these N (comma-separated): timing,
    /// scene load and BVH build only, no reference.
    #[arg(long, value_name = "N,N,...")]
    pub sweep_lights: Option<String>,
    /// Scene time of an animated scene (`--time`, `--fps`): frame i (warm-up included) is
    /// at T + i/F, and with F > 0 every measured frame has its own reference.
    #[command(flatten)]
    pub time: crate::cli::setup::TimeArgs,
    /// Runs every configuration K times, seeds S..S+K (S = `--seed`): every image figure
    /// is then stated as a mean with a 95 % interval over the seeds, with the accumulated
    /// image's squared bias and variance apart (docs/src/results.md, "Error bars"), and the
    /// lag metrics of a dynamic scene's events are averaged over them. Times, frames and
    /// the strip are seed S's, except `--knob`'s cost curves: their milliseconds are the
    /// mean of every seed's median, each seed's kept beside it, and the equal-time gain over
    /// the first configuration, which rests on every seed's error and median time.
    #[arg(long, default_value_t = 1)]
    pub seeds: u32,
    /// A job of a sweep: write the tables, figures.json and, with --knob, cost_curves.png
    /// (the crossover map's cells are read by it); no other plot, no strip, event strip or
    /// seeds.png; print nothing.
    #[arg(long)]
    pub quiet: bool,
    /// Print one `bench` command per configuration (each writing OUT/jobs/NAME) and run
    /// nothing: the sweep as independent jobs (docs/src/headless.md).
    #[arg(long, conflicts_with = "merge")]
    pub list_jobs: bool,
    /// Gather the jobs' figures under OUT's jobs folder into its figures.md and figures.csv and run
    /// nothing (the same command line as --list-jobs otherwise).
    #[arg(long)]
    pub merge: bool,
}

#[derive(Args, Debug)]
pub struct MapArgs {
    /// The folder holding one bench output folder per cell (docs/bench/crossover/map).
    pub dir: PathBuf,
    /// The knob the cells swept (`--knob NAME=...`).
    #[arg(long, default_value = "light_candidates")]
    pub knob: String,
}

#[derive(Args, Debug)]
pub struct PlotArgs {
    /// The folder whose pictures to redraw, and every folder under it
    /// (docs/bench/crossover).
    pub dir: PathBuf,
}
