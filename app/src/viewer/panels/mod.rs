//! The side panel: one collapsible section per panel, each in its own file, each editing
//! the plain `ViewerState` (never the renderer).

pub mod accuracy;
pub mod accuracy_plots;
pub mod camera;
pub mod compare;
pub mod environment;
pub mod inspector;
mod inspector_pt;
mod inspector_rows;
pub mod palette;
pub mod pipeline;
pub mod pixel_history;
pub mod scene;
mod scene_rows;
pub mod stats;
pub mod time;
pub mod tour;
pub mod view;

#[cfg(test)]
mod tests;

use egui::Ui;

use super::state::{Action, ViewerState};

/// Default width of the side panel in points.
pub const PANEL_WIDTH: f32 = 380.0;

/// The side panel (H hides it; dragging its edge resizes or closes it).
pub fn side_panel(ui: &mut Ui, state: &mut ViewerState) {
    scene::take_dropped_files(ui.ctx(), state);
    // Stays false while the panel is hidden (H): `sections` sets it when drawn.
    state.accuracy.panel_open = false;
    let mut open = state.panel_open;
    egui::Panel::right("controls")
        .resizable(true)
        .default_size(PANEL_WIDTH)
        .size_range(200.0..=900.0)
        .show_collapsible(ui, &mut open, |ui| {
            // Fill the panel's width (labels wrap at it) instead of shrinking to the content,
            // which would make the panel's width follow whatever section is open.
            egui::ScrollArea::vertical()
                .auto_shrink([false, true])
                .show(ui, |ui| sections(ui, state));
        });
    state.panel_open = open;
}

fn sections(ui: &mut Ui, state: &mut ViewerState) {
    let section = |title: &str, open: bool| {
        egui::CollapsingHeader::new(title)
            .id_salt(("section", title))
            .default_open(open)
    };
    if state.tour.is_some() {
        section("Tour", true).show(ui, |ui| tour::ui(ui, state));
    }
    section("Pipeline", true).show(ui, |ui| pipeline::ui(ui, state));
    section("View", true).show(ui, |ui| view::ui(ui, state));
    section("Compare", false).show(ui, |ui| compare::ui(ui, state));
    // Measuring reads every frame back: it runs while this section is drawn open.
    state.accuracy.panel_open = section("Accuracy", false)
        .show(ui, |ui| accuracy::ui(ui, state))
        .body_returned
        .is_some();
    section("Stats", true).show(ui, |ui| stats::ui(ui, state));
    if state.time.duration > 0.0 {
        section("Time", true).show(ui, |ui| time::ui(ui, &mut state.time));
    }
    section("Camera", false).show(ui, |ui| camera::ui(ui, &mut state.camera));
    section("Scene", false).show(ui, |ui| scene::ui(ui, state));
    // Picking a pixel opens the inspector and brings it into view (once: afterwards the
    // user may collapse it or scroll away).
    let reveal = std::mem::take(&mut state.inspector.reveal);
    let inspector = section("Pixel inspector", false)
        .open(reveal.then_some(true))
        .show(ui, |ui| {
            inspector::ui(ui, &mut state.inspector);
            pixel_history::ui(ui, state);
        });
    if reveal {
        inspector
            .header_response
            .scroll_to_me(Some(egui::Align::Min));
    }
}

/// Keys that work anywhere while no text field has focus: H (hide/show the panel), F12
/// (screenshot), F (frame the scene from the current direction), P (freeze), N (step one frame while frozen), PageDown / PageUp (the
/// tour's next / previous step), Escape (drop the inspected pixel; deliberately not a
/// quit key in a viewer kept open all day).
pub fn shortcuts(ctx: &egui::Context, state: &mut ViewerState) {
    if ctx.text_edit_focused() {
        return;
    }
    let pressed = |key| ctx.input(|i| i.key_pressed(key));
    if pressed(egui::Key::H) {
        state.panel_open = !state.panel_open;
    }
    if pressed(egui::Key::F12) {
        state.request(Action::Screenshot);
    }
    if pressed(egui::Key::F) {
        let (w, h) = state.render_size;
        let aspect = if w > 0 && h > 0 {
            w as f32 / h as f32
        } else {
            16.0 / 9.0
        };
        state.camera.frame_scene(aspect);
    }
    if pressed(egui::Key::P) {
        state.inspector.frozen = !state.inspector.frozen;
    }
    if pressed(egui::Key::N) && state.inspector.frozen {
        state.inspector.step = true;
    }
    if pressed(egui::Key::Escape) {
        state.inspector.pixel = None;
    }
    if pressed(egui::Key::PageDown) {
        super::tour::advance(state, 1);
    }
    if pressed(egui::Key::PageUp) {
        super::tour::advance(state, -1);
    }
}
