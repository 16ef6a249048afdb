//! The scene area (egui's central panel): the rendered image stretched over it, the fly
//! camera's input, and picking a pixel for the inspector (click, or Alt + hover).

use egui::{Color32, Key, PointerButton, Pos2, Rect, Sense, Ui, Vec2};

use super::camera::FlyInput;
use super::state::ViewerState;

/// Points of wheel scrolling that count as one speed step.
const POINTS_PER_WHEEL_STEP: f32 = 50.0;

pub use super::split_view::Images;

/// Shows the scene area and handles its input; returns its rectangle in points.
pub fn show(ui: &mut Ui, state: &mut ViewerState, images: Option<Images>) -> Rect {
    egui::CentralPanel::no_frame()
        .show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let response = ui.allocate_rect(rect, Sense::click_and_drag());
            // Keyboard focus follows the pointer onto the image (unless text is being
            // typed), so Space flies up instead of pressing the last clicked button.
            if response.hovered() && !ui.ctx().text_edit_focused() {
                response.request_focus();
            }
            super::split_view::show(ui, rect, images, state);
            let input = fly_input(ui, &response);
            let dt = ui.input(|i| i.unstable_dt).clamp(0.0, 0.25);
            state.camera.fly(&input, dt);
            pick_pixel(ui, &response, rect, state);
            overlay(ui, rect, state);
            rect
        })
        .inner
}

/// Keys while egui has no text focus, right-drag and the wheel over the scene.
fn fly_input(ui: &Ui, response: &egui::Response) -> FlyInput {
    let keyboard = !ui.ctx().text_edit_focused();
    let mut input = ui.input(|i| {
        let axis = |plus: &[Key], minus: &[Key]| {
            let down = |keys: &[Key]| keys.iter().any(|k| i.key_down(*k));
            (down(plus) as i32 - down(minus) as i32) as f32
        };
        let wheel: f32 = i
            .events
            .iter()
            .filter_map(|e| match e {
                egui::Event::MouseWheel { unit, delta, .. } => Some(match unit {
                    egui::MouseWheelUnit::Point => delta.y / POINTS_PER_WHEEL_STEP,
                    _ => delta.y,
                }),
                _ => None,
            })
            .sum();
        let mut input = FlyInput {
            wheel,
            fast: i.modifiers.shift,
            ..Default::default()
        };
        if keyboard {
            input.forward = axis(&[Key::W], &[Key::S]);
            input.right = axis(&[Key::D], &[Key::A]);
            input.up =
                axis(&[Key::E, Key::Space], &[Key::Q]) - if i.modifiers.ctrl { 1.0 } else { 0.0 };
        }
        input
    });
    if !response.hovered() {
        input.wheel = 0.0;
    }
    if response.dragged_by(PointerButton::Secondary) {
        let d = response.drag_delta();
        input.look = glam::Vec2::new(d.x, d.y);
    }
    input
}

/// The render-target pixel under `pos`.
fn pixel_at(pos: Pos2, rect: Rect, size: (u32, u32)) -> Option<(u32, u32)> {
    if !rect.contains(pos) || size.0 == 0 || size.1 == 0 {
        return None;
    }
    let t = (pos - rect.min) / rect.size();
    let x = ((t.x * size.0 as f32) as u32).min(size.0 - 1);
    let y = ((t.y * size.1 as f32) as u32).min(size.1 - 1);
    Some((x, y))
}

fn pick_pixel(ui: &Ui, response: &egui::Response, rect: Rect, state: &mut ViewerState) {
    let alt_hover = ui.input(|i| i.modifiers.alt) && response.hovered();
    let pos = if response.clicked_by(PointerButton::Primary) {
        response.interact_pointer_pos()
    } else if alt_hover {
        response.hover_pos()
    } else {
        None
    };
    if let Some(pixel) = pos.and_then(|p| pixel_at(p, rect, state.render_size)) {
        // A click reveals the inspector; hovering with Alt only updates it.
        state.inspector.reveal |= !alt_hover && state.inspector.pixel != Some(pixel);
        state.inspector.pixel = Some(pixel);
    }
}

