//! `results.csv` (one row per configuration, or per configuration and event on a dynamic
//! scene with events), `frames.csv` (one row per measured frame) and
//! the sweep's `sweep.csv`. Times carry a `timing` column that says whether they are GPU
//! timestamps or CPU wall-clock (lavapipe: ratios only).

use std::collections::BTreeSet;
use std::path::Path;

use anyhow::Context;

use super::BenchInfo;
use super::events::{EventLag, recovery_cell};
use super::run_loop::ConfigResult;
use super::{equal_time_gain, seed_figures};

/// The passes in pipeline order; others (from a newer renderer) follow alphabetically.
pub const PASS_ORDER: &[&str] = &[
    "gbuffer raster",
    "gbuffer resolve",
    "initial",
    "temporal",
    "spatial",
    "mutation",
    "shade",
    "display",
];

/// Every pass any result timed, in pipeline order.
pub fn pass_names<'a>(results: impl IntoIterator<Item = &'a ConfigResult>) -> Vec<String> {
    let seen: BTreeSet<&String> = results
        .into_iter()
        .flat_map(|r| r.times.pass_ms_median.keys())
        .collect();
    let mut names: Vec<String> = PASS_ORDER
        .iter()
        .filter(|p| seen.iter().any(|s| s == p))
        .map(|p| p.to_string())
        .collect();
    names.extend(
        seen.into_iter()
            .filter(|s| !PASS_ORDER.contains(&s.as_str()))
            .cloned(),
    );
    names
}

/// Column names of the passes' median times: `initial_ms`, `gbuffer_raster_ms`, ...
pub fn pass_columns(passes: &[String]) -> Vec<String> {
    passes
        .iter()
        .map(|p| format!("{}_ms", p.replace(' ', "_")))
        .collect()
}

/// The passes' median times of one result, in `pass_columns` order.
pub fn pass_cells<'a>(
    passes: &'a [String],
    r: &'a ConfigResult,
) -> impl Iterator<Item = String> + 'a {
    passes
        .iter()
        .map(|p| num(r.times.pass_ms_median.get(p).copied()))
}

/// A CSV table under construction.
pub struct Table {
    text: String,
}

impl Table {
    pub fn new(header: &[&str]) -> Table {
        let mut t = Table {
            text: String::new(),
        };
        t.row(header.iter().map(|s| s.to_string()));
        t
    }

    pub fn row(&mut self, cells: impl IntoIterator<Item = String>) {
        let cells: Vec<String> = cells.into_iter().map(|c| escape(&c)).collect();
        self.text.push_str(&cells.join(","));
        self.text.push('\n');
    }

    pub fn write(&self, path: &Path) -> anyhow::Result<()> {
        std::fs::write(path, &self.text)
            .with_context(|| format!("{}: cannot write", path.display()))
    }
}

fn escape(cell: &str) -> String {
    if cell.contains([',', '"', '\n']) {
        format!("\"{}\"", cell.replace('"', "\"\""))
    } else {
        cell.to_string()
    }
}

/// A number, or empty when there is none.
pub fn num(x: Option<f64>) -> String {
    x.map(|v| format!("{v}")).unwrap_or_default()
}

/// √(RMSE² − noise²): the error against the true image, when the reference's own noise
/// (independent of the frames) is known; E[RMSE²] = MSE + Var_ref.
pub fn without_noise(rmse: Option<f64>, noise: Option<f64>) -> Option<f64> {
    Some((rmse?.powi(2) - noise?.powi(2)).max(0.0).sqrt())
}

