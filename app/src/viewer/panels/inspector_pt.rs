//! The pixel inspector's ReSTIR PT section: how the shifts into the pixel went (the
//! previous pixel's path, the spatial neighbours'), M after each PT stage, the path
//! reservoir each stage kept and that path's vertices x_1 … x_n, z.

use egui::{RichText, Ui};
use restir_render::pt::constants::{PT_FAIL_NONE, PT_FAIL_REASON_COUNT};
use restir_render::renderer::{PtInspection, PtStagePath, PtVertex};

use super::inspector_rows::{reject_names, rejections, vec3};

/// Marks the reconnection vertex x_{k+1} in the vertex lists. A lozenge: the default
/// proportional font (Ubuntu-Light) has it, not the filled diamond ◆.
const RECONNECTION_MARK: &str = "◊ reconnection";

pub fn pt_inspection(ui: &mut Ui, pt: &PtInspection) {
    ui.strong("Indirect (ReSTIR PT)");
    shifts(ui, pt);
    let d = &pt.debug;
    ui.label(format!(
        "PT M after initial / temporal / spatial: {} / {} / {} · |J| of the survivor's last shift: {:.4}",
        d.m_initial, d.m_temporal, d.m_spatial, d.jacobian
    ));
    egui::ScrollArea::horizontal()
        .id_salt("pt reservoirs")
        .show(ui, |ui| stage_grid(ui, &pt.stages));
    for stage in &pt.stages {
        vertices(ui, stage);
    }
}

/// The temporal shift's outcome (after the previous pixel's G-buffer checks) and the
/// spatial neighbours' outcomes with their counts. Failures are in the warning colour: a
/// failed shift is a zero in its domain under pairwise MIS, not a rejection, but it is
/// where reuse gained nothing.
fn shifts(ui: &mut Ui, pt: &PtInspection) {
    let d = &pt.debug;
    rejections(
        ui,
        "PT temporal",
        d.temporal_mask,
        &reject_names(d.temporal_mask),
    );
    let temporal = match pt.temporal_outcome() {
        Some(outcome) => outcome,
        None => "not tried (no history, or the previous pixel failed its checks)",
    };
    let failed = pt.temporal_outcome().is_some() && d.temporal_failure != PT_FAIL_NONE;
    outcome_line(ui, format!("PT temporal shift: {temporal}"), failed);
    let outcomes = pt.spatial_outcomes();
    let listed = if outcomes.is_empty() {
        "none".to_string()
    } else {
        let named: Vec<String> = outcomes
            .iter()
            .map(|(name, n)| format!("{name} × {n}"))
            .collect();
        named.join(", ")
    };
    let failed = (PT_FAIL_NONE + 1..PT_FAIL_REASON_COUNT as u32).any(|f| d.spatial_count(f) > 0);
    outcome_line(
        ui,
        format!(
            "PT spatial shifts ({} neighbours tried): {listed}",
            d.spatial_tried
        ),
        failed,
    );
}

fn outcome_line(ui: &mut Ui, text: String, failed: bool) {
    let rich = RichText::new(text);
    ui.label(if failed {
        rich.color(ui.visuals().warn_fg_color)
    } else {
        rich
    });
}

/// One column per stage, one row per quantity, like the GI table; a null path shows
/// dashes past its source.
fn stage_grid(ui: &mut Ui, stages: &[PtStagePath]) {
    type Cell = fn(&PtStagePath) -> String;
    fn path(s: &PtStagePath, text: impl FnOnce() -> String) -> String {
        if s.is_null() {
            "–".to_string()
        } else {
            text()
        }
    }
    fn axis(s: &PtStagePath, v: [f32; 3], k: usize) -> String {
        path(s, || format!("{:.3}", v[k]))
    }
    /// The radiance beyond x_{k+1} matters only where the path reconnects.
    fn suffix(s: &PtStagePath, k: usize) -> String {
        match s.reconnection_step() {
            Some(_) => axis(s, s.reservoir.rc_suffix, k),
            None => "–".to_string(),
        }
    }
    let rows: [(&str, Cell); 15] = [
        ("source", |s| s.source_name().to_string()),
        ("length n", |s| path(s, || s.length().to_string())),
        ("end", |s| path(s, || s.end_name().to_string())),
        ("reconnection k", |s| {
            path(s, || match s.reconnection_step() {
                Some(k) => format!("{k} (at x{})", k + 1),
                None => "none (replayed whole)".to_string(),
            })
        }),
        ("lobes", |s| path(s, || s.lobes().join(", "))),
        ("value r", |s| axis(s, s.reservoir.value, 0)),
        ("value g", |s| axis(s, s.reservoir.value, 1)),
        ("value b", |s| axis(s, s.reservoir.value, 2)),
        ("p_hat", |s| format!("{:.4e}", s.reservoir.p_hat)),
        ("W", |s| format!("{:.4e}", s.reservoir.weight)),
        ("M", |s| format!("{}", s.reservoir.m)),
        ("|J|", |s| {
            path(s, || format!("{:.4}", s.reservoir.jacobian))
        }),
        ("rc suffix r", |s| suffix(s, 0)),
        ("rc suffix g", |s| suffix(s, 1)),
        ("rc suffix b", |s| suffix(s, 2)),
    ];
    ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Extend);
    egui::Grid::new("pt reservoirs")
        .num_columns(1 + stages.len())
        .striped(true)
        .show(ui, |ui| {
            ui.strong("stage");
            for stage in stages {
                ui.strong(stage.stage);
            }
            ui.end_row();
            for (name, cell) in rows {
                ui.label(name);
                for stage in stages {
                    ui.label(cell(stage));
                }
                ui.end_row();
            }
        });
}

/// A stage's path, one vertex a line: x_1 … x_n, the reconnection vertex marked, then the
/// light end z (a point, or a direction for the environment).
fn vertices(ui: &mut Ui, stage: &PtStagePath) {
    ui.label(RichText::new(format!("{} path", stage.stage)).strong());
    ui.indent(("pt vertices", stage.stage), |ui| {
        if stage.is_null() {
            ui.weak("no path");
            return;
        }
        for (i, v) in stage.vertices.iter().enumerate() {
            ui.label(vertex_line(i, v));
        }
        // x_1 … x_n and z: fewer when the rebuild from this frame's camera left the path.
        let whole = stage.length() as usize + 1;
        if stage.vertices.len() < whole {
            ui.weak(format!(
                "rebuilt {} of {whole} vertices: replaying the path from this frame's camera left it",
                stage.vertices.len()
            ));
        }
    });
}

/// "x2 (…)", "x3 ◊ reconnection (…)", "z light (…)" or "z direction (…)".
fn vertex_line(index: usize, v: &PtVertex) -> String {
    let name = match (v.light, v.direction) {
        (_, true) => "z direction".to_string(),
        (true, false) => "z light".to_string(),
        _ => format!("x{}", index + 1),
    };
    let mark = if v.reconnection {
        format!(" {RECONNECTION_MARK}")
    } else {
        String::new()
    };
    format!("{name}{mark} {}", vec3(v.position))
}
