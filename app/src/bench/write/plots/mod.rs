//! The bench's PNG plots, each readable on its own (title, axes with units, legend, and the
//! timing caveat under every time axis), every axis spanning its data (`axes.rs`):
//! - `pareto.png`: per-frame error against per-frame time, one point per configuration,
//!   the Pareto front dashed (`pareto.rs`);
//! - `error_per_frame.png`: per-frame luma RMSE, stability and (still camera) the running
//!   average's RGB RMSE against the frame number;
//! - `error_vs_time.png` (still camera): the running average's RGB RMSE against measured
//!   time, with the equal-time budget marked;
//! - `pass_times.png`: median time of each pass, stacked per configuration
//!   (`pass_times.rs`);
//! - `lag.png` (a dynamic scene with events): per-frame luma RMSE of every configuration
//!   against that frame's reference, linear, with a vertical line at each event frame;
//! - `lag_vs_noise.png` (the same): lag area against steady error, one point per
//!   configuration (`lag_noise.rs`).

pub mod axes;
pub mod canvas;
pub mod lag_noise;
pub mod legend;
pub mod line_chart;
pub mod pareto;
pub mod pass_times;

use std::path::Path;

use plotters::prelude::*;

use super::info::BenchInfo;
use crate::bench::plan::camera_path::CameraPath;
use crate::bench::score::frame_figures::FrameRecord;
use crate::bench::score::result::ConfigResult;
use canvas::{Area, DrawResult, color, render_png, with_footnote};
use line_chart::{LineChart, Series, line_chart};

/// Writes every plot the results support; returns the file names.
pub fn write_all(
    out: &Path,
    info: &BenchInfo,
    results: &[ConfigResult],
) -> anyhow::Result<Vec<String>> {
    let mut written = Vec::new();
    let scored = results.iter().all(|r| r.scores.is_some());
    let note = format!("{} · {}", subtitle(info), info.timing_note());
    if scored {
        render_png(&out.join("pareto.png"), (1200, 800), |a| {
            pareto::draw(a, &note, results)
        })?;
        written.push("pareto.png".into());
        render_png(&out.join("error_per_frame.png"), (1200, 1300), |a| {
            error_per_frame(a, info, results)
        })?;
        written.push("error_per_frame.png".into());
        // A running average needs one reference: a still camera on a still (or frozen) scene.
        if info.camera == CameraPath::Static && info.reference_count == 1 {
            render_png(&out.join("error_vs_time.png"), (1200, 800), |a| {
                error_vs_time(a, &note, info, results)
            })?;
            written.push("error_vs_time.png".into());
        }
    }
    if scored && results.iter().any(|r| !r.lag.is_empty()) {
        render_png(&out.join("lag.png"), (1200, 800), |a| lag(a, info, results))?;
        written.push("lag.png".into());
        let points: Vec<_> = results
            .iter()
            .filter_map(|r| lag_noise::point(&r.config.name, &r.lag))
            .collect();
        let note = format!(
            "{} · events from {} · averaged over {} seed(s) and the events",
            subtitle(info),
            info.event_source.unwrap_or("?"),
            info.seeds
        );
        lag_noise::write(&out.join("lag_vs_noise.png"), &note, &points)?;
        written.push("lag_vs_noise.png".into());
    }
    let height = 200 + 70 * results.len() as u32;
    render_png(&out.join("pass_times.png"), (1200, height), |a| {
        pass_times::draw(a, &note, results)
    })?;
    written.push("pass_times.png".into());
    Ok(written)
}

/// Scene, size and camera, for the footnotes.
pub fn subtitle(info: &BenchInfo) -> String {
    format!(
        "{} {}×{}, {} camera, reference {} spp",
        info.scene,
        info.size.0,
        info.size.1,
        info.camera.label(),
        info.reference_spp
    )
}

