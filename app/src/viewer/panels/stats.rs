//! The Stats panel: frame time, per-pass times (bars and a history plot), what the
//! reuse did over the last frames (rejections by reason, selection sources, M-cap hits)
//! and the non-finite guard's counters per pass.

use std::collections::BTreeMap;

use egui::{Color32, RichText, Ui};
use egui_plot::{Line, Plot, PlotPoints};
use restir_render::shader_constants::{GUARDED_PASS_NAMES, REJECT_REASON_NAMES, STAT_NONFINITE};
use restir_render::stats::{FrameCounters, FrameReport, StatsSummary};
use restir_render::tracing::RayBackend;

use super::palette::source_legend;
use crate::viewer::state::{StatsHistory, ViewerState};

pub fn ui(ui: &mut Ui, state: &ViewerState) {
    let device = &state.device;
    ui.label(format!("{} · timing: {}", device.adapter, device.timing));
    ui.weak(format!("driver: {}", device.driver));
    if device.is_cpu {
        ui.weak("CPU adapter: pass times are CPU wall-clock times, not GPU times");
    }
    ray_backend(ui, device);
    denoise_depth(ui, state);
    frame_time(ui, &state.stats);
    let window = state.stats.window();
    if window.is_empty() {
        ui.weak("waiting for the first frame reports…");
        return;
    }
    let summary = StatsSummary::from_reports(&window, 0);
    ui.label(format!("Summary of the last {} frames", summary.frames));
    pass_bars(ui, &summary.pass_ms_median);
    history_plot(ui, &state.stats);
    reuse(ui, &summary);
    non_finite(ui, &summary, &state.stats.since_load);
}

/// `denoise_auto_depth`: the depth its probe chose and each depth's error against the frame
/// it held out (docs/src/denoiser.md, "Choosing the depth").
fn denoise_depth(ui: &mut Ui, state: &ViewerState) {
    if !(state.settings.denoise && state.settings.denoise_auto_depth) {
        return;
    }
    let Some(choice) = &state.denoise_depth else {
        ui.weak("denoiser depth: probing once the history is warm…");
        return;
    };
    ui.label(format!(
        "denoiser depth: {} à-trous iteration{} (closest to a held-out frame; the probe took \
         {:.0} ms of CPU once)",
        choice.iterations,
        if choice.iterations == 1 { "" } else { "s" },
        choice.probe_ms
    ));
    let errors: Vec<String> = choice
        .held_out_error
        .iter()
        .enumerate()
        .map(|(k, e)| format!("{k}: {e:.2e}"))
        .collect();
    ui.weak(format!(
        "error against the next frame by depth ({} pixels): {}",
        choice.pixels,
        errors.join(" · ")
    ));
}

/// What traces the rays, and whether the other backend could.
fn ray_backend(ui: &mut Ui, device: &crate::viewer::state::DeviceInfo) {
    let Some(backend) = device.ray_backend else {
        return;
    };
    let what = match backend {
        RayBackend::RayQuery => "ray-query (the driver's acceleration structures)",
        RayBackend::Software => "software (BVH walked in WGSL)",
    };
    let available = if device.ray_query {
        "this device also has the other (Pipeline panel, Ray tracing)"
    } else {
        "no hardware ray queries on this device"
    };
    ui.label(format!("Rays: {what}")).on_hover_text(available);
}

/// Width of the longest pass bar, in points.
const BAR_WIDTH: f32 = 150.0;

fn frame_time(ui: &mut Ui, stats: &StatsHistory) {
    let recent: Vec<f64> = stats.frame_ms.iter().rev().take(30).copied().collect();
    if recent.is_empty() {
        return;
    }
    let mean = recent.iter().sum::<f64>() / recent.len() as f64;
    ui.strong(format!(
        "Frame {mean:.1} ms ({:.1} fps)",
        1000.0 / mean.max(1e-3)
    ));
}

/// One bar per pass, the median time over the window, scaled to the slowest pass.
fn pass_bars(ui: &mut Ui, pass_ms: &BTreeMap<String, f64>) {
    if pass_ms.is_empty() {
        ui.weak("no pass timings (timing is off on this adapter)");
        return;
    }
    let total: f64 = pass_ms.values().sum();
    let max = pass_ms.values().copied().fold(0.0, f64::max).max(1e-6);
    ui.label(format!("Passes (median): {total:.2} ms"));
    for (name, ms) in pass_ms {
        ui.horizontal(|ui| {
            let (rect, _) =
                ui.allocate_exact_size(egui::vec2(BAR_WIDTH, 12.0), egui::Sense::hover());
            ui.painter()
                .rect_filled(rect, 2.0, ui.visuals().extreme_bg_color);
            let filled = rect.with_max_x(rect.left() + (rect.width() * (ms / max) as f32).max(1.0));
            ui.painter().rect_filled(filled, 2.0, pass_color(name));
            ui.label(format!("{name}: {ms:.2} ms"));
        });
    }
}

/// A fixed colour per pass name, shared by its bar and its plot line (the bars are the
/// plot's legend).
pub fn pass_color(name: &str) -> Color32 {
    let hash = name
        .bytes()
        .fold(2166136261u32, |h, b| (h ^ b as u32).wrapping_mul(16777619));
    egui::ecolor::Hsva::new((hash % 360) as f32 / 360.0, 0.55, 0.9, 1.0).into()
}

