//! The View panel: what is shown (final image or a debug view, with its legend), exposure
//! and tonemapper, progressive accumulation, render scale and screenshots. None of this
//! changes the estimate.

use egui::Ui;
use restir_render::pt::constants::PT_FAIL_NAMES;
use restir_render::shader_constants::{
    BIAS_BATCH, BIAS_NEGLIGIBLE, BIAS_SIGNIFICANCE, BOILING_THRESHOLD, BOILING_VIEW_MAX,
    GI_REJECT_REASON_NAMES, MAX_BOUNCES, PROPOSER_NAMES, REJECT_REASON_NAMES,
    REJECT_TEMPORAL_REASONS, TEMPORAL_WINDOW_FRAMES,
};
use restir_render::{DebugView, Settings, Tonemapper, ViewSettings};

use super::accuracy;
use super::palette::{
    PT_DEPTHS, PT_JACOBIAN_SATURATION, bias_color, gi_reason_color, jacobian_colors,
    proposer_color, pt_depth_color, pt_failure_color, pt_pure_replay_color, ramp, reason_color,
    source_legend, spatial_count_ramp, swatch,
};
use crate::viewer::state::{Action, DisplayOptions, ViewerState};

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    egui::ComboBox::from_label("Debug view")
        .selected_text(state.view.view.name())
        .show_ui(ui, |ui| {
            for v in DebugView::ALL {
                ui.selectable_value(&mut state.view.view, v, v.name())
                    .on_hover_text(describe(v));
            }
        })
        .response
        .on_hover_text(describe(state.view.view));
    legend(ui, state);
    ui.separator();

    ui.horizontal(|ui| {
        ui.add(
            egui::Slider::new(&mut state.view.exposure_ev, -16.0..=16.0)
                .text("Exposure (EV)")
                .max_decimals(2),
        );
        if ui
            .button("Auto")
            .on_hover_text("Log-average luminance of this frame to middle grey")
            .clicked()
        {
            state.request(Action::AutoExposure);
        }
    });
    egui::ComboBox::from_label("Tonemapper")
        .selected_text(state.view.tonemapper.name())
        .show_ui(ui, |ui| {
            for t in Tonemapper::ALL {
                ui.selectable_value(&mut state.view.tonemapper, t, t.name());
            }
        });
    ui.horizontal(|ui| {
        ui.checkbox(&mut state.view.accumulate, "Accumulate")
            .on_hover_text("Show the running average of frames; it restarts on any change of camera, scene, size, mode or parameter");
        ui.weak(format!("{} frames", state.accumulated_frames));
        if ui.small_button("Restart").clicked() {
            state.request(Action::ResetAccumulation);
        }
    });
    ui.separator();
    display_ui(
        ui,
        &mut state.display,
        state.render_size,
        state.device.is_cpu,
    );
    ui.separator();
    screenshot_ui(ui, state);
}

