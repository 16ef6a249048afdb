//! The pixel inspector: one pixel's reservoir after each stage (light id, sample point,
//! p_hat, W, M, w_sum, source), its surface, and which rejection tests fired and why;
//! then ReSTIR GI's reservoirs and ReSTIR PT's paths (inspector_pt.rs) when they ran.
//! Freeze stops new frames; Step renders exactly one.

use egui::{RichText, Ui};
use restir_render::di::constants::*;
use restir_render::gpu_types::{GpuSurface, NO_LIGHT};
use restir_render::renderer::{
    DenoiseInspection, GiInspection, GiStageReservoir, PixelInspection, StageReservoir,
};
use restir_render::shader_constants::*;

use super::inspector_pt::pt_inspection;
use super::inspector_rows::{reject_names, rejections, vec3};
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
            inspector.history.clear();
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

/// Everything known about the pixel in one frame.
pub fn inspection(ui: &mut Ui, i: &PixelInspection) {
    ui.label(format!("Frame {}", i.frame));
    let s = &i.surface;
    if s.depth <= 0.0 {
        ui.label("No surface: the pixel sees the background.");
        layers(ui, s);
        return;
    }
    ui.label(format!(
        "Surface at {} · depth {:.3} · material {}",
        vec3(s.position),
        s.depth,
        s.material
    ));
    layers(ui, s);
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
    light_pdfs(ui, i);
    let merged = d.flags & DEBUG_FLAG_TEMPORAL_MERGED != 0;
    di_rejections(ui, "Temporal", d.temporal_mask, merged);
    di_rejections(ui, "Spatial", d.spatial_mask, false);
    ui.label(format!("Spatial neighbours merged: {}", d.spatial_accepted));
    ui.label(format!("Flags: {}", flag_names(d.flags)));
    if let Some(gi) = &i.gi {
        ui.separator();
        gi_inspection(ui, gi);
    }
    if let Some(pt) = &i.pt {
        ui.separator();
        pt_inspection(ui, pt);
    }
    if let Some(d) = &i.denoise {
        ui.separator();
        denoise_inspection(ui, d);
    }
}

/// What each light sampler would give the survivor's light here (docs/src/light-samplers.md).
fn light_pdfs(ui: &mut Ui, i: &PixelInspection) {
    let Some(p) = &i.light_pdfs else {
        return;
    };
    ui.label(format!(
        "Light {}: selection probability {:.3e} by power (and tiles), {} by the light BVH; ReGIR weighs it by its slot's W (no PDF)",
        p.light,
        p.power,
        p.bvh
            .map_or("not built (light_sampler ≠ bvh)".to_string(), |b| format!("{b:.3e}"))
    ));
    ui.label(format!(
        "Proposed by: {}",
        PROPOSER_NAMES
            .get(i.debug.proposer as usize)
            .unwrap_or(&"?")
    ));
}

/// The denoiser at this pixel (docs/src/denoiser.md): how many frames its history holds,
/// how noisy the luminance is by its moments, and the temporal gradient.
fn denoise_inspection(ui: &mut Ui, d: &DenoiseInspection) {
    ui.strong("Denoiser");
    ui.label(format!(
        "History: {} frames · illumination {} · σ/mean {:.3}",
        d.history.length,
        vec3(d.history.illumination),
        d.relative_sigma()
    ));
    ui.label(format!(
        "Temporal gradient λ {:.3} (neighbourhood shading {:.4e} last frame, {:.4e} now)",
        d.gradient, d.gradient_before, d.gradient_now
    ));
}

/// Behind transparent layers (docs/src/transparency.md, "Camera rays"): what this surface's
/// shading is worth, and the light added to it (emission seen, through the layers too,
/// their glass reflection and the share of a layer this surface leaves out).
fn layers(ui: &mut Ui, s: &GpuSurface) {
    if s.transparent_first == 0 {
        return;
    }
    ui.label(format!(
        "Seen through transparent layers: shading × {} · added: {} (emission, glass \
         reflection, the share of a layer this surface leaves out)",
        vec3(s.throughput),
        vec3(s.emission)
    ));
}

/// The ReSTIR GI reservoir after each GI stage, and the GI checks.
fn gi_inspection(ui: &mut Ui, gi: &GiInspection) {
    ui.strong("Indirect (ReSTIR GI)");
    type Cell = fn(&GiStageReservoir) -> String;
    fn axis(s: &GiStageReservoir, v: [f32; 3], k: usize) -> String {
        if s.is_null() {
            "–".to_string()
        } else {
            format!("{:.3}", v[k])
        }
    }
    let rows: [(&str, Cell); 12] = [
        ("source", |s| s.source_name().to_string()),
        ("hit x", |s| axis(s, s.reservoir.position, 0)),
        ("hit y", |s| axis(s, s.reservoir.position, 1)),
        ("hit z", |s| axis(s, s.reservoir.position, 2)),
        ("L_o r", |s| axis(s, s.reservoir.radiance, 0)),
        ("L_o g", |s| axis(s, s.reservoir.radiance, 1)),
        ("L_o b", |s| axis(s, s.reservoir.radiance, 2)),
        ("p_hat", |s| format!("{:.4e}", s.reservoir.p_hat)),
        ("W", |s| format!("{:.4e}", s.reservoir.weight)),
        ("M", |s| format!("{}", s.reservoir.m)),
        ("age", |s| s.age().to_string()),
        ("rejected", |s| {
            let names = s.rejections();
            if names.is_empty() {
                "–".to_string()
            } else {
                names.join(", ")
            }
        }),
    ];
    egui::ScrollArea::horizontal()
        .id_salt("gi reservoirs")
        .show(ui, |ui| {
            ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
            egui::Grid::new("gi reservoirs")
                .num_columns(1 + gi.stages.len())
                .striped(true)
                .show(ui, |ui| {
                    ui.strong("stage");
                    for stage in &gi.stages {
                        ui.strong(&stage.stage);
                    }
                    ui.end_row();
                    for (name, cell) in rows {
                        ui.label(name);
                        for stage in &gi.stages {
                            ui.label(cell(stage));
                        }
                        ui.end_row();
                    }
                });
        });
    let d = &gi.debug;
    rejections(
        ui,
        "GI temporal",
        d.temporal_mask,
        &gi.temporal_rejections(),
    );
    rejections(ui, "GI spatial", d.spatial_mask, &gi.spatial_rejections());
    ui.label(format!(
        "GI spatial neighbours merged: {} · |J| of the survivor's last shift: {:.4}",
        d.spatial_accepted, d.jacobian
    ));
}

