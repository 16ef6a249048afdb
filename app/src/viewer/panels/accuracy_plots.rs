//! The Accuracy panel's curves: per-frame luma RMSE, accumulated RGB RMSE and frame time
//! against the frame, one line per configuration (the current one bright, earlier ones
//! dimmed in the same hue), and the median time of each pass per configuration: what
//! a change removed in error next to what it cost. A curve's name, colour and numbers are
//! written here (`curve_text`, `significant`), and the panel's numbers (`accuracy.rs`)
//! write them the same way.

use std::collections::BTreeSet;

use egui::{Color32, RichText, Ui};
use egui_plot::{Line, Plot, PlotPoints, PlotUi};
use restir_render::stats::StatsSummary;

use super::stats::pass_color;
use crate::viewer::accuracy::{Curve, CurvePoint, Curves};

/// How a plot's y axis maps values.
#[derive(Clone, Copy, PartialEq)]
enum Scale {
    Linear,
    /// Errors: configurations differ by orders of magnitude (jitter on vs off was ~30×
    /// on `builtin:cornell`), and a linear axis flattens all but the worst to zero.
    Log,
}

pub fn ui(ui: &mut Ui, curves: &Curves) {
    legend(ui, curves);
    let per_frame = |p: &CurvePoint| Some(p.luma_rmse);
    let accumulated = |p: &CurvePoint| Some(p.accumulated_rgb_rmse);
    let title = "Per-frame luma RMSE (log scale)";
    plot(ui, title, Scale::Log, curves, per_frame, |_| {});
    let title = "Accumulated RGB RMSE (log scale)";
    plot(ui, title, Scale::Log, curves, accumulated, |_| {});
    let title = "Frame time (sum of passes), ms";
    plot(ui, title, Scale::Linear, curves, frame_ms, |plot| {
        current_passes(plot, curves)
    });
    pass_table(ui, curves);
}

/// One line per curve, newest first: its name in its colour and where it ended up.
fn legend(ui: &mut Ui, curves: &Curves) {
    let all: Vec<(&Curve, bool)> = curves.all().collect();
    for (curve, current) in all.into_iter().rev() {
        let Some(last) = curve.last() else { continue };
        ui.horizontal_wrapped(|ui| {
            ui.label(curve_text(curve, current).strong());
            let ms = curve
                .time_summary()
                .frame_gpu_ms_median
                .map_or(String::new(), |ms| format!(" · {ms:.1} ms"));
            ui.label(
                RichText::new(format!(
                    "{} frames · per-frame {} · accumulated {} · bias {:+.2} %{ms}",
                    last.x,
                    significant(curve.mean_luma_rmse().unwrap_or(0.0)),
                    significant(last.accumulated_rgb_rmse),
                    100.0 * last.signed_bias
                ))
                .small(),
            );
        });
    }
}

fn frame_ms(p: &CurvePoint) -> Option<f64> {
    (!p.pass_ms.is_empty()).then(|| p.pass_ms.iter().map(|(_, ms)| ms).sum())
}