fn describe(v: DebugView) -> &'static str {
    match v {
        DebugView::Final => "The tonemapped image",
        DebugView::Source => "Which stage's candidate survived: initial, temporal or spatial",
        DebugView::M => "Confidence M of the final reservoir, 0 to the M cap",
        DebugView::Rejection => {
            "Why the temporal candidate was rejected (first reason among those enabled below); elsewhere, how many spatial neighbours were"
        }
        DebugView::Weight => {
            "Contribution weight W on a log scale, 1e-4 to 1e4; null samples black"
        }
        DebugView::Normals => "Shading normals as colour",
        DebugView::Albedo => "Base colour",
        DebugView::Depth => "View depth relative to the scene size (near is bright)",
        DebugView::Motion => "Screen-space motion to the previous frame (grey: none)",
        DebugView::Error => {
            "|frame - reference| luminance against the reference of the Accuracy panel (obtained in the background while the camera stands still)"
        }
        DebugView::Difference => {
            "|A - B| luminance between the two sides of the split-screen comparison (Compare section)"
        }
        DebugView::Bias => {
            "Running average minus the reference (Accuracy panel), signed: blue darker, red brighter; grey where the difference is within the noise of the average"
        }
        DebugView::Age => {
            "Frames since the surviving sample was first drawn, 0 to 2 × the M cap; null samples black"
        }
        DebugView::Indirect => {
            "ReSTIR GI or PT (whichever runs): the indirect radiance alone, tonemapped like the image"
        }
        DebugView::GiSource => {
            "ReSTIR GI: which stage's sample survived: initial, temporal or spatial"
        }
        DebugView::GiM => "ReSTIR GI: confidence M of the final GI reservoir, 0 to the GI M cap",
        DebugView::GiRejection => {
            "ReSTIR GI: why the temporal candidate was rejected (first reason); elsewhere, how many spatial neighbours were"
        }
        DebugView::GiJacobian => {
            "ReSTIR GI: |J| of the surviving sample's last shift on a log scale: blue below 1, white at 1, red above, saturating at the Jacobian window"
        }
        DebugView::PtLength => {
            "ReSTIR PT: the surviving path's length, its surface vertices x_1 … x_n (2 to max bounces); null paths black"
        }
        DebugView::PtReconnection => {
            "ReSTIR PT: the depth of the surviving path's reconnection vertex x_(k+1); magenta where the path is replayed whole (no reconnection vertex)"
        }
        DebugView::PtFailure => {
            "ReSTIR PT: the shifts into this pixel this frame (the previous pixel's path and the spatial neighbours'): the commonest failure's colour, brighter the larger the share that failed; dark green where every path moved"
        }
        DebugView::PtJacobian => {
            "ReSTIR PT: |J| of the surviving path's last shift on a log scale: blue below 1, white at 1 (found here), red above, saturating at 1/16 and 16"
        }
        DebugView::DenoiseInput => "Denoiser: the frame before it (raw), tonemapped like the image",
        DebugView::HistoryLength => {
            "Denoiser: frames in each pixel's temporal history, 0 to the history cap (dark where it restarted: disocclusions, a cut)"
        }
        DebugView::DenoiseVariance => {
            "Denoiser: σ / mean of each pixel's luminance from its temporal moments, 0 to 1 (where the luminance gate blurs most)"
        }
        DebugView::TemporalGradient => {
            "Denoiser: λ, the share of the neighbourhood's lighting that changed since last frame (temporal gradients), 0 to 1; black where gradients are off"
        }
        DebugView::Proposer => {
            "Light samplers: which strategy proposed the initial survivor (a BSDF ray, the power table, a light tile, a ReGIR slot, the light BVH)"
        }
        DebugView::UsefulCandidates => {
            "Light samplers: the share of a pixel's light candidates that can light it at all (unshadowed contribution > 0), 0 to 1"
        }
        DebugView::RegirCell => {
            "Light samplers: the ReGIR cell each pixel lies in (a colour per cell; black outside the grid around the camera)"
        }
        DebugView::Boiling => {
            "Where the image flickers: each pixel's σ/mean of luminance over the last 16 frames"
        }
        DebugView::SurvivorChange => {
            "How often each pixel's surviving light changed over the last 16 frames"
        }
    }
}

