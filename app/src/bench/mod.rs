//! `bench`: what accuracy costs in time. Runs named configurations from a clean history
//! with the same seed against a cached reference and writes `results.csv`, `frames.csv`,
//! `results.md` and PNG plots; `--budget-ms` compares them at equal time, `--knob` reads
//! each one's cost to reach a target error, and `--sweep-lights` times light selection
//! against the light count. See docs/src/measured/how-the-bench-measures.md.
//!
//! The folders are the stages `run` goes through, in order:
//! - `plan/`: what to run, the command line checked into a `Plan` (configurations, a
//!   cost curve's knob, the camera path, the equal-time budget, jobs);
//! - `run/`: running it, the scene on a renderer per configuration, the references, light
//!   events and motion masks, then every seed through the interleaved run loop;
//! - `score/`: the numbers, each frame's as it is rendered and, once every seed ran, the
//!   figures over the seeds with their intervals, equal error, the equal-time gain, lag and
//!   the crossover map;
//! - `write/`: the CSV, Markdown, plots and picture strips.
//!
//! Each stage imports only from the ones before it, but scoring stands below running: the
//! run loop scores each frame as it renders it, so `run/` uses `score/`, never the other
//! way. `costs/` holds the separate cost commands (`bench-bvh`, `bench-load`,
//! `bench-rays`, `bench-shifts`, `bench-env`) and the light-count sweep.

pub mod costs;
pub mod plan;
pub mod run;
pub mod score;
pub mod write;

use anyhow::Context;

use plan::Plan;
pub use plan::args::{BenchArgs, MapArgs, PlotArgs};

/// `bench`, from its arguments and the words of its command line after the program name
/// (written to `command.txt`).
pub fn run(args: BenchArgs, command: &[String]) -> anyhow::Result<()> {
    // What to run: the arguments checked into a plan before anything renders.
    let plan = Plan::of(&args)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("--out {}: cannot create", args.out.display()))?;
    if args.list_jobs && args.sweep_lights.is_none() {
        return plan::jobs::list(&plan.configs, &args.out);
    }
    write::command_line::write(&args.out, command)?;
    if let Some(counts) = &args.sweep_lights {
        return costs::light_sweep::run(&args, counts, &plan);
    }
    if args.merge {
        return write::jobs_merge::merge(&plan.configs, &args.out);
    }
    // Running it: the scene on a renderer per configuration, the references, events and
    // masks, then every seed.
    let mut bench = run::Bench::set_up(&args, &plan)?;
    let per_seed = run::seeds::every_seed(&mut bench, &plan.configs, args.seeds)?;
    // Scoring over the seeds.
    let results = score::over_seeds::over_seeds(
        &per_seed,
        &bench.seed_references(&plan.configs),
        bench.event_times(),
    );
    // Writing it.
    write::all(&args, &plan, &bench, &per_seed, &results)
}

/// `bench-map DIR`: the crossover map from the `--knob` runs under DIR, each a cell
/// (score/map.rs reads them), into DIR's `map.md`, `map.csv` and `map.png`.
pub fn map(args: MapArgs, command: &[String]) -> anyhow::Result<()> {
    let cells = score::map::read_cells(&args.dir, &args.knob)?;
    anyhow::ensure!(
        !cells.is_empty(),
        "{}: no cell (a folder with cost_curves.csv and figures.json)",
        args.dir.display()
    );
    write::command_line::write(&args.dir, command)?;
    write::map::write(&args.dir, &cells)
}

/// `bench-plot DIR`: every `cost_curves.png` and `map.png` at or under DIR redrawn from the
/// tables beside it (write/redraw.rs); no table is touched and nothing runs.
pub fn plot(args: PlotArgs) -> anyhow::Result<()> {
    let written = write::redraw::redraw(&args.dir)?;
    anyhow::ensure!(
        !written.is_empty(),
        "{}: no cost_curves.csv or map.csv at or under it",
        args.dir.display()
    );
    for path in &written {
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