pub fn write_results(
    path: &Path,
    info: &BenchInfo,
    results: &[ConfigResult],
) -> anyhow::Result<()> {
    let passes = pass_names(results);
    let pass_headers = pass_columns(&passes);
    let mut header: Vec<&str> = vec![
        "config",
        "mode",
        "description",
        "frames",
        "median_frame_ms",
        "time_vs_nee",
    ];
    header.extend(pass_headers.iter().map(String::as_str));
    header.extend([
        "mean_luma_rmse",
        "mean_luma_rmse_antialiased",
        "mean_stability_rmse",
        "mean_low_frequency_rmse",
        "error_correlation",
        "temporal_flicker",
        "accumulated_rgb_rmse",
        "accumulated_rgb_rmse_minus_reference_noise",
        "accumulated_rel_mse",
        "luma_ratio",
        "mean_signed_bias",
        "black_pixel_fraction",
        "disoccluded_share",
        "disoccluded_luma_rmse",
        "disoccluded_signed_bias",
        "near_moving_share",
        "near_moving_luma_rmse",
        "near_moving_signed_bias",
        "detail_share",
        "detail_luma_rmse",
        "detail_kept",
        "detail_flip",
        "shadow_rays_per_pixel",
        "useful_candidate_share",
        "ray_backend",
        "denoise_auto_depth",
        "frame_mse_vs_nee",
        "budget_ms",
        "budget_used_ms",
        "budget_capped",
        "budget_mse_vs_nee",
        "non_finite_pixels",
        "scene",
        "size",
        "camera",
        "seed",
        "reference_spp",
        "reference_noise_luma_rmse",
        "reference_noise_rgb_rmse",
        "device",
        "timing",
    ]);
    header.extend(seed_figures::CSV_COLUMNS);
    header.extend(equal_time_gain::CSV_COLUMNS);
    header.extend(LAG_COLUMNS);
    let mut table = Table::new(&header);
    let gains = equal_time_gain::gains_vs_first(results);
    for (r, gain) in results.iter().zip(gains) {
        let s = r.scores.clone().unwrap_or_default();
        let scored = r.scores.is_some();
        let mut cells = vec![
            r.config.name.clone(),
            r.config.mode.name().to_string(),
            r.config.description.clone(),
            r.frames.len().to_string(),
            num(r.median_frame_ms()),
            num(r.time_vs_nee),
        ];
        cells.extend(pass_cells(&passes, r));
        cells.extend([
            num(scored.then_some(s.mean_luma_rmse)),
            num(s.antialiased_luma_rmse),
            num(scored.then_some(s.mean_stability)),
            num(scored.then_some(s.mean_low_frequency_rmse)),
            num(scored.then_some(s.error_correlation())),
            num(r.flicker),
            num(s.accumulated_rgb_rmse),
            num(without_noise(
                s.accumulated_rgb_rmse,
                info.reference_noise_rgb,
            )),
            num(s.accumulated_rel_mse),
            num(scored.then_some(s.luma_ratio)),
            num(scored.then_some(s.signed_bias)),
            num(scored.then_some(s.black_pixel_fraction)),
            num(s.disoccluded.map(|m| m.share)),
            num(s.disoccluded.and_then(|m| m.luma_rmse)),
            num(s.disoccluded.and_then(|m| m.signed_bias)),
            num(s.near_moving.map(|m| m.share)),
            num(s.near_moving.and_then(|m| m.luma_rmse)),
            num(s.near_moving.and_then(|m| m.signed_bias)),
            num(s.detail.map(|d| d.share)),
            num(s.detail.map(|d| d.luma_rmse)),
            num(s.detail.map(|d| d.kept)),
            num(s.detail.map(|d| d.flip)),
            num(Some(r.times.shadow_rays_per_pixel_total)),
            num(Some(r.times.useful_candidate_share)),
            r.ray_backend.map_or("", |b| b.name()).to_string(),
            r.denoise_auto_depth
                .map(|d| d.to_string())
                .unwrap_or_default(),
            num(r.frame_mse_vs_nee),
            num(r.budget.map(|b| b.budget.ms)),
            num(r.budget.map(|b| b.used_ms)),
            r.budget.map(|b| b.capped().to_string()).unwrap_or_default(),
            num(r.budget_mse_vs_nee),
            s.non_finite_pixels.to_string(),
            info.scene.clone(),
            format!("{}x{}", info.size.0, info.size.1),
            info.camera.label(),
            info.seed.to_string(),
            info.reference_spp.to_string(),
            num(info.reference_noise_luma),
            num(info.reference_noise_rgb),
            info.device.clone(),
            info.timing_note().to_string(),
        ]);
        cells.extend(seed_figures::csv_cells(r.over_seeds.as_ref()));
        cells.extend(equal_time_gain::csv_cells(gain));
        for lag in lag_rows(info.event_source, &r.lag) {
            let mut row = cells.clone();
            row.extend(lag);
            table.row(row);
        }
    }
    table.write(path)
}

/// The lag columns of `results.csv`: the number of events, which one this row is (0, 1,
/// ...), and its numbers averaged over the seeds; empty without events (a static scene,
/// frozen time), where a configuration keeps its single row.
pub const LAG_COLUMNS: [&str; 12] = [
    "events",
    "event",
    "event_source",
    "event_frame",
    "event_time",
    "seeds",
    "peak_error",
    "steady_error",
    "peak_over_steady",
    "recovery_frames",
    "lag_area",
    "signed_bias",
];

