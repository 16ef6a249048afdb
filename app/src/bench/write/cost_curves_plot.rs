//! `cost_curves.png`: error against time, one curve per configuration in its knob order,
//! both axes log and fitted to the points with their intervals (plots/axes.rs). Each point
//! carries what the seeds say of it (docs/src/measured/how-the-bench-measures.md, "Error
//! bars"): a vertical bar, the 95 % interval of its error over the seeds; a horizontal one,
//! where each seed's median frame time was kept, the 95 % interval of their mean, the
//! point's milliseconds. Drawn by a `--knob` bench, and redrawn from a committed
//! `cost_curves.csv` by `bench-plot` (`redraw`), without rerunning the bench.

use std::path::Path;

use anyhow::Context;
use restir_render::metrics::seeds::Interval;

use super::plots::canvas::{color, render_png, with_footnote};
use super::plots::line_chart::{Bars, LineChart, Series, line_chart};
use crate::bench::score::cost_curves_file::{self, NamedCurve};
use crate::bench::score::equal_error::{CostPoint, in_knob_order};

/// Where results.md's "Equal error" paragraph names the files, just before the note that
/// `redraw` reads back from it as the plot's footnote.
pub const FILES_SENTENCE: &str = "(`cost_curves.csv`, `cost_curves.png`, `equal_error.csv`). ";

/// A point's bars: the error's 95 % interval where it is finite, the time's over the
/// seeds where two or more were kept.
fn bars(p: &CostPoint) -> Bars {
    let y = (p.rmse_ci95.is_finite() && p.rmse_ci95 > 0.0)
        .then(|| (p.rmse - p.rmse_ci95, p.rmse + p.rmse_ci95));
    let x = (p.seed_ms.len() >= 2)
        .then(|| Interval::of(&p.seed_ms))
        .filter(|i| i.half_width.is_finite() && i.half_width > 0.0)
        .map(|i| (p.ms - i.half_width, p.ms + i.half_width));
    Bars { x, y }
}

/// One series per curve: its readable points in knob order, each with its bars.
pub fn series(curves: &[NamedCurve]) -> Vec<Series> {
    curves
        .iter()
        .enumerate()
        .map(|(i, (name, points))| {
            let shown = in_knob_order(
                points
                    .iter()
                    .filter(|p| p.ms.is_finite() && p.rmse.is_finite() && p.rmse > 0.0),
            );
            let mut s = Series::new(
                name.clone(),
                color(i),
                shown.iter().map(|p| (p.ms, p.rmse)).collect(),
            );
            s.bars = shown.iter().map(|p| bars(p)).collect();
            s
        })
        .collect()
}

/// Writes the plot of `curves` to `path`, `note` under it.
pub fn plot(path: &Path, curves: &[NamedCurve], knob_name: &str, note: &str) -> anyhow::Result<()> {
    let series = series(curves);
    let seeds = curves
        .iter()
        .flat_map(|c| c.1.iter().map(|p| p.seed_ms.len()))
        .max()
        .unwrap_or(0);
    let any_y = series.iter().flat_map(|s| &s.bars).any(|b| b.y.is_some());
    let x_desc = if seeds >= 2 {
        format!(
            "median frame time (ms, log): mean of {seeds} seeds' medians, bar its 95 % interval"
        )
    } else {
        "median frame time (ms, log)".to_string()
    };
    let y_desc = if any_y {
        "per-frame luma RMSE (log), bar its 95 % interval over the seeds"
    } else {
        "per-frame luma RMSE (log)"
    };
    let title = format!("Error against cost over {knob_name}");
    render_png(path, (1200, 800), |area| {
        area.fill(&plotters::style::WHITE)?;
        let area = with_footnote(area, note)?;
        line_chart(
            &area,
            &LineChart {
                title: &title,
                x_desc: &x_desc,
                y_desc,
                log_x: true,
                log_y: true,
                markers_x: &[],
            },
            &series,
        )
    })
}

/// The note results.md's "Equal error" paragraph ends with (scene, size, camera, reference,
/// timing caveat): the footnote the bench drew under the plot.
fn note_of(results_md: &str) -> Option<String> {
    let line = results_md
        .lines()
        .find(|l| l.starts_with("Each configuration ran at "))?;
    let (_, note) = line.split_once(FILES_SENTENCE)?;
    Some(note.trim().to_string())
}

/// Redraws `dir`'s `cost_curves.png` from its `cost_curves.csv`, the footnote from its
/// `results.md` (the folder's name where that says nothing).
pub fn redraw(dir: &Path) -> anyhow::Result<()> {
    let (knob, curves) = cost_curves_file::read(&dir.join("cost_curves.csv"))?;
    let note = std::fs::read_to_string(dir.join("results.md"))
        .ok()
        .and_then(|md| note_of(&md))
        .unwrap_or_else(|| dir.display().to_string());
    plot(&dir.join("cost_curves.png"), &curves, &knob, &note)
        .with_context(|| format!("{}: cannot redraw cost_curves.png", dir.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(knob: &str, ms: f64, rmse: f64, ci: f64, seeds: &[f64]) -> CostPoint {
        CostPoint {
            knob: knob.into(),
            ms,
            seed_ms: seeds.to_vec(),
            rays_per_pixel: 1.0,
            candidates_per_pixel: 1.0,
            rmse,
            rmse_ci95: ci,
        }
    }

    #[test]
    fn each_cost_curve_point_carries_its_intervals() {
        let curves = vec![(
            "ris".to_string(),
            vec![
                point("16", 120.0, 0.01, 0.001, &[110.0, 130.0, 120.0, 120.0]),
                point("8", 100.0, 0.02, f64::NAN, &[]),
            ],
        )];
        let s = &series(&curves)[0];
        // Knob order: 8 before 16, whatever the file's order.
        assert_eq!(s.points, vec![(100.0, 0.02), (120.0, 0.01)]);
        assert_eq!(s.bars[0], Bars { x: None, y: None });
        let b = s.bars[1];
        let (lo, hi) = b.y.unwrap();
        assert!((lo - 0.009).abs() < 1e-12 && (hi - 0.011).abs() < 1e-12);
        let i = Interval::of(&[110.0, 130.0, 120.0, 120.0]);
        assert_eq!(b.x, Some((120.0 - i.half_width, 120.0 + i.half_width)));
    }

    #[test]
    fn the_redrawn_plot_keeps_the_benchs_footnote() {
        let md = format!(
            "## Equal error\n\nEach configuration ran at light_candidates = 8, 16; the cost \
             read off its curve in log-log {FILES_SENTENCE}builtin:detail 384×256 · CPU\n"
        );
        assert_eq!(
            note_of(&md).as_deref(),
            Some("builtin:detail 384×256 · CPU")
        );
        assert_eq!(note_of("# Bench\n"), None);
    }
}