fn legend(ui: &mut Ui, state: &mut ViewerState) {
    match state.view.view {
        DebugView::Source => source_legend(ui, str::to_string),
        DebugView::M => ramp(ui, "0", &format!("M cap ({})", state.settings.m_cap)),
        DebugView::Age => ramp(
            ui,
            "0",
            &format!("2 × M cap ({})", 2.0 * state.settings.m_cap),
        ),
        DebugView::Weight => ramp(ui, "W 1e-4", "1e4"),
        DebugView::Error => {
            ramp(ui, "0", "1 (at this exposure)");
            // The reference is the Accuracy panel's; until it is there the view shows |frame|.
            accuracy::reference_status(ui, &state.accuracy);
        }
        DebugView::Bias => {
            bias_legend(ui);
            accuracy::reference_status(ui, &state.accuracy);
        }
        DebugView::Rejection => rejection_legend(ui, &mut state.view, &state.settings),
        DebugView::Difference => {
            ramp(ui, "0", "1 (at this exposure)");
            if !state.compare.enabled {
                ui.weak("Turn on Compare to choose B: until then the difference is to black.");
            }
        }
        DebugView::GiSource => source_legend(ui, str::to_string),
        DebugView::GiM => ramp(ui, "0", &format!("GI M cap ({})", state.settings.gi_m_cap)),
        DebugView::GiRejection => gi_rejection_legend(ui),
        DebugView::Boiling | DebugView::SurvivorChange => window_legend(ui, state),
        DebugView::GiJacobian => jacobian_legend(ui, state.settings.gi_jacobian_max.max(1.0)),
        DebugView::PtLength => {
            pt_depth_legend(ui, &state.settings, |n| format!("n = {n}"));
            ui.weak("black: no path (null reservoir)");
        }
        DebugView::PtReconnection => {
            pt_depth_legend(ui, &state.settings, |d| format!("x{d}"));
            ui.horizontal(|ui| {
                swatch(ui, pt_pure_replay_color());
                ui.label("replayed whole (no reconnection vertex)");
            });
            ui.weak("black: no path (null reservoir)");
        }
        DebugView::PtFailure => pt_failure_legend(ui),
        DebugView::HistoryLength => ramp(
            ui,
            "1 frame",
            &format!("history cap ({})", state.settings.denoise_history_cap),
        ),
        DebugView::DenoiseVariance => ramp(ui, "σ/mean 0", "1"),
        DebugView::TemporalGradient => ramp(ui, "λ 0 (unchanged)", "1 (all changed)"),
        DebugView::Proposer => proposer_legend(ui),
        DebugView::UsefulCandidates => ramp(ui, "0 useful", "all candidates useful"),
        DebugView::PtJacobian => {
            jacobian_legend(ui, PT_JACOBIAN_SATURATION);
            ui.weak("white: the pixel's own path (|J| = 1); black: no path");
        }
        _ => {}
    }
    if let Some(off) = technique_off(state.view.view, &state.settings) {
        ui.weak(off);
    }
}

/// Why a technique's view has nothing of this frame to show: the technique it draws is off.
/// `indirect` is drawn by whichever of GI and PT runs (PT replaces GI while on).
fn technique_off(view: DebugView, settings: &Settings) -> Option<&'static str> {
    let (gi, pt) = (settings.gi && !settings.pt, settings.pt);
    if view == DebugView::Indirect {
        return (!gi && !pt).then_some(
            "ReSTIR GI and PT are off (Indirect section): this view has nothing to show until one runs.",
        );
    }
    if view.is_indirect() && !gi {
        return Some(if pt {
            "ReSTIR PT replaces GI while on (Indirect section): the gi- views have nothing to show; the pt- views show its paths."
        } else {
            "ReSTIR GI is off (Indirect section): this view has nothing to show until it runs."
        });
    }
    if view.is_denoise_view() && !settings.denoise {
        return Some(
            "The denoiser is off (Denoiser section): this view has nothing to show until it runs.",
        );
    }
    (view.is_path_view() && !pt).then_some(
        "ReSTIR PT is off (Indirect section): this view has nothing to show until it runs.",
    )
}

/// The proposer palette, one swatch per strategy.
fn proposer_legend(ui: &mut Ui) {
    egui::Grid::new(ui.next_auto_id())
        .num_columns(3)
        .show(ui, |ui| {
            for (p, name) in PROPOSER_NAMES.iter().enumerate() {
                ui.horizontal(|ui| {
                    swatch(ui, proposer_color(p as u32));
                    ui.label(*name);
                });
                if p % 3 == 2 {
                    ui.end_row();
                }
            }
        });
}

/// A log |J| ramp's three anchors, saturating at 1/`w` and `w`.
fn jacobian_legend(ui: &mut Ui, w: f32) {
    let [low, one, high] = jacobian_colors();
    ui.horizontal(|ui| {
        swatch(ui, low);
        ui.label(format!("|J| ≤ 1/{w}"));
        swatch(ui, one);
        ui.label("1");
        swatch(ui, high);
        ui.label(format!("≥ {w}"));
    });
}

/// The PT depth palette from 2 to the deepest vertex a path can have now (max_bounces,
/// at least 2, as shaders/pt/path.wgsl clamps it), each swatch named by `label(d)`. Four to a row
/// so it fits the panel.
fn pt_depth_legend(ui: &mut Ui, settings: &Settings, label: fn(u32) -> String) {
    let deepest = settings.max_bounces.clamp(2, MAX_BOUNCES);
    egui::Grid::new(ui.next_auto_id())
        .num_columns(4)
        .show(ui, |ui| {
            for (i, d) in PT_DEPTHS.filter(|&d| d <= deepest).enumerate() {
                ui.horizontal(|ui| {
                    swatch(ui, pt_depth_color(d));
                    ui.label(label(d));
                });
                if i % 4 == 3 {
                    ui.end_row();
                }
            }
        });
}