/// One column per stage, one row per quantity: three stages fit the side panel at its
/// default width (a row per stage with nine columns did not). More spatial passes scroll
/// sideways rather than widening the panel.
fn reservoirs(ui: &mut Ui, i: &PixelInspection) {
    egui::ScrollArea::horizontal()
        .id_salt("reservoirs")
        .show(ui, |ui| reservoir_grid(ui, i));
}

fn reservoir_grid(ui: &mut Ui, i: &PixelInspection) {
    type Cell = fn(&StageReservoir) -> String;
    /// The sample point, or for an environment sample (no point) its direction.
    fn point(s: &StageReservoir, axis: usize) -> String {
        match (s.reservoir.light, s.environment_direction, s.sample_point) {
            (NO_LIGHT, ..) => "–".to_string(),
            (_, Some(d), _) => format!("dir {:.3}", d[axis]),
            (_, None, Some(p)) => format!("{:.3}", p[axis]),
            (_, None, None) => "?".to_string(),
        }
    }
    let rows: [(&str, Cell); 11] = [
        ("light", |s| {
            match (s.reservoir.light, s.environment_direction) {
                (NO_LIGHT, _) => "null".to_string(),
                (light, Some(_)) => format!("{light} environment"),
                (light, None) => light.to_string(),
            }
        }),
        ("uv", |s| match s.reservoir.light {
            NO_LIGHT => "–".to_string(),
            _ => format!("{:.3}, {:.3}", s.reservoir.uv[0], s.reservoir.uv[1]),
        }),
        ("point x", |s| point(s, 0)),
        ("point y", |s| point(s, 1)),
        ("point z", |s| point(s, 2)),
        ("p_hat", |s| format!("{:.4e}", s.reservoir.p_hat)),
        ("W", |s| format!("{:.4e}", s.reservoir.weight)),
        ("M", |s| format!("{}", s.reservoir.m)),
        ("w_sum", |s| format!("{:.4e}", s.reservoir.w_sum)),
        ("source", |s| {
            SOURCE_NAMES
                .get((s.reservoir.source & SOURCE_MASK) as usize)
                .copied()
                .unwrap_or("?")
                .to_string()
        }),
        // Frames since the sample was first drawn (packed above the source).
        ("age", |s| (s.reservoir.source >> AGE_SHIFT).to_string()),
    ];
    // Cells keep their text on one line: the grid widens a column to fit it (and the
    // scroll area takes the overflow) instead of wrapping into the next column.
    ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
    egui::Grid::new("reservoirs")
        .num_columns(1 + i.stages.len())
        .striped(true)
        .show(ui, |ui| {
            ui.strong("stage");
            for stage in &i.stages {
                ui.strong(&stage.stage);
            }
            ui.end_row();
            for (name, cell) in rows {
                ui.label(name);
                for stage in &i.stages {
                    ui.label(cell(stage));
                }
                ui.end_row();
            }
        });
}

/// DI's checks: the surface checks reject; the sample checks (reservoir null, target 0, ratio,
/// light gone) reject under 1/M and are counted, not rejected, under pairwise MIS
/// (docs/src/mis-and-bias.md, "The two rules of unbiased reuse"). A temporal candidate that merged
/// despite them was pairwise.
fn di_rejections(ui: &mut Ui, stage: &str, mask: u32, merged: bool) {
    let surface = mask & REJECT_SURFACE_CHECKS;
    let sample = mask & !REJECT_SURFACE_CHECKS;
    rejections(ui, stage, surface, &reject_names(surface));
    if sample == 0 {
        return;
    }
    let how = if merged {
        "counted, not rejected (pairwise MIS: merged as a domain of zero contribution)"
    } else {
        "rejected under 1/M; under pairwise MIS these are counted, not rejected"
    };
    let text = format!(
        "{stage} sample checks: {sample:#010b} {} — {how}",
        reject_names(sample).join(", ")
    );
    ui.label(if merged {
        RichText::new(text)
    } else {
        RichText::new(text).color(ui.visuals().warn_fg_color)
    });
}

fn flag_names(flags: u32) -> String {
    let names: Vec<&str> = [
        (DEBUG_FLAG_TEMPORAL_MERGED, "temporal merged"),
        (DEBUG_FLAG_TEMPORAL_CAP, "temporal M cap fired"),
        (DEBUG_FLAG_SPATIAL_CAP, "spatial M cap fired"),
        (DEBUG_FLAG_FALLBACK_TRIED, "permutation fallback tried"),
        (DEBUG_FLAG_FALLBACK_USED, "permutation fallback used"),
        (
            DEBUG_FLAG_ENVIRONMENT_SAMPLE,
            "survivor is an environment direction",
        ),
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
