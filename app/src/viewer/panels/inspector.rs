//! The pixel inspector: one pixel's reservoir after each stage (light id, sample point,
//! p_hat, W, M, w_sum, source), its surface, and which rejection tests fired and why.
//! Freeze stops new frames; Step renders exactly one.

use egui::{RichText, Ui};
use restir_render::gpu_types::NO_LIGHT;
use restir_render::renderer::PixelInspection;
use restir_render::shader_constants::*;

use crate::viewer::state::InspectorState;

pub fn ui(ui: &mut Ui, inspector: &mut InspectorState) {
    ui.weak("Click the image, or hold Alt and hover, to pick a pixel.");
    ui.horizontal(|ui| {
        match inspector.pixel {
            Some((x, y)) => ui.label(format!("Pixel {x}, {y}")),
            None => ui.label("No pixel selected"),
        };
        if inspector.pixel.is_some() && ui.small_button("Clear").clicked() {
            inspector.pixel = None;
            inspector.last = None;
        }
    });
    ui.horizontal(|ui| {
        ui.checkbox(&mut inspector.frozen, "Freeze")
            .on_hover_text("Stop rendering new frames (P)");
        if ui
            .add_enabled(inspector.frozen, egui::Button::new("Step"))
            .on_hover_text("Render one frame (N)")
            .clicked()
        {
            inspector.step = true;
        }
    });
    match &inspector.last {
        Some(i) if Some(i.pixel) == inspector.pixel => inspection(ui, i),
        _ if inspector.pixel.is_some() && inspector.frozen => {
            ui.weak("Frozen: Step (N) renders a frame that captures this pixel.");
        }
        _ if inspector.pixel.is_some() => {
            ui.weak("waiting for the next frame…");
        }
        _ => {}
    }
}

fn vec3(v: [f32; 3]) -> String {
    format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2])
}

/// Everything known about the pixel in one frame.
pub fn inspection(ui: &mut Ui, i: &PixelInspection) {
    ui.label(format!("Frame {}", i.frame));
    let s = &i.surface;
    if s.depth <= 0.0 {
        ui.label("No surface: the pixel sees the background.");
        return;
    }
    ui.label(format!(
        "Surface at {} · depth {:.3} · material {}",
        vec3(s.position),
        s.depth,
        s.material
    ));
    let d = &i.debug;
    ui.label(format!(
        "Final: source {} · W {:.4e} · p_hat {:.4e}",
        i.source_name(),
        d.weight,
        d.p_hat
    ));
    ui.label(format!(
        "M after initial / temporal / spatial: {} / {} / {}",
        d.m_initial, d.m_temporal, d.m_spatial
    ));
    reservoirs(ui, i);
    rejections(ui, "Temporal", d.temporal_mask, &i.temporal_rejections());
    rejections(ui, "Spatial", d.spatial_mask, &i.spatial_rejections());
    ui.label(format!("Spatial neighbours merged: {}", d.spatial_accepted));
    ui.label(format!("Flags: {}", flag_names(d.flags)));
}

/// One row per stage. The table scrolls sideways rather than widening the side panel.
fn reservoirs(ui: &mut Ui, i: &PixelInspection) {
    egui::ScrollArea::horizontal()
        .id_salt("reservoirs")
        .show(ui, |ui| reservoir_grid(ui, i));
}

fn reservoir_grid(ui: &mut Ui, i: &PixelInspection) {
    egui::Grid::new("reservoirs")
        .num_columns(9)
        .striped(true)
        .show(ui, |ui| {
            for h in [
                "stage",
                "light",
                "uv",
                "sample point",
                "p_hat",
                "W",
                "M",
                "w_sum",
                "source",
                "age",
            ] {
                ui.strong(h);
            }
            ui.end_row();
            for stage in &i.stages {
                let r = &stage.reservoir;
                ui.label(&stage.stage);
                if r.light == NO_LIGHT {
                    ui.label("null");
                    ui.label("–");
                    ui.label("–");
                } else {
                    ui.label(r.light.to_string());
                    ui.label(format!("({:.3}, {:.3})", r.uv[0], r.uv[1]));
                    ui.label(stage.sample_point.map_or("?".to_string(), vec3));
                }
                ui.label(format!("{:.4e}", r.p_hat));
                ui.label(format!("{:.4e}", r.weight));
                ui.label(format!("{}", r.m));
                ui.label(format!("{:.4e}", r.w_sum));
                let source = (r.source & SOURCE_MASK) as usize;
                ui.label(SOURCE_NAMES.get(source).copied().unwrap_or("?"));
                ui.label((r.source >> AGE_SHIFT).to_string())
                    .on_hover_text("frames since this sample was first drawn");
                ui.end_row();
            }
        });
}

fn rejections(ui: &mut Ui, stage: &str, mask: u32, names: &[&str]) {
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

fn flag_names(flags: u32) -> String {
    let names: Vec<&str> = [
        (DEBUG_FLAG_TEMPORAL_MERGED, "temporal merged"),
        (DEBUG_FLAG_TEMPORAL_CAP, "temporal M cap fired"),
        (DEBUG_FLAG_SPATIAL_CAP, "spatial M cap fired"),
        (DEBUG_FLAG_FALLBACK_TRIED, "permutation fallback tried"),
        (DEBUG_FLAG_FALLBACK_USED, "permutation fallback used"),
    ]
    .into_iter()
    .filter(|(bit, _)| flags & bit != 0)
    .map(|(_, name)| name)
    .collect();
    if names.is_empty() {
        "none".to_string()
    } else {
        names.join(", ")
    }
}
