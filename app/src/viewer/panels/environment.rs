//! The Scene panel's environment part: what lights the sky (or nothing), opening one by
//! path, the built-in sky, removing it; an .hdr/.exr dropped on the window replaces it
//! (`scene::take_dropped_files`). A failed load keeps the previous one.

use egui::Ui;

use super::scene_rows::{facts, open_row};
use crate::viewer::state::{Action, ViewerState};

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    ui.separator();
    let info = state
        .scene
        .info
        .as_ref()
        .and_then(|i| i.environment.clone());
    match &info {
        Some(e) => {
            ui.strong(format!("Environment: {}", e.name));
            facts(
                ui,
                "environment facts",
                &[
                    ("Size", format!("{}×{}", e.width, e.height)),
                    ("Strength", format!("{}", e.strength)),
                    ("Rotation", format!("{}° about +Y", e.rotation_deg)),
                    (
                        "Light share",
                        format!("{:.1} % of light samples", e.light_share * 100.0),
                    ),
                    (
                        "Distribution",
                        format!("built in {:.0} ms", e.distribution_build_ms),
                    ),
                ],
            );
        }
        None => {
            ui.label("Environment: none");
        }
    }
    // Not "Open": that button loads scenes.
    let mut request = open_row(
        ui,
        &mut state.scene.env_open_path,
        "path/to/sky.hdr",
        "Open environment",
    )
    .map(Some);
    ui.horizontal(|ui| {
        if ui.button("Built-in sky").clicked() {
            request = Some(Some(restir_render::environment::BUILTIN_SKY.to_string()));
        }
        if info.is_some() && ui.button("None").clicked() {
            request = Some(None);
        }
    });
    ui.weak(
        "…or drop an .hdr/.exr on the window (strength and rotation: --env-strength, --env-rotation)",
    );
    if let Some(r) = request {
        state.request(Action::LoadEnvironment(r));
    }
    if let Some(error) = &state.scene.env_error {
        ui.colored_label(
            ui.visuals().error_fg_color,
            format!("Could not load: {error}"),
        );
        ui.weak("The previous environment is still used.");
    }
}
