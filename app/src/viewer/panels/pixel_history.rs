//! The inspector's strip chart of the picked pixel over its last N frames: luminance and
//! the reference there (when the Accuracy reference of this moment exists) on top, M and
//! the survivor's age below, then W (log scale) and a strip of the survivor's source, with
//! the scene's light events as vertical lines; an N field and the CSV export.

use egui::{Color32, Ui};
use egui_plot::{Line, Plot, PlotPoints, PlotUi, VLine};

use super::palette::source_color;
use crate::probe::{PixelHistory, ProbeSample};
use crate::viewer::state::{Action, ViewerState};

const EVENT_COLOR: Color32 = Color32::from_rgb(255, 80, 80);

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    let inspector = &mut state.inspector;
    if inspector.pixel.is_none() {
        return;
    }
    ui.separator();
    ui.horizontal(|ui| {
        ui.strong("Pixel history");
        let label = ui.label("last").id;
        ui.add(
            egui::DragValue::new(&mut inspector.history.capacity)
                .range(PixelHistory::FRAMES_RANGE)
                .suffix(" frames"),
        )
        .labelled_by(label);
        inspector.history.trim();
    });
    let history = &inspector.history;
    if history.samples.is_empty() || history.pixel != inspector.pixel {
        ui.weak("The chart fills as frames render (P freezes, N steps).");
    } else {
        charts(ui, history);
    }
    let mut export = false;
    ui.horizontal(|ui| {
        export = ui
            .button("Export CSV")
            .on_hover_text(
                "One row per frame: luminance, reference, M, W, source, light, age, light event",
            )
            .clicked();
        let to = ui.label("to").id;
        ui.add(egui::TextEdit::singleline(&mut inspector.history_path).desired_width(160.0))
            .labelled_by(to);
    });
    if let Some(message) = &inspector.history_message {
        ui.weak(message);
    }
    if export {
        state.request(Action::ExportPixelHistory);
    }
}

fn charts(ui: &mut Ui, history: &PixelHistory) {
    let samples: Vec<&ProbeSample> = history.samples.iter().collect();
    let x = |s: &ProbeSample| s.frame as f64;
    let series = |f: &dyn Fn(&ProbeSample) -> Option<f64>| -> Vec<[f64; 2]> {
        samples.iter().filter_map(|s| Some([x(s), f(s)?])).collect()
    };
    let events: Vec<f64> = samples.iter().filter(|s| s.event).map(|s| x(s)).collect();
    let mark_events = |plot: &mut PlotUi| {
        for &e in &events {
            plot.vline(VLine::new("light event", e).color(EVENT_COLOR));
        }
    };
    let last = samples.last().expect("not empty");
    ui.label(format!(
        "frame {} · luminance {:.4}{} · M {} · W {:.3e} · {} · age {}",
        last.frame,
        last.luminance,
        last.reference
            .map_or(String::new(), |r| format!(" (reference {r:.4})")),
        last.m,
        last.w,
        last.source_name(),
        last.age
    ));
    strip(
        ui,
        "luminance (reference dashed, light events red)",
        90.0,
        |plot| {
            plot.line(Line::new(
                "luminance",
                PlotPoints::from(series(&|s| Some(s.luminance as f64))),
            ));
            let reference = series(&|s| s.reference.map(f64::from));
            if !reference.is_empty() {
                plot.line(
                    Line::new("reference", PlotPoints::from(reference))
                        .style(egui_plot::LineStyle::dashed_loose()),
                );
            }
            mark_events(plot);
        },
    );
    strip(ui, "M and age (frames)", 70.0, |plot| {
        plot.line(Line::new(
            "M",
            PlotPoints::from(series(&|s| Some(s.m as f64))),
        ));
        plot.line(Line::new(
            "age",
            PlotPoints::from(series(&|s| Some(s.age as f64))),
        ));
        mark_events(plot);
    });
    strip(ui, "log10 W", 60.0, |plot| {
        let w = series(&|s| (s.w > 0.0).then(|| (s.w as f64).log10()));
        plot.line(Line::new("log10 W", PlotPoints::from(w)));
        mark_events(plot);
    });
    source_strip(ui, &samples);
}

fn strip(ui: &mut Ui, title: &str, height: f32, lines: impl FnOnce(&mut PlotUi)) {
    ui.label(title);
    Plot::new(("pixel history", title))
        .height(height)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .show_x(false)
        .legend(egui_plot::Legend::default())
        .show(ui, lines);
}

/// The survivor's source per frame, in the source view's colours (null black).
fn source_strip(ui: &mut Ui, samples: &[&ProbeSample]) {
    ui.label("survivor's source (initial blue, temporal green, spatial orange)");
    let (rect, _) =
        ui.allocate_exact_size(egui::vec2(ui.available_width(), 10.0), egui::Sense::hover());
    let w = rect.width() / samples.len().max(1) as f32;
    for (i, s) in samples.iter().enumerate() {
        let cell = egui::Rect::from_min_size(
            egui::pos2(rect.left() + i as f32 * w, rect.top()),
            egui::vec2(w.max(1.0) + 0.5, rect.height()),
        );
        ui.painter().rect_filled(cell, 0.0, source_color(s.source));
        if s.event {
            ui.painter().rect_filled(
                egui::Rect::from_min_size(cell.min, egui::vec2(1.5, rect.height())),
                0.0,
                EVENT_COLOR,
            );
        }
    }
}