/// Milliseconds per pass (coloured as their bars) and per frame (white) over the kept
/// history.
fn history_plot(ui: &mut Ui, stats: &StatsHistory) {
    let series = pass_series(stats.reports.iter());
    let frame: Vec<[f64; 2]> = stats
        .frame_ms
        .iter()
        .enumerate()
        .map(|(i, ms)| [i as f64, *ms])
        .collect();
    ui.label("History: frame (white) and passes, ms");
    Plot::new("pass history")
        .height(140.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .include_y(0.0)
        .y_axis_label("ms")
        .show(ui, |plot| {
            plot.line(Line::new("frame", PlotPoints::from(frame)).color(Color32::WHITE));
            for (name, points) in series {
                plot.line(Line::new(name, PlotPoints::from(points)).color(pass_color(name)));
            }
        });
}

/// Per pass, (report index, ms) with a pass recorded several times in a frame summed.
fn pass_series<'a>(
    reports: impl Iterator<Item = &'a FrameReport>,
) -> BTreeMap<&'static str, Vec<[f64; 2]>> {
    let mut series: BTreeMap<&'static str, Vec<[f64; 2]>> = BTreeMap::new();
    for (i, report) in reports.enumerate() {
        let mut frame: BTreeMap<&'static str, f64> = BTreeMap::new();
        for (name, ms) in &report.pass_ms {
            *frame.entry(name).or_default() += ms;
        }
        for (name, ms) in frame {
            series.entry(name).or_default().push([i as f64, ms]);
        }
    }
    series
}

fn percent(x: f64) -> String {
    format!("{:.1} %", 100.0 * x)
}

fn reuse(ui: &mut Ui, s: &StatsSummary) {
    let pixels = s.surface_pixels.max(1) as f64;
    ui.label("Selection source (share of surface pixels)");
    source_legend(ui, |name| {
        format!(
            "{name} {}",
            percent(s.source_fractions.get(name).copied().unwrap_or(0.0))
        )
    });
    ui.label(format!(
        "M cap fired: temporal {} · spatial {}",
        percent(s.temporal_cap_fired_fraction),
        percent(s.spatial_cap_fired_fraction)
    ));
    ui.label(format!(
        "Temporal sample merged: {} · permutation fallback {} tried / {} used · boiling drops {}",
        percent(s.temporal_accepted_fraction),
        s.fallback_tried,
        s.fallback_used,
        s.boiling_dropped
    ));
    if s.mutations_per_pixel > 0.0 {
        ui.label(format!(
            "MCMC mutations: {:.2} per pixel, {} accepted",
            s.mutations_per_pixel,
            percent(s.mutation_acceptance)
        ))
        .on_hover_text("Steps tried per surface pixel and frame and the share accepted (docs/src/mcmc-mutation.md): a step that is nearly always accepted barely moves the sample.");
    }
    let rays: Vec<String> = s
        .shadow_rays_per_pixel
        .iter()
        .map(|(pass, n)| format!("{pass} {n:.2}"))
        .collect();
    ui.label(format!(
        "Shadow rays per pixel: {:.2} ({})",
        s.shadow_rays_per_pixel_total,
        rays.join(" · ")
    ))
    .on_hover_text("Per surface pixel and frame, by pass. With MIS visibility (pairwise) reuse traces two per neighbour and per temporal merge, and shading none.");
    ui.label("Rejections (per surface pixel; spatial counts every neighbour)")
        .on_hover_text("Under pairwise MIS the sample reasons (reservoir null, target zero, target ratio, light gone) are counted, not rejected: the candidate stays in the MIS as a domain of zero contribution");
    egui::Grid::new("rejections")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.strong("reason");
            ui.strong("temporal");
            ui.strong("spatial");
            ui.end_row();
            // In bit order, the order of the rejection view's legend.
            for name in REJECT_REASON_NAMES {
                let count =
                    |map: &BTreeMap<String, u64>| map.get(name).copied().unwrap_or(0) as f64;
                ui.label(name);
                ui.label(percent(count(&s.temporal_rejections) / pixels));
                ui.label(percent(count(&s.spatial_rejections) / pixels));
                ui.end_row();
            }
        });
}

/// The guard's counters (docs/src/ris.md, "Conventions": nothing poisoned spreads): NaN/Inf values
/// each pass produced or read and replaced. Any count is a bug to chase, so non-zero ones stand
/// out; the "since load" column keeps a single bad frame visible after it leaves the summary
/// window.
fn non_finite(ui: &mut Ui, window: &StatsSummary, since_load: &FrameCounters) {
    ui.label("Non-finite values replaced, per pass");
    let alarm = ui.visuals().error_fg_color;
    let count = |n: u64| {
        let text = RichText::new(n.to_string());
        if n > 0 {
            text.color(alarm).strong()
        } else {
            text.weak()
        }
    };
    egui::Grid::new("non-finite")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.strong("pass");
            ui.strong(format!("last {} frames", window.frames));
            ui.strong("since load");
            ui.end_row();
            for (i, name) in GUARDED_PASS_NAMES.iter().enumerate() {
                let recent = window.non_finite_by_pass.get(*name).copied().unwrap_or(0);
                let total = since_load.get(STAT_NONFINITE + i as u32);
                let label = RichText::new(*name);
                ui.label(if total > 0 { label.color(alarm) } else { label });
                ui.label(count(recent));
                ui.label(count(total));
                ui.end_row();
            }
        });
}
