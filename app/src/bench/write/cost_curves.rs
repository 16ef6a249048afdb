//! What a `--knob` bench writes about its cost curves (score/equal_error.rs):
//! `cost_curves.csv` (every point), `equal_error.csv` (each curve's cost at the target,
//! against the first curve's), `cost_curves.png` (`cost_curves_plot.rs`), and the "Equal
//! error" section of results.md.

use std::fmt::Write;
use std::path::Path;

use super::cost_curves_plot::{FILES_SENTENCE, plot};
use super::markdown::table;
use super::table::{Table, num};
use crate::bench::score::equal_error::{Curve, Reach, cost_at, curves, default_target};
use crate::bench::score::result::ConfigResult;

/// A finite number, or empty.
fn finite(x: f64) -> String {
    num(Some(x).filter(|v| v.is_finite()))
}

/// Writes the files (the plot where `draw`); returns the markdown section for results.md
/// (empty without a target).
pub fn write(
    out: &Path,
    results: &[ConfigResult],
    noise: &[f64],
    (knob_name, target): (&str, Option<f64>),
    note: &str,
    draw: bool,
) -> anyhow::Result<String> {
    let curves = curves(results, noise, knob_name);
    let Some(target) = target.or_else(|| default_target(&curves)) else {
        return Ok(String::new());
    };
    points(&curves, knob_name).write(&out.join("cost_curves.csv"))?;
    let reaches: Vec<Option<Reach>> = curves.iter().map(|c| cost_at(&c.points, target)).collect();
    let (at_target, rows) = at_target(&curves, &reaches, target);
    at_target.write(&out.join("equal_error.csv"))?;
    let md = section(&curves, knob_name, target, note, &rows);
    if draw {
        let named: Vec<(String, Vec<_>)> = curves
            .iter()
            .map(|c| (c.name.clone(), c.points.clone()))
            .collect();
        plot(&out.join("cost_curves.png"), &named, knob_name, note)?;
    }
    Ok(md)
}

/// `cost_curves.csv`: every point of every curve.
fn points(curves: &[Curve], knob_name: &str) -> Table {
    let mut points = Table::new(&[
        "config",
        knob_name,
        "median_frame_ms",
        "shadow_rays_per_pixel",
        "light_candidates_per_pixel",
        "frame_luma_rmse_without_reference_noise",
        "frame_luma_rmse_ci95",
        "seed_median_frame_ms",
    ]);
    for c in curves {
        for p in &c.points {
            let seeds: Vec<String> = p.seed_ms.iter().map(|&ms| finite(ms)).collect();
            points.row(vec![
                c.name.clone(),
                p.knob.clone(),
                finite(p.ms),
                finite(p.rays_per_pixel),
                finite(p.candidates_per_pixel),
                finite(p.rmse),
                finite(p.rmse_ci95),
                seeds.join(";"),
            ]);
        }
    }
    points
}

/// `equal_error.csv` and the rows of results.md's table: each curve's cost at the target,
/// a bound where the target lies outside the curve.
fn at_target(
    curves: &[Curve],
    reaches: &[Option<Reach>],
    target: f64,
) -> (Table, Vec<Vec<String>>) {
    let first_ms = reaches.first().copied().flatten().map(|r| r.cost().ms);
    let mut table = Table::new(&[
        "config",
        "target_rmse",
        "reach",
        "ms_at_target",
        "ms_vs_first",
        "shadow_rays_per_pixel_at_target",
        "light_candidates_per_pixel_at_target",
    ]);
    let mut rows = Vec::new();
    for (c, reach) in curves.iter().zip(reaches) {
        let Some(reach) = reach else {
            table.row(vec![c.name.clone(), finite(target), "no curve".into()]);
            continue;
        };
        let cost = reach.cost();
        let ratio = first_ms.map(|f| cost.ms / f).unwrap_or(f64::NAN);
        table.row(vec![
            c.name.clone(),
            finite(target),
            reach.code().to_string(),
            finite(cost.ms),
            finite(ratio),
            finite(cost.rays_per_pixel),
            finite(cost.candidates_per_pixel),
        ]);
        let bound = match reach {
            Reach::At(_) => "",
            Reach::AtMost(_) => "≤ ",
            Reach::Beyond(_) => "> ",
        };
        rows.push(vec![
            format!("`{}`", c.name),
            format!("{bound}{:.2}", cost.ms),
            if ratio.is_finite() {
                format!("{bound}{ratio:.2}×")
            } else {
                "n/a".into()
            },
            format!("{:.2}", cost.rays_per_pixel),
            format!("{:.1}", cost.candidates_per_pixel),
        ]);
    }
    (table, rows)
}

/// results.md's "Equal error" section: what ran, the target, and the table.
fn section(
    curves: &[Curve],
    knob_name: &str,
    target: f64,
    note: &str,
    rows: &[Vec<String>],
) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n## Equal error\n\nEach configuration ran at {knob_name} = {}; the cost at which its \
         per-frame luma RMSE, the reference's own noise taken out, reaches {target:.4} \
         (`--target-rmse`, else the first configuration's error at the middle value), read \
         off its curve in log-log {FILES_SENTENCE}{note}\n",
        curves
            .first()
            .map(|c| {
                c.points
                    .iter()
                    .map(|p| p.knob.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .unwrap_or_default(),
    );
    table(
        &mut md,
        &[
            "configuration".into(),
            "ms per frame at the target".into(),
            "vs the first".into(),
            "shadow rays / px".into(),
            "light candidates / px".into(),
        ],
        rows,
    );
    md
}
