//! `results.md`: the tables people paste (into README, an issue, the book's chapters), with the
//! device and the conditions named, and the timing caveat next to every time.

use std::fmt::Write;

use super::info::BenchInfo;
use super::lag_table::lag_table;
use super::markdown::{ms, on_off, pass_table, ratio, sig, table, time_footnote};
use super::seed_tables::seeds_table;
use crate::bench::plan::camera_path::CameraPath;
use crate::bench::score::result::ConfigResult;

/// The whole page: the conditions, one row per configuration, the figures over the seeds,
/// the lag around events, the equal-time budget and the pass times.
pub fn results(info: &BenchInfo, results: &[ConfigResult]) -> String {
    let mut md = String::new();
    conditions(&mut md, info);
    main_table(&mut md, info, results);
    seeds_table(&mut md, info, results);
    lag_table(&mut md, info, results);
    if let Some(t) = info.budget_ms {
        budget_table(&mut md, t, results);
    }
    pass_times(&mut md, info, results);
    md
}

/// The title and what every number below depends on: the device, the reference, jitter,
/// the spatial radius, the seeds and the warm-up.
fn conditions(md: &mut String, info: &BenchInfo) {
    let what = match (info.frames, info.budget_ms) {
        (_, Some(t)) => format!("equal time, {t} ms[^t] per configuration"),
        (Some(n), None) => format!("{n} frames per configuration"),
        (None, None) => String::new(),
    };
    let _ = writeln!(
        md,
        "# Bench: {}, {}×{}, {} camera, {what}\n",
        info.scene,
        info.size.0,
        info.size.1,
        info.camera.label()
    );
    let _ = writeln!(
        md,
        "- Device: **{}** — {}.",
        info.device,
        info.timing_note()
    );
    reference_line(md, info);
    jitter_line(md, info);
    let (set, used) = info.radius;
    let _ = writeln!(
        md,
        "- Spatial radius: {used} px ({set} px at 1080p, scaled to the image height)."
    );
    seeds_line(md, info);
}

/// With jitter on, what the per-frame errors are measured against.
fn jitter_line(md: &mut String, info: &BenchInfo) {
    if info.jitter && info.camera == CameraPath::Static {
        let _ = writeln!(
            md,
            "- Jitter on: every per-frame error is measured against the reference of the \
             frame's own sub-pixel offset (docs/src/viewer.md, \"Accuracy with jitter on\"); \
             against the antialiased reference, which the running average is scored against, \
             it would measure the pixel footprint (`mean_luma_rmse_antialiased` in results.csv)."
        );
    } else if info.jitter {
        let _ = writeln!(
            md,
            "- **Jitter on with a moving camera**: each frame is scored against its camera's \
             antialiased reference, so the per-frame errors include the pixel footprint, the \
             same for every configuration (docs/src/viewer.md, \"Accuracy with jitter on\"); \
             compare configurations with the bench's default, jitter off."
        );
    }
}

/// The seeds every figure rests on, the clean history and the warm-up, what a time is.
fn seeds_line(md: &mut String, info: &BenchInfo) {
    let seeds = if info.seeds > 1 {
        format!(
            "Seeds {}..{} ({}); the table below is seed {} alone, the next one states every \
             image figure over the seeds",
            info.seed,
            info.seed.wrapping_add(info.seeds - 1),
            info.seeds,
            info.seed
        )
    } else {
        format!(
            "Seed {} (one seed: every figure below is a single run's, without an interval; \
             `--seeds K` gives intervals)",
            info.seed
        )
    };
    let _ = writeln!(
        md,
        "- {}; every configuration starts from a clean history{}. Time per frame = sum of its pass times, median over frames.\n",
        seeds,
        if info.warmup > 0 {
            format!(" and renders {} unmeasured warm-up frames", info.warmup)
        } else {
            String::new()
        }
    );
}

