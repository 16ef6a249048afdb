//! The bench's PNG plots, each readable on its own (title, axes with units, legend, and the
//! timing caveat under every time axis):
//! - `pareto.png`: per-frame error against per-frame time, one point per configuration,
//!   the Pareto front dashed;
//! - `error_per_frame.png`: per-frame luma RMSE, stability and (still camera) the running
//!   average's RGB RMSE against the frame number;
//! - `error_vs_time.png` (still camera): the running average's RGB RMSE against measured
//!   time, with the equal-time budget marked;
//! - `pass_times.png`: median time of each pass, stacked per configuration;
//! - `lag.png` (a dynamic scene with events): per-frame luma RMSE of every configuration
//!   against that frame's reference, linear, with a vertical line at each event frame;
//! - `lag_vs_noise.png` (the same): lag area against steady error, one point per
//!   configuration (`lag_noise.rs`).

pub mod canvas;
pub mod lag_noise;

use std::path::Path;

use plotters::prelude::*;

use super::info::BenchInfo;
use super::passes::pass_names;
use crate::bench::plan::camera_path::CameraPath;
use crate::bench::score::frame_figures::FrameRecord;
use crate::bench::score::result::ConfigResult;
use canvas::{
    Area, DrawResult, LineChart, Series, TEXT_SIZE, TITLE_SIZE, color, draw_axes, legend,
    line_chart, log_ticks, render_png, text, with_footnote,
};

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
            pareto(a, &note, results)
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
        pass_times(a, &note, results)
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

fn pareto(area: &Area, note: &str, results: &[ConfigResult]) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, note)?;
    let points: Vec<(f64, f64, usize)> = results
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((r.median_frame_ms()?, r.scores.as_ref()?.mean_luma_rmse, i)))
        .collect();
    let max_x = points.iter().map(|p| p.0).fold(0.0, f64::max).max(1e-3) * 1.25;
    // Log errors: nee's is several times the rest, which a linear axis would crowd together.
    let max_y = points.iter().map(|p| p.1).fold(0.0, f64::max).max(1e-6) * 1.3;
    let min_y = points
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .min(max_y)
        / 1.3;
    let mut chart = ChartBuilder::on(&area)
        .caption(
            "Error vs time per frame (Pareto: lower left is better)",
            text(TITLE_SIZE),
        )
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(90)
        .build_cartesian_2d(
            0.0..max_x,
            (min_y..max_y)
                .log_scale()
                .with_key_points(log_ticks(min_y, max_y)),
        )?;
    draw_axes(
        &mut chart,
        "median time per frame (ms, sum of passes; see note below)",
        "per-frame luma RMSE vs reference (mean over frames, log)",
    )?;
    // The front: sorted by time, each point better than every faster one.
    let mut sorted = points.clone();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for &(x, y, _) in &sorted {
        if front.last().is_none_or(|&(_, best)| y < best) {
            front.push((x, y));
        }
    }
    chart
        .draw_series(DashedLineSeries::new(
            front,
            10,
            6,
            RGBColor(120, 120, 120).stroke_width(2),
        ))?
        .label("Pareto front")
        .legend(|(x, y)| {
            PathElement::new(
                vec![(x, y), (x + 24, y)],
                RGBColor(120, 120, 120).stroke_width(2),
            )
        });
    for &(x, y, i) in &points {
        let c = color(i);
        let name = results[i].config.name.clone();
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((x, y))
                    + Circle::new((0, 0), 9, c.filled())
                    + Text::new(name.clone(), (12, -24), text(TEXT_SIZE)),
            ))?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 12, y), 7, c.filled()));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    Ok(())
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
        .map(|(i, r)| Series {
            name: r.config.name.clone(),
            color: color(i),
            points: r
                .frames
                .iter()
                .filter_map(|f| {
                    Some((
                        if x_time {
                            f.cumulative_ms
                        } else {
                            f.index as f64 + 1.0
                        },
                        value(f)?,
                    ))
                })
                .collect(),
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

fn pass_times(area: &Area, note: &str, results: &[ConfigResult]) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, note)?;
    let passes = pass_names(results);
    let totals: Vec<f64> = results
        .iter()
        .map(|r| {
            passes
                .iter()
                .filter_map(|p| r.times.pass_ms_median.get(p))
                .sum()
        })
        .collect();
    let max_x = totals.iter().copied().fold(0.0, f64::max).max(1e-3) * 1.15;
    let names: Vec<String> = results.iter().map(|r| r.config.name.clone()).collect();
    let n = results.len().max(1);
    let mut chart = ChartBuilder::on(&area)
        .caption("Median time per pass (stacked)", text(TITLE_SIZE))
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(170)
        .build_cartesian_2d(0.0..max_x, (0..n - 1).into_segmented())?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .y_labels(n)
        .y_label_formatter(&|v| match v {
            SegmentValue::CenterOf(i) => names.get(*i).cloned().unwrap_or_default(),
            _ => String::new(),
        })
        .x_desc("median time (ms; see note below)")
        .axis_desc_style(text(TEXT_SIZE))
        .label_style(text(TEXT_SIZE - 2))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    for (p, pass) in passes.iter().enumerate() {
        let c = color(p);
        let bars: Vec<Rectangle<(f64, SegmentValue<usize>)>> = results
            .iter()
            .enumerate()
            .filter_map(|(i, r)| {
                let ms = *r.times.pass_ms_median.get(pass)?;
                let before: f64 = passes[..p]
                    .iter()
                    .filter_map(|q| r.times.pass_ms_median.get(q))
                    .sum();
                let mut bar = Rectangle::new(
                    [
                        (before, SegmentValue::Exact(i)),
                        (before + ms, SegmentValue::Exact(i + 1)),
                    ],
                    c.filled(),
                );
                bar.set_margin(10, 10, 0, 0);
                Some(bar)
            })
            .collect();
        chart
            .draw_series(bars)?
            .label(pass.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 7), (x + 20, y + 7)], c.filled()));
    }
    chart.draw_series(totals.iter().enumerate().map(|(i, t)| {
        Text::new(
            format!("{t:.1} ms"),
            (*t, SegmentValue::CenterOf(i)),
            text(TEXT_SIZE - 2),
        )
    }))?;
    legend(&mut chart, SeriesLabelPosition::LowerRight)?;
    Ok(())
}
