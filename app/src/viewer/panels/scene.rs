//! The Scene panel: what is loaded (counts, light power range, the file's glTF extensions
//! and what the loader did with each, the compiled effect set and why), the built-in scene picker and opening a glTF file by path or drag-and-drop;
//! the environment part is `environment.rs`.

use egui::Ui;
use restir_render::scene::builtin::catalogue;

use super::environment;
use super::scene_rows::{facts, open_row};
use crate::viewer::state::{Action, ViewerState};

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    let scene = &state.scene;
    if let Some(info) = &scene.info {
        // Name and source may be long paths: wrapped labels, not grid cells.
        ui.strong(&info.name);
        if scene.spec != info.name {
            ui.weak(&scene.spec);
        }
        facts(
            ui,
            "scene facts",
            &[
                ("Triangles", info.triangles.to_string()),
                ("Emissive triangles", info.emissive_triangles.to_string()),
                ("Punctual lights", info.punctual_lights.to_string()),
                ("Light table entries", info.light_table_entries.to_string()),
                (
                    "Light power",
                    info.power_range
                        .map_or("no lights".to_string(), |(lo, hi)| {
                            format!("{lo:.3e} … {hi:.3e} (total {:.3e})", info.total_power)
                        }),
                ),
                (
                    "BVH",
                    format!(
                        "{} nodes, depth {}, {:.0} ms",
                        info.bvh_nodes, info.bvh_depth, info.bvh_build_ms
                    ),
                ),
                (
                    // An animated scene's tree keeps them in their own subtree.
                    "BVH moving part",
                    match info.bvh_moving_triangles {
                        0 => "none".to_string(),
                        moving => format!("{moving} triangles, own subtree"),
                    },
                ),
                (
                    "Ray-query structures",
                    info.accel
                        .map_or("none (no ray queries on this device)".to_string(), |a| {
                            format!(
                                "{} BLAS, {} instances, {} of {} triangles opaque, {:.0} ms",
                                a.blas_count,
                                a.instance_count,
                                a.opaque_triangles,
                                info.triangles,
                                a.build_ms
                            )
                        }),
                ),
            ],
        );
        extensions(ui, &info.extensions);
        load_phases(ui, &scene.load);
    }
    let mut pick = None;
    egui::ComboBox::from_label("Built-in scene")
        .selected_text(builtin_label(&scene.spec))
        .show_ui(ui, |ui| {
            for (name, line) in catalogue() {
                // A family (`city:N`) needs its count: type `builtin:city:4096` in the
                // path box below, or pass it to `--scene`.
                if name.ends_with(":N") {
                    continue;
                }
                let row = ui.selectable_label(scene.spec == name, &name);
                if row.on_hover_text(line).clicked() {
                    pick = Some(name);
                }
            }
        });
    if let Some(path) = open_row(ui, &mut state.scene.open_path, "path/to/scene.gltf", "Open") {
        pick = Some(path);
    }
    ui.weak("…or drop a .gltf/.glb file on the window");
    if let Some(spec) = pick {
        state.request(Action::LoadScene(spec));
    }
    status(ui, state);
    environment::ui(ui, state);
    effects(ui, state);
}

/// The file's glTF extensions and what the loader did with each (used, partly used and
/// what is ignored, or ignored), wrapped: the details can be long.
fn extensions(ui: &mut Ui, extensions: &[restir_render::scene::ExtensionUse]) {
    if extensions.is_empty() {
        return;
    }
    ui.label(format!("glTF extensions ({})", extensions.len()));
    for e in extensions {
        ui.add(egui::Label::new(format!("• {e}")).wrap());
    }
}

fn builtin_label(spec: &str) -> &str {
    if spec.starts_with("builtin:") {
        spec
    } else {
        "(file)"
    }
}

/// How long each phase from file to first frame took (`bench-load` prints the same).
fn load_phases(ui: &mut Ui, load: &restir_render::load_phases::LoadPhases) {
    if load.phases.is_empty() {
        return;
    }
    let title = format!("Load phases ({:.1} s)", load.total_ms() / 1e3);
    egui::CollapsingHeader::new(title)
        .id_salt("load phases")
        .show(ui, |ui| {
            egui::Grid::new("load phase grid")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    for p in &load.phases {
                        ui.label(p.name);
                        ui.label(format!("{:.0} ms", p.ms)).on_hover_text(&p.detail);
                        ui.end_row();
                    }
                });
        });
}

fn status(ui: &mut Ui, state: &ViewerState) {
    if let Some(loading) = &state.scene.loading {
        let progress = &state.scene.progress;
        let phase = if progress.phase.is_empty() {
            "starting".to_string()
        } else {
            progress.phase.clone()
        };
        // The phase's own count where it has one (images), else the phases done.
        let bar = egui::ProgressBar::new(progress.fraction.unwrap_or(0.0))
            .text(format!("loading: {phase}"))
            .animate(progress.fraction.is_none());
        ui.add(bar);
        ui.weak(loading);
        ui.weak(if state.scene.first_frame_waits {
            "The first frame waits for its shaders; the panels work meanwhile."
        } else {
            "The current scene stays interactive while the file loads."
        });
    }
    if let Some(error) = &state.scene.error {
        ui.colored_label(
            ui.visuals().error_fg_color,
            format!("Could not load: {error}"),
        );
        ui.weak("The previous scene is still shown.");
    }
}

fn effects(ui: &mut Ui, state: &ViewerState) {
    let Some(effects) = &state.scene.effects else {
        return;
    };
    let title = format!(
        "Effects compiled: {} of {}",
        effects.enabled.len(),
        effects.reasons.len()
    );
    egui::CollapsingHeader::new(title)
        .id_salt("effects")
        .show(ui, |ui| {
            for (effect, reason) in &effects.reasons {
                let on = effects.contains(*effect);
                ui.horizontal_wrapped(|ui| {
                    ui.label(if on { "on " } else { "off" });
                    ui.strong(effect.name());
                    ui.weak(reason);
                });
            }
            ui.label(format!("Passes: {}", state.scene.passes.join(" > ")));
        });
}

/// Files dropped on the window replace the scene, or the environment for .hdr/.exr (the
/// last one wins).
pub fn take_dropped_files(ctx: &egui::Context, state: &mut ViewerState) {
    let dropped = ctx.input(|i| {
        i.raw
            .dropped_files
            .iter()
            .map(|f| f.path().to_path_buf())
            .next_back()
    });
    if let Some(path) = dropped {
        let spec = path.display().to_string();
        if crate::viewer::scene_loader::is_environment_spec(&spec) {
            state.request(Action::LoadEnvironment(Some(spec)));
        } else {
            state.request(Action::LoadScene(spec));
        }
    }
}