/// The reference: its samples, how many, its bounces, jitter, and its own noise.
fn reference_line(md: &mut String, info: &BenchInfo) {
    let noise = match (info.reference_noise_luma, info.reference_noise_rgb) {
        // Jitter on: the per-frame errors are against the phases' references, whose noise
        // is the pixel centre's lighting alone; the antialiased one's adds the footprint.
        (Some(l), Some(r)) if info.frame_reference_noise_luma != Some(l) => format!(
            "its own RMSE ≈ {} luma / {} RGB (antialiased: in the accumulated image's error); \
             the jitter phases' references', which every per-frame error is measured \
             against, ≈ {} luma (every per-frame RMSE² includes this²)",
            sig(Some(l)),
            sig(Some(r)),
            sig(info.frame_reference_noise_luma)
        ),
        (Some(l), Some(r)) => format!(
            "its own RMSE ≈ {} luma / {} RGB (every per-frame RMSE² includes this²)",
            sig(Some(l)),
            sig(Some(r))
        ),
        _ => "its own noise not estimated".into(),
    };
    let per = if info.reference_count > 1 {
        format!(" ({} references, one per frame)", info.reference_count)
    } else {
        String::new()
    };
    let bounces = match info.reference_bounces.as_slice() {
        [] | [1] => String::new(),
        list => format!(
            ", max_bounces {} (each configuration against the reference of its own max_bounces)",
            list.iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(" and ")
        ),
    };
    let _ = writeln!(
        md,
        "- Reference: {} spp{per}{bounces}, jitter {}, {noise}.",
        info.reference_spp,
        on_off(info.jitter)
    );
}

/// One row per configuration: its time and, scored against the reference, its errors.
fn main_table(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
    let accumulated = if info.camera == CameraPath::Static {
        "accumulated RGB RMSE"
    } else {
        "accumulated RGB RMSE (n/a: moving camera)"
    };
    let header: Vec<String> = [
        "configuration",
        "ms/frame[^t]",
        "time × nee[^t]",
        "per-frame luma RMSE",
        "stability (luma RMSE)",
        "8×8 error (low-freq. RMSE)",
        "error correlation[^c]",
        "flicker (\\|Δ luma\\| / reference)",
        accumulated,
        "luma ratio",
        "signed bias",
        "black pixels",
        "shadow rays / pixel",
        "useful candidates",
        "rays traced by",
        "per-frame MSE × nee",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            let s = r.scores.as_ref();
            vec![
                format!("`{}`", r.config.name),
                ms(r.median_frame_ms()),
                ratio(r.time_vs_nee),
                sig(s.map(|s| s.mean_luma_rmse)),
                sig(s.map(|s| s.mean_stability)),
                sig(s.map(|s| s.mean_low_frequency_rmse)),
                s.map(|s| format!("{:.2}", s.error_correlation()))
                    .unwrap_or_else(|| "n/a".into()),
                sig(r.flicker),
                sig(s.and_then(|s| s.accumulated_rgb_rmse)),
                s.map(|s| format!("{:.4}", s.luma_ratio))
                    .unwrap_or_else(|| "n/a".into()),
                s.map(|s| format!("{:+.4}", s.signed_bias))
                    .unwrap_or_else(|| "n/a".into()),
                s.map(|s| format!("{:.2} %", 100.0 * s.black_pixel_fraction))
                    .unwrap_or_else(|| "n/a".into()),
                format!("{:.2}", r.times.shadow_rays_per_pixel_total),
                format!("{:.1} %", 100.0 * r.times.useful_candidate_share),
                r.ray_backend.map_or("n/a", |b| b.name()).to_string(),
                ratio(r.frame_mse_vs_nee),
            ]
        })
        .collect();
    table(md, &header, &rows);
}

/// Equal-time mode: each configuration's frames within the budget and its running
/// average's error there.
fn budget_table(md: &mut String, t: f64, results: &[ConfigResult]) {
    let _ = writeln!(md, "\n## Equal time: {t} ms[^t] each\n");
    let header: Vec<String> = [
        "configuration",
        "frames",
        "time used (ms)[^t]",
        "accumulated RGB RMSE",
        "MSE × nee (lower is better)",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            let capped = if r.budget.is_some_and(|b| b.capped()) {
                " (frame cap)"
            } else {
                ""
            };
            vec![
                format!("`{}`", r.config.name),
                format!("{}{capped}", r.frames.len()),
                ms(r.budget.map(|b| b.used_ms)),
                sig(r.final_accumulated_rmse()),
                ratio(r.budget_mse_vs_nee),
            ]
        })
        .collect();
    table(md, &header, &rows);
}

/// The median time of each pass, and the footnotes.
fn pass_times(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
    let _ = writeln!(md, "\n## Median time per pass (ms)[^t]\n");
    let labelled: Vec<(String, &ConfigResult)> = results
        .iter()
        .map(|r| (format!("`{}`", r.config.name), r))
        .collect();
    pass_table(md, "configuration", &labelled);
    let _ = writeln!(md, "\n{}", time_footnote(info.timing_note()));
    let _ = writeln!(
        md,
        "[^c]: 8 × the 8×8-tile error's RMSE / the per-pixel RMSE: 1 for grain, 8 for blotches \
         a tile wide (docs/src/measured/how-the-bench-measures.md, \"How it measures\")."
    );
}
