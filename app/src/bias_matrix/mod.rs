//! `bias-matrix`: every scene × every estimator over K seeds against a high-spp reference,
//! one verdict per cell (docs/src/measured/unbiased-reuse.md, "The bias matrix"). Each cell is one
//! `bench` run writing `figures.json` under `OUT/cells/SCENE/ESTIMATOR/`, so the same sweep
//! runs in this process, or as independent jobs (`--list-jobs` prints one command per cell
//! for GNU parallel, a Slurm array or a Kubernetes indexed Job; `--merge` builds the table
//! from whatever the jobs wrote; docs/src/headless.md, "Sweeps as independent jobs").
//!
//! A cell found biased is run again with `--confirm` times the frames before the table
//! calls it biased: a real bias keeps its size as frames grow, while the shortfall of an
//! unbiased estimator with heavy tails (rare huge samples that K seeds of a few frames
//! never drew) shrinks or widens into an undecided interval (docs/src/measured/unbiased-reuse.md,
//! "The bias matrix").

pub mod cells;
mod table;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use clap::{Args, Parser};

use crate::bench::plan::jobs::shell_line;
use crate::bench::write::figures_json::FIGURES_FILE;
use crate::bench::{self, BenchArgs};
use cells::{Cell, ESTIMATORS, all_scenes};
use restir_render::metrics::seeds::Verdict;

#[derive(Args, Debug)]
pub struct BiasMatrixArgs {
    /// Output directory: `cells/` holds each cell's bench output, `bias-matrix.md` and
    /// `bias-matrix.csv` the table.
    #[arg(long)]
    pub out: PathBuf,
    /// Image size of every cell, WxH.
    #[arg(long, default_value = "48x32")]
    pub size: String,
    /// Measured frames per seed.
    #[arg(long, default_value_t = 64)]
    pub frames: u32,
    /// Seeds per cell (the interval needs two; four give a t interval worth having).
    #[arg(long, default_value_t = 4)]
    pub seeds: u32,
    /// Samples per pixel of the references.
    #[arg(long, default_value_t = 4096)]
    pub reference_spp: u32,
    /// Comma-separated scenes (default: every built-in scene, the families at N = 16384 and
    /// the models; see `cells.rs`).
    #[arg(long)]
    pub scenes: Option<String>,
    /// Comma-separated estimators, bench configuration names (default: the 18 of the book).
    #[arg(long)]
    pub estimators: Option<String>,
    /// Print one command per cell (a `bench` run) and run nothing.
    #[arg(long, conflicts_with = "merge")]
    pub list_jobs: bool,
    /// Build the table from the cells under --out and run nothing.
    #[arg(long)]
    pub merge: bool,
    /// Skip the cells that already wrote their figures under --out (a sweep stopped
    /// halfway goes on where it stopped; the cells must have been run with these settings).
    #[arg(long)]
    pub resume: bool,
    /// Reference cache directory (default: $RESTIR_CACHE_DIR, else target/restir-cache).
    #[arg(long)]
    pub cache_dir: Option<PathBuf>,
    /// A cell found biased runs again with this many times the frames (under
    /// `cells/SCENE/ESTIMATOR/confirm/`); its verdict is the table's. 0 or 1: no confirmation.
    #[arg(long, default_value_t = 4)]
    pub confirm: u32,
}

/// `bench` on its own, to parse a cell's arguments exactly as its job's command line.
#[derive(Parser)]
struct BenchCommand {
    #[command(flatten)]
    bench: BenchArgs,
}

pub fn run(args: BiasMatrixArgs) -> anyhow::Result<()> {
    crate::cli::setup::parse_size(&args.size)?;
    if args.frames < 32 {
        bail!(
            "--frames {}: the bias view's rule needs two batches of 16 frames; use 32 or more",
            args.frames
        );
    }
    if args.seeds < 2 {
        bail!(
            "--seeds {}: an interval needs two seeds at least",
            args.seeds
        );
    }
    if args.confirm > MAX_CONFIRM {
        bail!(
            "--confirm {}: at most {MAX_CONFIRM} times the frames (a confirmation is one more \
             run of the cell, that many times as long)",
            args.confirm
        );
    }
    let scenes = list_or(&args.scenes, all_scenes());
    let estimators = list_or(&args.estimators, ESTIMATORS.map(String::from).to_vec());
    let base = restir_render::Settings::default();
    bench::plan::configs::parse_configs(&estimators.join(","), &base)?;
    for s in &scenes {
        if !s.starts_with("builtin:") && !Path::new(s).is_file() {
            bail!(
                "scene '{s}' not found (paths are relative to the working directory: run \
                 from the repository root, or pick scenes with --scenes)"
            );
        }
    }
    let cells = cells::cells(&scenes, &estimators);
    if args.list_jobs {
        return list_jobs(&args, &cells);
    }
    if !args.merge {
        let started = Instant::now();
        for (i, cell) in cells.iter().enumerate() {
            if args.resume && done(&args, cell, Stage::First) {
                continue;
            }
            eprintln!(
                "[{}/{}] {} · {} ({:.0} s so far)",
                i + 1,
                cells.len(),
                cell.scene,
                cell.estimator,
                started.elapsed().as_secs_f64()
            );
            run_cell(&args, cell, Stage::First);
        }
        let confirming = to_confirm(&args, &cells)?;
        for (i, cell) in confirming.iter().enumerate() {
            if args.resume && done(&args, cell, Stage::Confirm) {
                continue;
            }
            eprintln!(
                "[confirm {}/{}] {} · {} at {} frames ({:.0} s so far)",
                i + 1,
                confirming.len(),
                cell.scene,
                cell.estimator,
                Stage::Confirm.frames(&args),
                started.elapsed().as_secs_f64()
            );
            run_cell(&args, cell, Stage::Confirm);
        }
        eprintln!(
            "bias matrix: {} cells, {} confirmed, in {:.0} s",
            cells.len(),
            confirming.len(),
            started.elapsed().as_secs_f64()
        );
    }
    table::merge(&args.out, &cells, &args)
}

