//! The Accuracy panel: the reference of the current view (progress while it renders),
//! the current errors as numbers, and per configuration the error and time curves
//! (`accuracy_plots.rs`). It edits plain state; `viewer/accuracy/tracker.rs` does the work.

use egui::Ui;
use restir_render::Settings;

use super::accuracy_plots::{self, significant};
use crate::viewer::accuracy::{AccuracyState, Curve, PhaseStatus, ReferenceStatus, SPP_CHOICES};
use crate::viewer::state::ViewerState;

pub fn ui(ui: &mut Ui, state: &mut ViewerState) {
    if state.time.duration > 0.0 && state.time.playing {
        ui.label(
            "Scene time is playing: a reference is of one moment, and per-frame references \
             are far too slow to render live on a CPU. Nothing is measured until time is \
             paused; then the reference is of the paused moment. For lag over time use \
             `bench` (docs/src/measured/dynamic-scenes.md).",
        );
        return;
    }
    let is_cpu = state.device.is_cpu;
    let accuracy = &mut state.accuracy;
    egui::ComboBox::from_label("Reference spp")
        .selected_text(accuracy.reference_spp.to_string())
        .show_ui(ui, |ui| {
            for spp in SPP_CHOICES {
                ui.selectable_value(&mut accuracy.reference_spp, spp, spp.to_string());
            }
        })
        .response
        .on_hover_text("Samples per pixel of the reference (light + BSDF MIS, cached on disk). More: less of its own noise in every number below, a longer first render");
    reference_status(ui, accuracy);
    jitter_note(ui, &mut state.settings, state.accuracy.phases.as_ref());
    ui.separator();
    let accuracy = &mut state.accuracy;
    match &accuracy.curves.current {
        Some(curve) => current_numbers(ui, curve),
        None if accuracy.curves.is_empty() => {
            ui.weak("Curves start once the reference is there. Changing a parameter or the mode starts a new curve; the previous ones stay, dimmed.");
            return;
        }
        None => {}
    }
    accuracy_plots::ui(ui, &accuracy.curves);
    measuring(ui, accuracy, is_cpu);
}

/// Where the reference stands (also the error view's legend).
pub fn reference_status(ui: &mut Ui, accuracy: &AccuracyState) {
    match &accuracy.reference {
        ReferenceStatus::Idle => {
            ui.weak("Reference: not needed yet");
        }
        ReferenceStatus::WaitingForStill => {
            ui.horizontal_wrapped(|ui| {
                ui.spinner();
                ui.label("View changed: the reference starts once camera, size and jitter stay unchanged for a moment");
            });
        }
        ReferenceStatus::Starting => {
            ui.horizontal_wrapped(|ui| {
                ui.spinner();
                ui.label("Reference: looking in the cache…");
            });
        }
        ReferenceStatus::Rendering(p) => {
            let eta = p
                .eta()
                .map(|d| format!(", ~{:.0} s left", d.as_secs_f64()))
                .unwrap_or_default();
            ui.label("Rendering the reference in the background");
            // Keeps the bar moving while the viewer is frozen (it redraws only on demand).
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(250));
            ui.add(egui::ProgressBar::new(p.fraction() as f32).text(format!(
                "{}/{} spp ({:.1} s{eta})",
                p.samples_done,
                p.samples_total,
                p.elapsed.as_secs_f64()
            )));
        }
        ReferenceStatus::Ready(info) => {
            let origin = if info.from_cache {
                "loaded from the cache".to_string()
            } else {
                format!("rendered in {:.1} s", info.meta.render_seconds)
            };
            ui.label(format!("Reference: {} spp, {origin}", info.meta.spp))
                .on_hover_text(info.path.display().to_string());
            if let Some(noise) = info.meta.noise_luma_rmse {
                ui.weak(format!(
                    "Its own noise: luma RMSE ≈ {noise:.2e} (errors near this are the reference's)"
                ));
            }
        }
        ReferenceStatus::Failed(e) => {
            ui.colored_label(
                ui.visuals().error_fg_color,
                format!("Reference failed: {e}"),
            );
        }
    }
}

