//! The rows of a `map.csv` read back (map.rs writes it), for `map.png`: the picture is
//! drawn from the table, so it shows the committed numbers even where the cells under the
//! folder would now read otherwise (a folder written by an older `bench-map`).

use std::path::Path;

use anyhow::Context;

use crate::bench::score::csv_read::records;

/// One (cell, configuration) of the map: what the picture shows of it.
#[derive(Clone, Debug, PartialEq)]
pub struct MapRow {
    pub folder: String,
    pub scene: String,
    pub size: String,
    pub camera: String,
    pub config: String,
    /// `ms_vs_baseline_at_best`, and its interval over the seeds where kept.
    pub ratio: Option<f64>,
    pub seed_mean: Option<f64>,
    pub seed_ci95: Option<f64>,
    /// `reach_at_best`: interpolated, at_most or beyond.
    pub reach: String,
}

/// The rows of `map.csv` text; a column an older file lacks (the seeds') reads as none.
pub fn parse(text: &str) -> anyhow::Result<Vec<MapRow>> {
    let mut records = records(text).into_iter();
    let header = records.next().context("no header")?;
    let column = |name: &str| header.iter().position(|h| h == name);
    let need = |name: &str| column(name).with_context(|| format!("no column {name}"));
    let (folder, scene, size) = (need("folder")?, need("scene")?, need("size")?);
    let (camera, config) = (need("camera")?, need("config")?);
    let (ratio, reach) = (need("ms_vs_baseline_at_best")?, need("reach_at_best")?);
    let (mean, ci) = (
        column("ms_vs_baseline_at_best_seed_mean"),
        column("ms_vs_baseline_at_best_seed_ci95"),
    );
    let mut rows = Vec::new();
    for r in records.filter(|r| r.iter().any(|c| !c.trim().is_empty())) {
        let cell = |i: usize| r.get(i).map_or("", |c| c.trim());
        let num = |i: Option<usize>| i.and_then(|i| cell(i).parse::<f64>().ok());
        rows.push(MapRow {
            folder: cell(folder).into(),
            scene: cell(scene).into(),
            size: cell(size).into(),
            camera: cell(camera).into(),
            config: cell(config).into(),
            ratio: num(Some(ratio)),
            seed_mean: num(mean),
            seed_ci95: num(ci),
            reach: cell(reach).into(),
        });
    }
    Ok(rows)
}

pub fn read_rows(path: &Path) -> anyhow::Result<Vec<MapRow>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    parse(&text).with_context(|| path.display().to_string())
}
