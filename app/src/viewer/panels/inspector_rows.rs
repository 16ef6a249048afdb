//! The lines both parts of the pixel inspector write the same way (DI and GI in
//! `inspector.rs`, PT in `inspector_pt.rs`): a position, and a stage's rejection bits with
//! their names, in the warning colour when a check fired.

use egui::{RichText, Ui};
use restir_render::shader_constants::REJECT_REASON_NAMES;

/// A point or vector, three decimals per axis.
pub(super) fn vec3(v: [f32; 3]) -> String {
    format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2])
}

/// The names of DI's `REJECT_*` bits set in `mask` (PT's previous-pixel checks are the
/// same G-buffer checks).
pub(super) fn reject_names(mask: u32) -> Vec<&'static str> {
    REJECT_REASON_NAMES
        .iter()
        .enumerate()
        .filter(|(b, _)| mask & (1 << b) != 0)
        .map(|(_, n)| *n)
        .collect()
}

/// "{stage} rejections: 0b… names", in the warning colour when a check fired.
pub(super) fn rejections(ui: &mut Ui, stage: &str, mask: u32, names: &[&str]) {
    let text = if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    };
    let rich = RichText::new(format!("{stage} rejections: {mask:#010b} {text}"));
    ui.label(if names.is_empty() {
        rich
    } else {
        rich.color(ui.visuals().warn_fg_color)
    });
}
