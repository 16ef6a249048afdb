//! The Compare section: configuration B of the split screen (a mode with these settings,
//! a preset file, or the reference), where the divider is, and each side's error.

use egui::Ui;
use restir_render::Mode;

use crate::viewer::state::ViewerState;

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    let state_jitter = state.settings.jitter;
    let compare = &mut state.compare;
    ui.checkbox(&mut compare.enabled, "Split screen: A | B")
        .on_hover_text("Render configuration B beside the current one (A) every frame, same camera, each with its own history. Drag the divider; X swaps the sides.");
    ui.horizontal(|ui| {
        egui::ComboBox::from_label("B")
            .selected_text(compare.spec.as_str())
            .show_ui(ui, |ui| {
                for mode in Mode::ALL {
                    ui.selectable_value(&mut compare.spec, mode.name().to_string(), mode.name())
                        .on_hover_text(format!("{} with the settings of A", mode.name()));
                }
            });
        ui.add(
            egui::TextEdit::singleline(&mut compare.spec)
                .desired_width(140.0)
                .hint_text("mode or preset.toml"),
        )
        .on_hover_text("A mode (reference, nee, ris, restir: A's settings in that mode) or a preset file (defaults + preset, restir mode)");
    });
    ui.add(egui::Slider::new(&mut compare.divider, 0.0..=1.0).text("Divider"));
    ui.checkbox(&mut compare.flipped, "B on the left (X)");
    if let Some(e) = &compare.error {
        ui.colored_label(ui.visuals().error_fg_color, e);
    }
    if compare.enabled {
        match compare.errors {
            Some((a, b)) => {
                ui.label(format!("Per-frame luma RMSE: A {a:.4} · B {b:.4}"));
                if state_jitter {
                    ui.weak("Jitter on: each frame against the reference of its own sub-pixel offset (see the Accuracy panel)");
                }
            }
            None => {
                ui.weak("Per-frame errors appear once the Accuracy reference of this view is ready (the camera must stand still).");
            }
        }
        ui.weak("Debug view 'difference' shows |A − B|.");
    }
}
