//! `bench --merge` (docs/src/headless.md, "Sweeps as independent jobs"): the jobs'
//! `figures.json` under the output folder's `jobs/` gathered into its `figures.md` and
//! `figures.csv`.
//! The figures hold no time or path, so the merged table is the one a single process
//! writes; times from separate jobs are not comparable (each ran under its own load), which
//! is why the merge leaves them out.

use std::fmt::Write;
use std::path::Path;

use anyhow::bail;

use super::figure_columns::{SEED_COLUMNS, seed_cells};
use super::figures_json::{FIGURES_FILE, FigureRow, read_rows};
use super::seed_tables::seed_figures_table;
use super::table::Table;
use crate::bench::plan::configs::Config;
use crate::bench::plan::jobs::job_dir;
use crate::bench::score::seed_figures::SeedFigures;

/// Gathers the jobs' figures into `figures.md` and `figures.csv` under `out`.
pub fn merge(configs: &[Config], out: &Path) -> anyhow::Result<()> {
    let mut rows: Vec<FigureRow> = Vec::new();
    let mut missing = Vec::new();
    for c in configs {
        let path = job_dir(out, &c.name).join(FIGURES_FILE);
        if !path.is_file() {
            missing.push(c.name.clone());
            continue;
        }
        let found = read_rows(&path)?;
        rows.extend(found.into_iter().filter(|r| r.config == c.name));
    }
    if !missing.is_empty() {
        bail!(
            "no figures yet for {} under {}",
            missing.join(", "),
            out.join("jobs").display()
        );
    }
    let mut md = String::new();
    if let Some(first) = rows.first() {
        let _ = writeln!(
            md,
            "# Bench jobs merged: {}, {}×{}, {} camera, {} seeds × {} frames\n",
            first.scene,
            first.size.0,
            first.size.1,
            first.camera,
            first.figures.seeds,
            first.figures.frames
        );
    }
    let named: Vec<(&str, &SeedFigures)> = rows
        .iter()
        .map(|r| (r.config.as_str(), &r.figures))
        .collect();
    seed_figures_table(&mut md, &named);
    std::fs::write(out.join("figures.md"), &md)?;
    let mut csv_header = vec!["config"];
    csv_header.extend(SEED_COLUMNS);
    let mut csv = Table::new(&csv_header);
    for r in &rows {
        let mut cells = vec![r.config.clone()];
        cells.extend(seed_cells(Some(&r.figures)));
        csv.row(cells);
    }
    csv.write(&out.join("figures.csv"))?;
    println!("{md}");
    Ok(())
}
