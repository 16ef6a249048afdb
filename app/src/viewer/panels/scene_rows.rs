//! The rows both parts of the Scene panel draw the same way (the scene in `scene.rs`, its
//! environment in `environment.rs`): a grid of facts, and a path field with its button.

use egui::Ui;

/// A two-column grid of facts.
pub(super) fn facts(ui: &mut Ui, id: &str, rows: &[(&str, String)]) {
    egui::Grid::new(id).num_columns(2).show(ui, |ui| {
        for (k, v) in rows {
            ui.label(*k);
            ui.label(v);
            ui.end_row();
        }
    });
}

/// A path field and a button; the trimmed path when the button is clicked with one.
pub(super) fn open_row(ui: &mut Ui, path: &mut String, hint: &str, button: &str) -> Option<String> {
    let mut picked = None;
    ui.horizontal(|ui| {
        ui.add(
            egui::TextEdit::singleline(path)
                .desired_width(180.0)
                .hint_text(hint),
        );
        if ui.button(button).clicked() && !path.trim().is_empty() {
            picked = Some(path.trim().to_string());
        }
    });
    picked
}