/// `value` of every point of every curve against its frame, plus `extra` lines.
fn plot(
    ui: &mut Ui,
    title: &str,
    scale: Scale,
    curves: &Curves,
    value: impl Fn(&CurvePoint) -> Option<f64>,
    extra: impl FnOnce(&mut PlotUi),
) {
    ui.label(title);
    let plot = Plot::new(title)
        .height(110.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .x_axis_label("frame");
    let plot = match scale {
        Scale::Linear => plot.include_y(0.0),
        // Drawn as log10; the axis shows the values themselves, the hover label none
        // (it would show the logarithm).
        Scale::Log => plot
            .y_axis_formatter(|mark, _| significant(10f64.powf(mark.value)))
            .show_y(false),
    };
    let y = |v: f64| match scale {
        Scale::Linear => Some(v),
        Scale::Log => (v > 0.0).then(|| v.log10()),
    };
    plot.show(ui, |plot| {
        for (curve, current) in curves.all() {
            let points: Vec<[f64; 2]> = curve
                .points
                .iter()
                .filter_map(|p| y(value(p)?).map(|y| [p.x as f64, y]))
                .collect();
            let width = if current { 2.0 } else { 1.0 };
            plot.line(
                Line::new(curve_name(curve), PlotPoints::from(points))
                    .color(curve_color(curve.id, current))
                    .width(width),
            );
        }
        extra(plot);
    });
}

/// The current curve's passes, thin, in the Stats panel's pass colours.
fn current_passes(plot: &mut PlotUi, curves: &Curves) {
    let Some(curve) = &curves.current else { return };
    let passes: BTreeSet<&'static str> = curve
        .points
        .iter()
        .flat_map(|p| p.pass_ms.iter().map(|(name, _)| *name))
        .collect();
    for pass in passes {
        let points: Vec<[f64; 2]> = curve
            .points
            .iter()
            .filter(|p| !p.pass_ms.is_empty())
            .map(|p| {
                // A pass recorded several times in a frame (spatial) counts as its sum.
                let ms = p
                    .pass_ms
                    .iter()
                    .filter(|(n, _)| *n == pass)
                    .map(|(_, ms)| ms);
                [p.x as f64, ms.sum()]
            })
            .collect();
        plot.line(
            Line::new(pass, PlotPoints::from(points))
                .color(pass_color(pass))
                .width(1.0),
        );
    }
}

/// Median milliseconds per pass (rows) and configuration (columns, by curve number).
fn pass_table(ui: &mut Ui, curves: &Curves) {
    let columns: Vec<(&Curve, bool, StatsSummary)> = curves
        .all()
        .map(|(c, current)| (c, current, c.time_summary()))
        .collect();
    let passes: BTreeSet<&String> = columns
        .iter()
        .flat_map(|(_, _, s)| s.pass_ms_median.keys())
        .collect();
    if passes.is_empty() {
        ui.weak("No pass times yet");
        return;
    }
    ui.label("Median ms per pass, by curve");
    let cell = |ms: Option<&f64>| ms.map_or("–".to_string(), |ms| format!("{ms:.2}"));
    egui::Grid::new("accuracy pass times")
        .num_columns(columns.len() + 1)
        .striped(true)
        .show(ui, |ui| {
            ui.label("pass");
            for (curve, current, _) in &columns {
                let number = RichText::new((curve.id + 1).to_string()).strong();
                ui.label(number.color(curve_color(curve.id, *current)))
                    .on_hover_text(&curve.label);
            }
            ui.end_row();
            for pass in passes {
                ui.label(RichText::new(pass.as_str()).color(pass_color(pass)));
                for (_, _, summary) in &columns {
                    ui.label(cell(summary.pass_ms_median.get(pass)));
                }
                ui.end_row();
            }
            ui.strong("frame");
            for (_, _, summary) in &columns {
                ui.label(cell(summary.frame_gpu_ms_median.as_ref()));
            }
            ui.end_row();
        });
}

/// A curve's colour, kept when it becomes a previous (dimmed) curve.
fn curve_color(id: u64, current: bool) -> Color32 {
    const PALETTE: [Color32; 6] = [
        Color32::from_rgb(90, 170, 255),
        Color32::from_rgb(255, 150, 60),
        Color32::from_rgb(110, 220, 110),
        Color32::from_rgb(240, 90, 200),
        Color32::from_rgb(240, 220, 80),
        Color32::from_rgb(160, 130, 255),
    ];
    let c = PALETTE[(id % PALETTE.len() as u64) as usize];
    if current { c } else { c.gamma_multiply(0.4) }
}

/// "2: temporal off" in its colour: the name a curve has in legends and tables.
fn curve_name(curve: &Curve) -> String {
    format!("{}: {}", curve.id + 1, curve.label)
}

fn curve_text(curve: &Curve, current: bool) -> RichText {
    RichText::new(curve_name(curve)).color(curve_color(curve.id, current))
}

/// Three significant digits: errors differ by orders of magnitude between scenes.
pub fn significant(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return v.to_string();
    }
    let decimals = (2 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{v:.decimals$}")
}