/// The shift outcomes and their colours; the view dims a failure where few shifts failed.
fn pt_failure_legend(ui: &mut Ui) {
    egui::Grid::new("pt failure legend")
        .num_columns(2)
        .show(ui, |ui| {
            for (f, name) in PT_FAIL_NAMES.iter().enumerate() {
                ui.label(if f == 0 { "every shift moved" } else { name });
                swatch(ui, pt_failure_color(f as u32));
                ui.end_row();
            }
        });
    ui.weak(
        "the commonest failure among the shifts into the pixel (the previous pixel's path and \
         the spatial neighbours'), brighter the larger the share that failed; black: none tried",
    );
}

/// The bias view: the diverging ramp, and what grey means.
fn bias_legend(ui: &mut Ui) {
    let negligible = 100.0 * BIAS_NEGLIGIBLE;
    ui.horizontal(|ui| {
        ui.label("−25 %");
        let (rect, _) = ui.allocate_exact_size(egui::vec2(140.0, 12.0), egui::Sense::hover());
        let steps = 28;
        let w = rect.width() / steps as f32;
        for s in 0..steps {
            let cell = egui::Rect::from_min_size(
                egui::pos2(rect.left() + s as f32 * w, rect.top()),
                egui::vec2(w + 0.5, rect.height()),
            );
            let t = 2.0 * (s as f32 + 0.5) / steps as f32 - 1.0;
            ui.painter().rect_filled(cell, 0.0, bias_color(t));
        }
        ui.label("+25 %");
    });
    ui.weak(format!(
        "(average − reference) / reference of the running average. Grey (the scene, \
         dimmed): within {BIAS_SIGNIFICANCE} standard errors of the average (the spread of \
         means of {BIAS_BATCH} frames, which holds the frames' correlation) and the \
         reference's noise, or under {negligible} % of the reference: noise, not bias. All \
         grey until {} frames have accumulated.",
        2 * BIAS_BATCH
    ));
}

/// The temporal window views: the palette, the window and how full it is.
fn window_legend(ui: &mut Ui, state: &ViewerState) {
    if state.view.view == DebugView::Boiling {
        ramp(ui, "σ/mean 0", &format!("{BOILING_VIEW_MAX}"));
        ui.weak(format!(
            "past {BOILING_THRESHOLD} (the middle, teal) a pixel counts as boiling"
        ));
    } else {
        ramp(ui, "never changed", "every frame");
    }
    ui.weak(format!(
        "window: {} of {TEMPORAL_WINDOW_FRAMES} frames (restarts on a cut or a new scene); black: not yet two frames",
        state.window_frames
    ));
    if state.view.view == DebugView::SurvivorChange && state.mode == restir_render::Mode::Reference
    {
        ui.weak("The reference keeps no reservoirs: nothing to change.");
    }
}

/// The GI rejection reasons and their colours.
fn gi_rejection_legend(ui: &mut Ui) {
    ui.weak("temporal: first reason; black: nothing rejected");
    egui::Grid::new("gi rejection legend")
        .num_columns(2)
        .show(ui, |ui| {
            for (bit, name) in GI_REJECT_REASON_NAMES.iter().enumerate() {
                ui.label(*name);
                swatch(ui, gi_reason_color(bit as u32));
                ui.end_row();
            }
        });
    ui.weak("spatial (where temporal passed): grey = share of neighbours rejected");
}

