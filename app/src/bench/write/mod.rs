//! Writing it: what a bench run gives, once it is scored. The tables (`results_csv.rs`,
//! `events_csv.rs`, `figures_json.rs`, `results_md.rs` with `seed_tables.rs` and
//! `lag_table.rs`), the plots (`plots/`), the picture strips (`strip.rs`,
//! `event_strip.rs`, `seed_maps.rs`) and a `--knob` run's cost curves (`cost_curves.rs`,
//! `cost_curves_plot.rs`); also the crossover map's files (`map.rs`, its picture
//! `map_png.rs` with `map_rows.rs` and `map_colours.rs`), the pictures redrawn from
//! committed tables (`redraw.rs`), a merge of jobs (`jobs_merge.rs`) and every folder's
//! `command.txt` (`command_line.rs`). `table.rs`, `markdown.rs` and `passes.rs` hold what
//! the tables share.

pub mod command_line;
pub mod cost_curves;
pub mod cost_curves_plot;
pub mod event_strip;
pub mod events_csv;
pub mod figure_columns;
pub mod figures_json;
pub mod info;
pub mod jobs_merge;
pub mod lag_table;
pub mod map;
pub mod map_colours;
pub mod map_png;
pub mod map_rows;
pub mod markdown;
pub mod passes;
pub mod plots;
pub mod redraw;
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

/// The pictures a bench draws besides its tables. `--quiet` marks a job of a sweep (the
/// crossover map's cells, docs/bench/crossover/map/run.sh): it keeps a `--knob` run's
/// `cost_curves.png`, the one picture a cell is read by and which the map folders hold,
/// and leaves out the plots, the strips and seeds.png, which take longer to draw than a
/// small cell takes to run (plan/args.rs says the same in `--quiet`'s help).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pictures {
    pub plots: bool,
    pub strip: bool,
    pub event_strip: bool,
    pub seed_maps: bool,
    pub cost_curves: bool,
}

impl Pictures {
    /// What a run draws: `moves`, a moving shot; `events`, a dynamic scene's light events.
    pub fn of(args: &BenchArgs, moves: bool, events: bool) -> Pictures {
        let full = !args.quiet;
        Pictures {
            plots: full,
            // One reference for every frame: a still camera on a still (or frozen) scene.
            strip: full && !moves && args.budget_ms.is_none(),
            event_strip: full && events,
            seed_maps: full && !moves && args.seeds > 1,
            cost_curves: args.knob.is_some(),
        }
    }
}

/// Everything a bench writes into `--out`, from every seed's runs (`per_seed`) and the
/// results scored over them: the pictures first (`Pictures` says which), then the tables
/// and plots, then a `--knob` run's cost curves.
pub fn all(
    args: &BenchArgs,
    plan: &Plan,
    bench: &Bench,
    per_seed: &[Vec<ConfigResult>],
    results: &[ConfigResult],
) -> anyhow::Result<()> {
    let out = &args.out;
    let draw = Pictures::of(args, bench.shot.moves(), bench.events.is_some());
    if draw.seed_maps {
        seed_maps::write_for_seeds(out, per_seed, &plan.configs, &bench.references)?;
    }
    if let (Some(e), true) = (&bench.events, draw.event_strip) {
        // Each configuration beside the references it was scored against.
        let own: Vec<&[restir_render::LinearImage]> = plan
            .configs
            .iter()
            .map(|c| {
                let refs = bench.references.for_bounces(c.settings.reference_bounces());
                refs.images.as_slice()
            })
            .collect();
        event_strip::write(&out.join("event_strip.png"), e, results, &own)?;
    }
    if draw.strip {
        strip::write_last_frames(out, results, &bench.references)?;
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
        equal_error(out, &info, results, &noise, knob, args, draw.cost_curves)?;
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
    plot: bool,
) -> anyhow::Result<()> {
    let note = format!("{} · {}", plots::subtitle(info), info.timing_note());
    let section = cost_curves::write(
        out,
        results,
        noise,
        (knob::name(knob), args.target_rmse),
        &note,
        plot,
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

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        bench: BenchArgs,
    }

    fn pictures(words: &[&str], moves: bool, events: bool) -> Pictures {
        let mut all = vec!["bench", "--scene", "builtin:concourse", "--size", "8x8"];
        all.extend(["--frames", "2", "--out", "/tmp/x"]);
        all.extend(words);
        Pictures::of(&Cli::parse_from(all).bench, moves, events)
    }

    #[test]
    fn a_quiet_job_draws_its_cost_curves_and_nothing_else() {
        // The crossover map's jobs: --quiet --knob --seeds 4, still, a dynamic scene.
        let quiet = pictures(
            &["--quiet", "--knob", "light_candidates=8,16", "--seeds", "4"],
            false,
            true,
        );
        let only_curves = Pictures {
            plots: false,
            strip: false,
            event_strip: false,
            seed_maps: false,
            cost_curves: true,
        };
        assert_eq!(quiet, only_curves);
        // Without --quiet everything the run supports is drawn.
        let full = pictures(
            &["--knob", "light_candidates=8,16", "--seeds", "4"],
            false,
            true,
        );
        assert!(full.plots && full.strip && full.event_strip && full.seed_maps);
        // A moving shot has no strip or seed maps (a reference per frame).
        let moving = pictures(&["--seeds", "4"], true, false);
        assert!(!moving.strip && !moving.seed_maps && !moving.cost_curves);
    }
}
