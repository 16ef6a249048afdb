//! The Tour section (`--tour FILE`): step n of N, its caption, Back / Next (PageUp /
//! PageDown), and the live numbers the step names: each side's per-frame RMSE and signed
//! bias against the Accuracy reference, and the frames each side takes to settle after
//! a light event.

use egui::{RichText, Ui};

use crate::tour::LiveNumber;
use crate::viewer::state::ViewerState;
use crate::viewer::tour::lag::LagMeter;
use crate::viewer::tour::{self, state::SideNumbers};

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    let Some(t) = &state.tour else {
        ui.weak("No tour. Start one with --tour FILE.toml (assets/tours/restir.toml).");
        return;
    };
    let (current, count) = (t.current, t.tour.steps.len());
    let step = t.step().clone();
    ui.label(RichText::new(&t.tour.title).strong());
    let mut go = None;
    ui.horizontal(|ui| {
        if ui
            .add_enabled(current > 0, egui::Button::new("Back"))
            .on_hover_text("The previous step (PageUp)")
            .clicked()
        {
            go = Some(current - 1);
        }
        ui.label(format!("Step {} of {count}", current + 1));
        if ui
            .add_enabled(current + 1 < count, egui::Button::new("Next"))
            .on_hover_text("The next step (PageDown)")
            .clicked()
        {
            go = Some(current + 1);
        }
    });
    ui.heading(&step.title);
    ui.label(&step.caption);
    if t.pending.is_some() {
        ui.weak(format!("loading {}…", step.scene));
    }
    let split = step.compare.is_some();
    let b_label = step.compare.as_ref().map(|b| b.label.clone());
    for number in &step.show {
        numbers(
            ui,
            *number,
            &t.numbers.a,
            &t.numbers.b,
            split,
            b_label.as_deref(),
        );
    }
    if let Some(index) = go {
        tour::go(state, index);
    }
}

fn percent(x: f64) -> String {
    format!("{:+.1} %", 100.0 * x)
}

/// One line of numbers for A (and B).
fn numbers(
    ui: &mut Ui,
    number: LiveNumber,
    a: &SideNumbers,
    b: &SideNumbers,
    split: bool,
    b_label: Option<&str>,
) {
    let sides = |f: &dyn Fn(&SideNumbers) -> Option<String>| -> Option<String> {
        let a = f(a)?;
        if !split {
            return Some(a);
        }
        Some(format!("A {a} · B ({}) {}", b_label.unwrap_or("B"), f(b)?))
    };
    match number {
        LiveNumber::Rmse => match sides(&|s| s.rmse.map(|e| format!("{e:.4}"))) {
            Some(text) => ui.label(format!("Per-frame luma RMSE: {text}")),
            None => ui.weak("Per-frame luma RMSE: once the Accuracy reference is ready (keep the camera still)."),
        },
        LiveNumber::Bias => match sides(&|s| s.bias.map(percent)) {
            Some(text) => ui.label(format!("Signed bias (frame mean vs reference): {text}")),
            None => ui.weak("Signed bias: once the Accuracy reference is ready."),
        },
        LiveNumber::Lag => match sides(&|s| settled(&s.lag)) {
            Some(text) => ui.label(format!("After the last light event: {text}")),
            None => ui.weak(waiting(&a.lag)),
        },
    };
}

fn settled(lag: &LagMeter) -> Option<String> {
    let s = lag.last?;
    let frames = match s.frames {
        Some(f) => format!("settles in {f} frames"),
        None => format!("not settled in {} frames", s.segment),
    };
    Some(format!("{frames} (starts {})", percent(s.start_offset)))
}

fn waiting(lag: &LagMeter) -> String {
    match lag.frames_since_event() {
        None => "Lag: waiting for a light event (time must play).".to_string(),
        Some(k) => {
            format!("Lag: {k} frames since the light event; measured when the next one comes.")
        }
    }
}