/// One series per configuration from a per-frame value.
fn per_frame_series(
    results: &[ConfigResult],
    value: impl Fn(&FrameRecord) -> Option<f64>,
    x_time: bool,
) -> Vec<Series> {
    results
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let points = r
                .frames
                .iter()
                .filter_map(|f| {
                    let x = if x_time {
                        f.cumulative_ms
                    } else {
                        f.index as f64 + 1.0
                    };
                    Some((x, value(f)?))
                })
                .collect();
            Series::new(r.config.name.clone(), color(i), points)
        })
        .collect()
}

fn error_per_frame(area: &Area, info: &BenchInfo, results: &[ConfigResult]) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, &subtitle(info))?;
    let still = info.camera == CameraPath::Static;
    let stability = if still {
        "Stability: luma RMSE between consecutive frames"
    } else {
        "Stability: luma RMSE between consecutive error images (frame − its reference)"
    };
    type Value = fn(&FrameRecord) -> Option<f64>;
    let mut panels: Vec<(&str, &str, Value)> = vec![
        (
            "Per-frame accuracy: luma RMSE of each frame vs reference",
            "luma RMSE (log)",
            |f| f.scores.luma_rmse,
        ),
        (stability, "luma RMSE (log)", |f| f.scores.stability),
    ];
    if still {
        panels.push((
            "Accumulated accuracy: RGB RMSE of the running average vs reference",
            "RGB RMSE (log)",
            |f| f.scores.accumulated_rgb_rmse,
        ));
    }
    // Log scales: nee's error is several times the others', which a linear axis flattens.
    for ((title, y_desc, value), panel) in panels.iter().zip(area.split_evenly((panels.len(), 1))) {
        let chart = LineChart {
            title,
            x_desc: "frame (after a clean history)",
            y_desc,
            log_x: false,
            log_y: true,
            markers_x: &[],
        };
        line_chart(&panel, &chart, &per_frame_series(results, value, false))?;
    }
    Ok(())
}

/// Error per frame around the events: a linear axis, so a lag's excess reads as area.
fn lag(area: &Area, info: &BenchInfo, results: &[ConfigResult]) -> DrawResult {
    area.fill(&WHITE)?;
    let note = format!(
        "{} · events from {} · lag metrics over {} seed(s), curves: seed {}",
        subtitle(info),
        info.event_source.unwrap_or("?"),
        info.seeds,
        info.seed
    );
    let area = with_footnote(area, &note)?;
    // Frames are plotted 1-based (as in error_per_frame.png): event frame f is at f + 1.
    let markers: Vec<(f64, &str)> = results
        .iter()
        .find(|r| !r.lag.is_empty())
        .map(|r| {
            r.lag
                .iter()
                .map(|e| (e.frame as f64 + 1.0, "light event"))
                .collect()
        })
        .unwrap_or_default();
    line_chart(
        &area,
        &LineChart {
            title: "Lag: per-frame luma RMSE vs that frame's reference, events marked",
            x_desc: "frame (after a clean history)",
            y_desc: "luma RMSE",
            log_x: false,
            log_y: false,
            markers_x: &markers,
        },
        &per_frame_series(results, |f| f.scores.luma_rmse, false),
    )
}

fn error_vs_time(
    area: &Area,
    note: &str,
    info: &BenchInfo,
    results: &[ConfigResult],
) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, note)?;
    let title = if info.budget_ms.is_some() {
        "Equal time: error of the running average vs time spent"
    } else {
        "Error of the running average vs time spent"
    };
    let budget = info.budget_ms.map(|t| (t, "budget"));
    line_chart(
        &area,
        &LineChart {
            title,
            x_desc: "measured time, summed over frames (ms, log; see note below)",
            y_desc: "accumulated RGB RMSE (log)",
            log_x: true,
            log_y: true,
            markers_x: budget.as_slice(),
        },
        &per_frame_series(results, |f| f.scores.accumulated_rgb_rmse, true),
    )
}