/// Temporal: one row per reason, its colour, a toggle (shown in the view or not) and
/// "only" to show that reason alone. Spatial: the rejected-neighbour count's grey ramp.
fn rejection_legend(ui: &mut Ui, view: &mut ViewSettings, settings: &Settings) {
    ui.horizontal(|ui| {
        ui.strong("temporal");
        if ui.small_button("All").clicked() {
            view.reason_mask = REJECT_TEMPORAL_REASONS;
        }
        if ui.small_button("None").clicked() {
            view.reason_mask = 0;
        }
        ui.weak("black: nothing rejected");
    });
    egui::Grid::new("rejection legend")
        .num_columns(2)
        .show(ui, |ui| {
            for (bit, name) in REJECT_REASON_NAMES.iter().enumerate() {
                ui.label(*name);
                ui.horizontal(|ui| {
                    swatch(ui, reason_color(bit as u32));
                    let mut on = view.reason_mask & (1 << bit) != 0;
                    if ui
                        .checkbox(&mut on, "")
                        .on_hover_text(format!("show temporal {name}"))
                        .changed()
                    {
                        view.reason_mask ^= 1 << bit;
                    }
                    if ui
                        .small_button("only")
                        .on_hover_text(format!("show temporal {name} alone"))
                        .clicked()
                    {
                        view.reason_mask = 1 << bit;
                    }
                });
                ui.end_row();
            }
        });
    ui.horizontal(|ui| {
        ui.strong("spatial");
        ui.checkbox(&mut view.spatial_count, "rejected neighbours")
            .on_hover_text(
                "Where the temporal candidate was not rejected: how many of the spatial neighbours tried were rejected, for any reason (Stats lists the reasons)",
            );
    });
    let tries = settings.spatial_neighbours * settings.spatial_passes;
    spatial_count_ramp(ui, "0", &format!("all {tries} tried"));
}

fn display_ui(ui: &mut Ui, display: &mut DisplayOptions, render_size: (u32, u32), is_cpu: bool) {
    ui.add(egui::Slider::new(&mut display.render_scale, DisplayOptions::SCALE_RANGE).text("Render scale").max_decimals(2))
        .on_hover_text(if is_cpu {
            "Render at this fraction of the window's pixels. A CPU adapter (lavapipe) starts small to stay interactive."
        } else {
            "Render at this fraction of the window's pixels"
        });
    ui.horizontal(|ui| {
        ui.checkbox(&mut display.smooth, "Smooth upscaling");
        ui.weak(format!("{}×{} px", render_size.0, render_size.1));
    });
}

fn screenshot_ui(ui: &mut Ui, state: &mut ViewerState) {
    ui.horizontal(|ui| {
        if ui
            .button("Screenshot (F12)")
            .on_hover_text("PNG of the window and of the image, EXR of the linear radiance")
            .clicked()
        {
            state.request(Action::Screenshot);
        }
        ui.add(
            egui::TextEdit::singleline(&mut state.screenshot_dir)
                .desired_width(120.0)
                .hint_text("folder"),
        );
    });
    if let Some(message) = &state.screenshot_message {
        ui.weak(message);
    }
    record_ui(ui, state);
}

/// Record: every rendered frame as PNG (what is shown) or EXR (linear), and/or a GIF.
fn record_ui(ui: &mut Ui, state: &mut ViewerState) {
    use crate::recording::SequenceFormat;
    let rec = &mut state.recording;
    let mut toggle = false;
    ui.horizontal(|ui| {
        let label = if rec.active {
            "Stop recording"
        } else {
            "Record"
        };
        toggle = ui
            .add(egui::Button::new(label).selected(rec.active))
            .on_hover_text(
                "Every rendered frame (the split screen as shown) into a new recording-N folder",
            )
            .clicked();
        ui.add_enabled(
            !rec.active,
            egui::TextEdit::singleline(&mut rec.dir)
                .desired_width(120.0)
                .hint_text("folder"),
        );
    });
    ui.add_enabled_ui(!rec.active, |ui| {
        ui.horizontal(|ui| {
            let name = |f: Option<SequenceFormat>| match f {
                Some(SequenceFormat::Png) => "PNG frames",
                Some(SequenceFormat::Exr) => "EXR frames (linear)",
                None => "no frames",
            };
            egui::ComboBox::from_label("and")
                .selected_text(name(rec.sequence))
                .show_ui(ui, |ui| {
                    for f in [Some(SequenceFormat::Png), Some(SequenceFormat::Exr), None] {
                        ui.selectable_value(&mut rec.sequence, f, name(f));
                    }
                });
            ui.checkbox(&mut rec.gif, "GIF");
        });
    });
    if let Some(message) = &rec.message {
        ui.weak(message);
    }
    if toggle {
        let action = if rec.active {
            Action::StopRecording
        } else {
            Action::StartRecording
        };
        state.request(action);
    }
}
