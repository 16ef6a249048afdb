//! Writing it: what a bench run gives, once it is scored. The tables (`results_csv.rs`,
//! `events_csv.rs`, `figures_json.rs`, `results_md.rs` with `seed_tables.rs` and
//! `lag_table.rs`), the plots (`plots/`), the picture strips (`strip.rs`,
//! `event_strip.rs`, `seed_maps.rs`) and a `--knob` run's cost curves (`cost_curves.rs`);
//! also the crossover map's files (`map.rs`), a merge of jobs (`jobs_merge.rs`) and every
//! folder's `command.txt` (`command_line.rs`). `table.rs`, `markdown.rs` and `passes.rs`
//! hold what the tables share.

pub mod command_line;
pub mod cost_curves;
pub mod event_strip;
pub mod events_csv;
pub mod figure_columns;
pub mod figures_json;
pub mod info;
pub mod jobs_merge;
pub mod lag_table;
pub mod map;
pub mod markdown;
pub mod passes;
pub mod plots;
pub mod results_csv;
pub mod results_md;
pub mod seed_maps;
pub mod seed_tables;
pub mod strip;
pub mod table;

use std::path::Path;

use anyhow::Context;

use crate::bench::plan::Plan;
use crate::bench::plan::args::BenchArgs;
use crate::bench::plan::knob;
use crate::bench::run::Bench;
use crate::bench::score::result::ConfigResult;
use info::BenchInfo;

/// Everything a bench writes into `--out`, from every seed's runs (`per_seed`) and the
/// results scored over them: the pictures first, then the tables and plots, then a
/// `--knob` run's cost curves. `--quiet` leaves out the plots, the strip and seeds.png.
pub fn all(
    args: &BenchArgs,
    plan: &Plan,
    bench: &Bench,
    per_seed: &[Vec<ConfigResult>],
    results: &[ConfigResult],
) -> anyhow::Result<()> {
    let out = &args.out;
    let moves = bench.shot.moves();
    if !moves && args.seeds > 1 && !args.quiet {
        seed_maps::write_for_seeds(out, per_seed, &plan.configs, &bench.references)?;
    }
    if let Some(e) = &bench.events {
        let primary = bench.references.primary();
        event_strip::write(&out.join("event_strip.png"), e, results, primary)?;
    }
    // One reference for every frame: a still camera on a still (or frozen) scene.
    if !moves && args.budget_ms.is_none() && !args.quiet {
        strip::write_last_frames(out, results, &bench.renderers, &bench.references)?;
    }
    let info = BenchInfo::of(args, plan, bench);
    tables_and_plots(out, &info, results, args.quiet)?;
    if let Some(knob) = &args.knob {
        let noise: Vec<f64> = plan
            .configs
            .iter()
            .map(|c| {
                let own = bench.references.for_bounces(c.settings.reference_bounces());
                own.frame_noise_luma().unwrap_or(0.0)
            })
            .collect();
        equal_error(out, &info, results, &noise, knob, args)?;
    }
    Ok(())
}

/// results.csv, figures.json, frames.csv, events.csv, results.md and the plots; prints
/// results.md unless `quiet`.
fn tables_and_plots(
    out: &Path,
    info: &BenchInfo,
    results: &[ConfigResult],
    quiet: bool,
) -> anyhow::Result<()> {
    results_csv::write_results(&out.join("results.csv"), info, results)?;
    let rows = figures_json::rows_of(info, results);
    figures_json::write_rows(&out.join(figures_json::FIGURES_FILE), &rows)?;
    results_csv::write_frames(&out.join("frames.csv"), results)?;
    if results.iter().any(|r| !r.lag.is_empty()) {
        events_csv::write_events(&out.join("events.csv"), results)?;
    }
    let md = results_md::results(info, results);
    std::fs::write(out.join("results.md"), &md)
        .with_context(|| format!("{}: cannot write", out.display()))?;
    let written = if quiet {
        Vec::new()
    } else {
        plots::write_all(out, info, results)?
    };
    if !quiet {
        println!("{md}");
    }
    eprintln!(
        "wrote {}/results.csv, frames.csv, results.md, figures.json, {}",
        out.display(),
        written.join(", ")
    );
    Ok(())
}

/// A `--knob` run's cost curves (`cost_curves.rs`), their section appended to results.md
/// and printed unless `--quiet`; `noise[i]` is configuration i's reference's own noise.
fn equal_error(
    out: &Path,
    info: &BenchInfo,
    results: &[ConfigResult],
    noise: &[f64],
    knob: &str,
    args: &BenchArgs,
) -> anyhow::Result<()> {
    let note = format!("{} · {}", plots::subtitle(info), info.timing_note());
    let section = cost_curves::write(
        out,
        results,
        noise,
        knob::name(knob),
        args.target_rmse,
        &note,
    )?;
    let path = out.join("results.md");
    let mut md = std::fs::read_to_string(&path)?;
    md.push_str(&section);
    std::fs::write(&path, md).with_context(|| format!("{}: cannot write", path.display()))?;
    if !args.quiet {
        println!("{section}");
    }
    Ok(())
}