/// With jitter on each frame shades one sub-pixel offset; against the antialiased
/// reference its error would be mostly the pixel footprint, the same for every estimator.
/// So per-frame errors are measured against the reference of the frame's own offset
/// (docs/src/viewer.md, "Accuracy with jitter on"), rendered one offset after another.
fn jitter_note(ui: &mut Ui, settings: &mut Settings, phases: Option<&PhaseStatus>) {
    if !settings.jitter {
        ui.weak("Jitter off: frames and reference shade the same rasterised surfaces, so the errors measure lighting alone (as the bench does)");
        return;
    }
    ui.label("Jitter is on: each frame's per-frame error is measured against the reference of its own sub-pixel offset, so it measures the estimator, not the pixel footprint; accumulated errors against the antialiased reference");
    let period = restir_render::renderer::JITTER_PERIOD;
    match phases {
        None => {
            ui.weak("Per-offset references start once the antialiased reference is there");
        }
        Some(p) => {
            ui.label(format!(
                "Offsets with a reference: {} of {period} (frames at the others are not scored yet)",
                p.ready
            ));
            if let Some((phase, progress)) = &p.rendering {
                ui.add(
                    egui::ProgressBar::new(progress.fraction() as f32).text(format!(
                        "offset {phase}: {}/{} spp",
                        progress.samples_done, progress.samples_total
                    )),
                );
                ui.ctx()
                    .request_repaint_after(std::time::Duration::from_millis(250));
            }
            if let Some(e) = &p.failed {
                ui.colored_label(
                    ui.visuals().error_fg_color,
                    format!("Offset reference failed: {e}"),
                );
            }
        }
    }
    if ui
        .button("Jitter off for measuring")
        .on_hover_text("Sets the jitter parameter off, as the bench measures: one reference serves every frame, instead of one per sub-pixel offset")
        .clicked()
    {
        settings.jitter = false;
    }
}

fn current_numbers(ui: &mut Ui, curve: &Curve) {
    let Some(last) = curve.last() else {
        ui.weak(format!(
            "{}: waiting for the first measured frame",
            curve.label
        ));
        return;
    };
    ui.strong(format!("{} · frame {}", curve.label, last.x));
    let number = |v: Option<f64>| v.map_or("–".to_string(), significant);
    egui::Grid::new("accuracy numbers")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            let rows = [
                (
                    "Per-frame luma RMSE",
                    format!(
                        "{} (mean {})",
                        number(Some(last.luma_rmse)),
                        number(curve.mean_luma_rmse())
                    ),
                    "This frame against the reference (per-frame accuracy)",
                ),
                (
                    "Stability",
                    format!("mean {}", number(curve.mean_stability())),
                    "Luma RMSE between consecutive measured frames: flicker and boiling",
                ),
                (
                    "Accumulated RGB RMSE",
                    number(Some(last.accumulated_rgb_rmse)),
                    "The average of this curve's measured frames against the reference: it falls as frames accumulate; where it levels off, what remains is bias (or the reference's own noise)",
                ),
                (
                    "Luma ratio",
                    number(Some(last.luma_ratio)),
                    "Mean luminance of that average over the reference's: 1 = no energy bias",
                ),
                (
                    "Signed bias",
                    format!("{:+.2} %", 100.0 * last.signed_bias),
                    "(mean luminance of a frame − the reference's) / the reference's, averaged over this curve's frames: 0 = no energy bias, negative = too dark; the bias view shows where",
                ),
            ];
            for (name, value, doc) in rows {
                ui.label(name).on_hover_text(doc);
                ui.label(value);
                ui.end_row();
            }
        });
}

/// What measuring costs and how often it runs.
fn measuring(ui: &mut Ui, accuracy: &mut AccuracyState, is_cpu: bool) {
    ui.horizontal_wrapped(|ui| {
        if let Some(ms) = accuracy.measure_ms {
            let rate = match accuracy.frames_skipped {
                0 => "every frame".to_string(),
                n => format!("1 frame in {}", n + 1),
            };
            ui.weak(format!("Readback + metrics: {ms:.1} ms per measured frame; {rate}"));
        }
        ui.checkbox(&mut accuracy.every_frame, "Every frame")
            .on_hover_text("Measure every frame even when reading it back is slow (by default measuring takes at most a quarter of the time)");
        if ui.small_button("Clear curves").clicked() {
            accuracy.curves.clear();
        }
    });
    if is_cpu && matches!(accuracy.reference, ReferenceStatus::Rendering(_)) {
        ui.weak("Pass times are inflated while the reference renders: on a CPU adapter both share the cores");
    }
}