/// A cell's first run, or its confirmation at `--confirm` times the frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    First,
    Confirm,
}

impl Stage {
    pub fn frames(self, args: &BiasMatrixArgs) -> u32 {
        match self {
            Stage::First => args.frames,
            Stage::Confirm => args.frames.saturating_mul(args.confirm.max(1)),
        }
    }

    pub fn dir(self, args: &BiasMatrixArgs, cell: &Cell) -> PathBuf {
        match self {
            Stage::First => cell_dir(&args.out, cell),
            Stage::Confirm => cell_dir(&args.out, cell).join(CONFIRM_DIR),
        }
    }
}

/// The largest `--confirm`: 64 × 64 frames already take a heavy cell hours.
const MAX_CONFIRM: u32 = 64;

/// Where a cell's confirmation run writes, inside the cell's folder.
pub const CONFIRM_DIR: &str = "confirm";

fn done(args: &BiasMatrixArgs, cell: &Cell, stage: Stage) -> bool {
    stage.dir(args, cell).join(FIGURES_FILE).is_file()
}

/// The cells whose first run reads biased (those that have run), to run again at
/// `--confirm` times the frames; none when confirmation is off.
fn to_confirm(args: &BiasMatrixArgs, cells: &[Cell]) -> anyhow::Result<Vec<Cell>> {
    if args.confirm <= 1 {
        return Ok(Vec::new());
    }
    let mut biased = Vec::new();
    for cell in cells {
        if table::first_verdict(&args.out, cell)? == Some(Verdict::Biased) {
            biased.push(cell.clone());
        }
    }
    Ok(biased)
}

/// Prints one command per cell still to run: every cell's first run (only those without
/// output under `--resume`), then a confirmation for each cell whose first run reads
/// biased. A job runner lists with `--resume` until nothing is printed (two rounds: the
/// confirmations can be listed only once the first runs are done).
fn list_jobs(args: &BiasMatrixArgs, cells: &[Cell]) -> anyhow::Result<()> {
    let exe = std::env::current_exe()?;
    let exe = exe.to_string_lossy();
    let mut waiting = 0;
    for cell in cells {
        if !(args.resume && done(args, cell, Stage::First)) {
            println!(
                "{}",
                shell_line(&exe, &bench_argv(args, cell, Stage::First))
            );
            waiting += 1;
        }
    }
    for cell in to_confirm(args, cells)? {
        if !(args.resume && done(args, &cell, Stage::Confirm)) {
            println!(
                "{}",
                shell_line(&exe, &bench_argv(args, &cell, Stage::Confirm))
            );
        }
    }
    if waiting > 0 && args.confirm > 1 {
        eprintln!(
            "{waiting} cells have not run yet: once their jobs are done, list again with \
             --resume for the confirmations of the cells that read biased"
        );
    }
    Ok(())
}

fn list_or(list: &Option<String>, default: Vec<String>) -> Vec<String> {
    match list {
        Some(l) => l
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect(),
        None => default,
    }
}

/// The `bench` arguments of one cell's run (after the `bench` subcommand).
fn bench_argv(args: &BiasMatrixArgs, cell: &Cell, stage: Stage) -> Vec<String> {
    let mut argv: Vec<String> = [
        "--scene",
        &cell.scene,
        "--size",
        &args.size,
        "--frames",
        &stage.frames(args).to_string(),
        "--seeds",
        &args.seeds.to_string(),
        "--reference-spp",
        &args.reference_spp.to_string(),
        "--configs",
        &cell.estimator,
        // Animated scenes are measured at one moment: an accumulated image of a scene that
        // moves has no single reference.
        "--fps",
        "0",
        "--quiet",
        "--out",
    ]
    .map(String::from)
    .to_vec();
    argv.push(stage.dir(args, cell).to_string_lossy().into_owned());
    if let Some(c) = &args.cache_dir {
        argv.push("--cache-dir".into());
        argv.push(c.to_string_lossy().into_owned());
    }
    argv
}

pub fn cell_dir(out: &Path, cell: &Cell) -> PathBuf {
    out.join("cells").join(cell.folder())
}

/// Runs one cell in this process; a cell that fails leaves `error.txt` in its folder (the
/// table shows it) rather than stopping the sweep.
fn run_cell(args: &BiasMatrixArgs, cell: &Cell, stage: Stage) {
    let dir = stage.dir(args, cell);
    let result = (|| -> anyhow::Result<()> {
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("{}: cannot create", dir.display()))?;
        let _ = std::fs::remove_file(dir.join(table::ERROR_FILE));
        let argv: Vec<String> = std::iter::once("bench".to_string())
            .chain(bench_argv(args, cell, stage))
            .collect();
        let parsed = BenchCommand::try_parse_from(&argv)?;
        bench::run(parsed.bench, &argv)
    })();
    if let Err(e) = result {
        eprintln!("{} · {}: {e:#}", cell.scene, cell.estimator);
        let _ = std::fs::write(dir.join(table::ERROR_FILE), format!("{e:#}\n"));
    }
}

#[cfg(test)]
mod confirm_tests;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn job_lines_quote_what_a_shell_would_split() {
        let line = shell_line("/bin/x", &["a b".into(), "it's".into(), "c+d@e".into()]);
        assert_eq!(line, r"/bin/x bench 'a b' 'it'\''s' c+d@e");
    }
}
