//! `figures.json`: every bench's figures over seeds, beside `results.csv`, and what merges of
//! independent jobs read back (write/jobs_merge.rs, and the bias matrix's table).

use anyhow::Context;

use super::info::BenchInfo;
use crate::bench::score::result::ConfigResult;
use crate::bench::score::seed_figures::SeedFigures;

/// One configuration's figures as `figures.json` holds them: what a merge of independent
/// jobs (`bench --list-jobs`, `bias-matrix --list-jobs`; docs/src/headless.md, "Sweeps as
/// independent jobs") reads back. Deterministic: no times or paths, only what the seeds
/// rendered.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FigureRow {
    pub scene: String,
    pub size: (u32, u32),
    pub camera: String,
    pub config: String,
    pub description: String,
    pub first_seed: u32,
    pub reference_spp: u32,
    pub figures: SeedFigures,
}

/// The file every bench writes beside results.csv.
pub const FIGURES_FILE: &str = "figures.json";

/// One row per scored configuration of a bench.
pub fn rows_of(info: &BenchInfo, results: &[ConfigResult]) -> Vec<FigureRow> {
    results
        .iter()
        .filter_map(|r| {
            Some(FigureRow {
                scene: info.scene.clone(),
                size: info.size,
                camera: info.camera.label(),
                config: r.config.name.clone(),
                description: r.config.description.clone(),
                first_seed: info.seed,
                reference_spp: info.reference_spp,
                figures: r.over_seeds.clone()?,
            })
        })
        .collect()
}

pub fn write_rows(path: &std::path::Path, rows: &[FigureRow]) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(rows)?;
    std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
}

pub fn read_rows(path: &std::path::Path) -> anyhow::Result<Vec<FigureRow>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("{}: not a figures file", path.display()))
}