/// The `LAG_COLUMNS` cells of one configuration's rows: one row per event, or a single
/// empty row without events.
fn lag_rows(event_source: Option<&str>, lag: &[EventLag]) -> Vec<Vec<String>> {
    if lag.is_empty() {
        return vec![vec![String::new(); LAG_COLUMNS.len()]];
    }
    lag.iter()
        .enumerate()
        .map(|(k, e)| {
            let mut cells = vec![
                lag.len().to_string(),
                k.to_string(),
                event_source.unwrap_or_default().to_string(),
            ];
            cells.extend(event_cells(e));
            cells
        })
        .collect()
}

/// Frame, time, seeds and the metrics of one event.
fn event_cells(e: &EventLag) -> Vec<String> {
    vec![
        e.frame.to_string(),
        e.time.to_string(),
        e.seeds.to_string(),
        num(e.peak_error),
        num(e.steady_error),
        num(e.peak_over_steady),
        recovery_cell(e.recovery_frames),
        num(e.lag_area),
        num(e.signed_bias),
    ]
}

/// `events.csv`: one row per configuration and event.
pub fn write_events(path: &Path, results: &[ConfigResult]) -> anyhow::Result<()> {
    let mut header = vec!["config", "event"];
    header.extend(&LAG_COLUMNS[3..]);
    let mut table = Table::new(&header);
    for r in results {
        for (k, e) in r.lag.iter().enumerate() {
            let mut cells = vec![r.config.name.clone(), k.to_string()];
            cells.extend(event_cells(e));
            table.row(cells);
        }
    }
    table.write(path)
}

pub fn write_frames(path: &Path, results: &[ConfigResult]) -> anyhow::Result<()> {
    let mut table = Table::new(&[
        "config",
        "frame",
        "frame_ms",
        "cumulative_ms",
        "luma_rmse",
        "stability_rmse",
        "accumulated_rgb_rmse",
    ]);
    for r in results {
        for f in &r.frames {
            table.row([
                r.config.name.clone(),
                f.index.to_string(),
                f.ms.to_string(),
                f.cumulative_ms.to_string(),
                num(f.scores.luma_rmse),
                num(f.scores.stability),
                num(f.scores.accumulated_rgb_rmse),
            ]);
        }
    }
    table.write(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_csv_cells_are_escaped() {
        let mut t = Table::new(&["a", "b"]);
        t.row(["x,y".to_string(), "say \"hi\"".to_string()]);
        assert_eq!(t.text, "a,b\n\"x,y\",\"say \"\"hi\"\"\"\n");
        assert_eq!(num(None), "");
        assert_eq!(num(Some(0.5)), "0.5");
        assert_eq!(without_noise(Some(0.5), Some(0.3)), Some(0.4));
        assert_eq!(without_noise(Some(0.1), Some(0.3)), Some(0.0));
        assert_eq!(without_noise(Some(0.1), None), None);
    }

    fn event(frame: usize, lag_area: f64, recovery: Option<Option<f64>>) -> EventLag {
        EventLag {
            frame,
            time: frame as f32 / 30.0,
            seeds: 2,
            peak_error: Some(0.5),
            steady_error: Some(0.1),
            peak_over_steady: Some(5.0),
            recovery_frames: recovery,
            lag_area: Some(lag_area),
            signed_bias: Some(-0.25),
        }
    }

    #[test]
    fn results_csv_has_a_row_per_event_with_that_events_numbers() {
        let column = |name: &str| LAG_COLUMNS.iter().position(|c| *c == name).unwrap();
        let rows = lag_rows(
            Some("scene"),
            &[event(9, 1.5, Some(Some(4.0))), event(39, 0.75, Some(None))],
        );
        assert_eq!(rows.len(), 2);
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), LAG_COLUMNS.len());
            assert_eq!(row[column("events")], "2");
            assert_eq!(row[column("event")], k.to_string());
            assert_eq!(row[column("event_source")], "scene");
            assert_eq!(row[column("signed_bias")], "-0.25");
        }
        // Each row carries its own event, not the first one's.
        assert_eq!(
            (
                rows[0][column("event_frame")].as_str(),
                rows[1][column("event_frame")].as_str()
            ),
            ("9", "39")
        );
        assert_eq!(rows[0][column("lag_area")], "1.5");
        assert_eq!(rows[1][column("lag_area")], "0.75");
        assert_eq!(rows[0][column("recovery_frames")], "4");
        assert_eq!(rows[1][column("recovery_frames")], "never");
        // Without events: one row of empty cells, so a static scene keeps one row per
        // configuration.
        assert_eq!(
            lag_rows(None, &[]),
            vec![vec![String::new(); LAG_COLUMNS.len()]]
        );
        // events.csv keeps its columns: config, event, then event_frame onwards.
        assert_eq!(LAG_COLUMNS[3], "event_frame");
    }
}