/// The inspected pixel's outline and the status words over the image.
fn overlay(ui: &Ui, rect: Rect, state: &ViewerState) {
    let painter = ui.painter_at(rect);
    let waiting = if state.scene.first_frame_waits {
        let phase = &state.scene.progress.phase;
        Some(format!(
            "Preparing the first frame ({}): its shaders compile beside the window",
            if phase.is_empty() { "starting" } else { phase }
        ))
    } else if state.scene.pipelines_warming {
        Some("Compiling the pipelines this change needs, beside the window…".to_string())
    } else {
        None
    };
    if let Some(text) = waiting {
        let galley =
            painter.layout_no_wrap(text, egui::FontId::proportional(16.0), Color32::LIGHT_GRAY);
        let at = rect.center() - galley.size() / 2.0;
        painter.rect_filled(
            egui::Rect::from_min_size(at, galley.size()).expand(6.0),
            4.0,
            Color32::from_black_alpha(200),
        );
        painter.galley(at, galley, Color32::LIGHT_GRAY);
    }
    let (w, h) = state.render_size;
    if let Some((x, y)) = state.inspector.pixel
        && w > 0
        && h > 0
    {
        let cell = rect.size() / Vec2::new(w as f32, h as f32);
        let min = rect.min + Vec2::new(x as f32, y as f32) * cell;
        let pixel = Rect::from_min_size(min, cell).expand(1.0);
        painter.rect_stroke(
            pixel,
            0.0,
            (1.5, Color32::from_rgb(255, 0, 200)),
            egui::StrokeKind::Outside,
        );
        let c = pixel.center();
        for d in [Vec2::X, Vec2::Y] {
            painter.line_segment(
                [
                    c - d * (cell.max_elem() + 8.0),
                    c - d * (cell.max_elem() * 0.5 + 3.0),
                ],
                (1.0, Color32::WHITE),
            );
            painter.line_segment(
                [
                    c + d * (cell.max_elem() * 0.5 + 3.0),
                    c + d * (cell.max_elem() + 8.0),
                ],
                (1.0, Color32::WHITE),
            );
        }
    }
    let mut words = Vec::new();
    if state.inspector.frozen {
        words.push("FROZEN (P to resume, N to step)".to_string());
    }
    if let Some(spec) = &state.scene.loading {
        words.push(format!("loading {spec}…"));
    }
    if !state.panel_open {
        words.push("H: show panel".to_string());
    }
    if !words.is_empty() {
        let text = words.join("\n");
        let pos = rect.left_top() + Vec2::splat(8.0);
        let galley = painter.layout_no_wrap(text, egui::FontId::proportional(14.0), Color32::WHITE);
        painter.rect_filled(
            Rect::from_min_size(pos, galley.size()).expand(4.0),
            3.0,
            Color32::from_black_alpha(160),
        );
        painter.galley(pos, galley, Color32::WHITE);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_map_from_points_to_the_render_target() {
        let rect = Rect::from_min_size(Pos2::new(10.0, 20.0), Vec2::new(400.0, 200.0));
        assert_eq!(
            pixel_at(Pos2::new(10.0, 20.0), rect, (100, 50)),
            Some((0, 0))
        );
        assert_eq!(
            pixel_at(Pos2::new(409.9, 219.9), rect, (100, 50)),
            Some((99, 49))
        );
        assert_eq!(
            pixel_at(Pos2::new(210.0, 120.0), rect, (100, 50)),
            Some((50, 25))
        );
        assert_eq!(pixel_at(Pos2::new(5.0, 20.0), rect, (100, 50)), None);
    }
}

#[cfg(test)]
mod input_tests {
    use egui_kittest::Harness;

    use super::*;
    use crate::viewer::camera::CameraState;
    use crate::viewer::state::DisplayOptions;
    use restir_render::scene::Aabb;
    use restir_render::{Camera, Settings};

    fn state() -> ViewerState {
        let bounds = Aabb {
            min: glam::Vec3::splat(-1.0),
            max: glam::Vec3::splat(1.0),
        };
        let camera = CameraState::new(
            Camera::look_at(glam::Vec3::new(0.0, 0.0, 5.0), glam::Vec3::ZERO, 0.8),
            bounds,
        );
        let mut s = ViewerState::new(
            Settings::default(),
            camera,
            DisplayOptions::for_adapter(true),
        );
        s.render_size = (100, 50);
        s
    }

    #[test]
    fn keys_fly_and_a_click_picks_a_pixel() {
        let mut h = Harness::builder()
            .with_size(egui::vec2(400.0, 200.0))
            .build_ui_state(
                |ui, s: &mut ViewerState| {
                    show(ui, s, None);
                },
                state(),
            );
        let start = h.state().camera.camera.position;
        h.key_down(Key::W);
        h.run_steps(5);
        h.key_up(Key::W);
        h.run();
        let moved = h.state().camera.camera.position - start;
        assert!(
            moved.z < 0.0 && moved.x.abs() < 1e-5,
            "W moves forward (-Z here): {moved:?}"
        );
        // A click at the centre of the 400×200 area picks pixel (50, 25) of 100×50.
        let pos = Pos2::new(201.0, 101.0);
        h.hover_at(pos);
        for pressed in [true, false] {
            h.event(egui::Event::PointerButton {
                pos,
                button: PointerButton::Primary,
                pressed,
                modifiers: Default::default(),
            });
            h.run();
        }
        assert_eq!(h.state().inspector.pixel, Some((50, 25)));
    }
}
