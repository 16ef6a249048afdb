//! The image in the scene area: one renderer's picture, or the split screen — A left of a
//! divider the mouse drags, B right of it (X swaps the sides), each labelled with its
//! configuration and, when the Accuracy reference exists, its per-frame error.

use egui::{Color32, CursorIcon, Key, Pos2, Rect, Sense, Ui, Vec2};

use super::state::ViewerState;

/// The textures to draw: A always, B while the comparison runs.
#[derive(Clone, Copy, Debug)]
pub struct Images {
    pub a: egui::TextureId,
    pub b: Option<egui::TextureId>,
}

/// Points either side of the divider line that grab it.
const GRAB: f32 = 5.0;

/// Draws the image(s) over `rect` and handles the divider and the swap key.
pub fn show(ui: &mut Ui, rect: Rect, images: Option<Images>, state: &mut ViewerState) {
    let Some(images) = images else {
        ui.painter().rect_filled(rect, 0.0, Color32::BLACK);
        return;
    };
    let b = match images.b {
        Some(b) if state.compare.enabled => b,
        _ => {
            let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
            ui.painter().image(images.a, rect, uv, Color32::WHITE);
            return;
        }
    };
    if ui.input(|i| i.key_pressed(Key::X)) && !ui.ctx().text_edit_focused() {
        state.compare.flipped = !state.compare.flipped;
    }
    let (left, right) = if state.compare.flipped {
        (b, images.a)
    } else {
        (images.a, b)
    };
    let d = state.compare.divider.clamp(0.0, 1.0);
    let x = rect.left() + d * rect.width();
    let painter = ui.painter_at(rect);
    let part = |x0: f32, x1: f32, u0: f32, u1: f32, id| {
        let r = Rect::from_min_max(Pos2::new(x0, rect.top()), Pos2::new(x1, rect.bottom()));
        let uv = Rect::from_min_max(Pos2::new(u0, 0.0), Pos2::new(u1, 1.0));
        painter.image(id, r, uv, Color32::WHITE);
    };
    part(rect.left(), x, 0.0, d, left);
    part(x, rect.right(), d, 1.0, right);

    // The divider: drawn on top of both, dragged with the left button.
    let grab = Rect::from_min_max(
        Pos2::new(x - GRAB, rect.top()),
        Pos2::new(x + GRAB, rect.bottom()),
    );
    let response = ui.interact(
        grab,
        ui.make_persistent_id("compare divider"),
        Sense::drag(),
    );
    if let Some(p) = response
        .interact_pointer_pos()
        .filter(|_| response.dragged())
    {
        state.compare.divider = ((p.x - rect.left()) / rect.width()).clamp(0.0, 1.0);
    }
    if response.hovered() || response.dragged() {
        ui.ctx().set_cursor_icon(CursorIcon::ResizeHorizontal);
    }
    painter.line_segment(
        [Pos2::new(x, rect.top()), Pos2::new(x, rect.bottom())],
        (2.0, Color32::WHITE),
    );
    let (a_label, b_label) = labels(state);
    let (left_label, right_label) = if state.compare.flipped {
        (b_label, a_label)
    } else {
        (a_label, b_label)
    };
    tag(
        &painter,
        Pos2::new(x - 8.0, rect.bottom() - 8.0),
        left_label,
        true,
    );
    tag(
        &painter,
        Pos2::new(x + 8.0, rect.bottom() - 8.0),
        right_label,
        false,
    );
}

/// "A: restir · RMSE 0.123" and "B: ris · RMSE 0.456" (errors once a reference exists);
/// with jitter on "RMSE 0.123 per offset": each frame against its own sub-pixel offset's
/// reference (docs/src/viewer.md, "Accuracy with jitter on").
fn labels(state: &ViewerState) -> (String, String) {
    let how = if state.settings.jitter {
        " per offset"
    } else {
        ""
    };
    let error = |e: Option<f64>| e.map_or(String::new(), |e| format!(" · RMSE {e:.3}{how}"));
    let errors = state.compare.errors;
    (
        format!("A: {}{}", a_name(state), error(errors.map(|e| e.0))),
        format!("B: {}{}", state.compare.spec, error(errors.map(|e| e.1))),
    )
}

/// What A is: the mode, or the denoiser's companion preset while it is on.
fn a_name(state: &ViewerState) -> &str {
    if state.denoised_preset.is_on() {
        "restir-denoised"
    } else {
        state.mode.name()
    }
}

/// A label with a dark background, its bottom corner at `anchor` (right-aligned when
/// `to_left`).
fn tag(painter: &egui::Painter, anchor: Pos2, text: String, to_left: bool) {
    let galley = painter.layout_no_wrap(text, egui::FontId::proportional(14.0), Color32::WHITE);
    let size = galley.size();
    let min = if to_left {
        anchor - size
    } else {
        anchor - Vec2::new(0.0, size.y)
    };
    painter.rect_filled(
        Rect::from_min_size(min, size).expand(4.0),
        3.0,
        Color32::from_black_alpha(160),
    );
    painter.galley(min, galley, Color32::WHITE);
}
