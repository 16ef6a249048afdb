//! `results.md`: the tables people paste (into README, an issue, docs/bench.md), with the
//! device and the conditions named, and the timing caveat next to every time.

use std::fmt::Write;

use super::BenchInfo;
use super::csv::pass_names;
use super::equal_time_gain::{self, SeedCosts};
use super::references::CameraPath;
use super::run_loop::ConfigResult;
use super::seed_figures::SeedFigures;

/// A number with 4 significant digits (errors), or "n/a".
pub fn sig(x: Option<f64>) -> String {
    match x {
        Some(0.0) => "0".into(),
        Some(v) if v.is_finite() => {
            let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 8) as usize;
            format!("{v:.digits$}")
        }
        Some(v) => format!("{v}"),
        None => "n/a".into(),
    }
}

/// Milliseconds with two decimals (or "n/a").
pub fn ms(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.2}")).unwrap_or_else(|| "n/a".into())
}

/// A ratio like `1.23×`.
pub fn ratio(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.2}×"))
        .unwrap_or_else(|| "n/a".into())
}

/// One Markdown table.
pub fn table(out: &mut String, header: &[String], rows: &[Vec<String>]) {
    let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
    out.push_str(&line(header));
    out.push_str(&line(&vec!["---".to_string(); header.len()]));
    for r in rows {
        out.push_str(&line(r));
    }
}

/// The `[^t]` footnote on every time: what kind of time it is.
pub fn time_footnote(note: &str) -> String {
    format!("[^t]: {note}.\n")
}

pub fn results(info: &BenchInfo, results: &[ConfigResult]) -> String {
    let mut md = String::new();
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
    let noise = match (info.reference_noise_luma, info.reference_noise_rgb) {
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
    let (set, used) = info.radius;
    let _ = writeln!(
        md,
        "- Spatial radius: {used} px ({set} px at 1080p, scaled to the image height)."
    );
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
    table(&mut md, &header, &rows);
    seeds_table(&mut md, info, results);
    lag_table(&mut md, info, results);
    if let Some(t) = info.budget_ms {
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
        table(&mut md, &header, &rows);
    }
    let _ = writeln!(md, "\n## Median time per pass (ms)[^t]\n");
    let labelled: Vec<(String, &ConfigResult)> = results
        .iter()
        .map(|r| (format!("`{}`", r.config.name), r))
        .collect();
    pass_table(&mut md, "configuration", &labelled);
    let _ = writeln!(md, "\n{}", time_footnote(info.timing_note()));
    let _ = writeln!(
        md,
        "[^c]: 8 × the 8×8-tile error's RMSE / the per-pixel RMSE: 1 for grain, 8 for blotches \
         a tile wide (docs/bench.md, \"How it measures\")."
    );
    md
}

/// The image figures over the seeds (seed_figures.rs; docs/src/results.md, "Error bars"),
/// when there are two or more.
fn seeds_table(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
    if info.seeds < 2 {
        return;
    }
    let _ = writeln!(md, "\n## Over {} seeds: mean ± 95 % interval\n", info.seeds);
    let rows: Vec<(&str, &SeedFigures)> = results
        .iter()
        .filter_map(|r| Some((r.config.name.as_str(), r.over_seeds.as_ref()?)))
        .collect();
    seed_figures_table(md, &rows);
    equal_time_table(md, info, results);
}

/// Each configuration's equal-time gain over the first one, with its interval over the
/// seeds (`equal_time_gain.rs`).
fn equal_time_table(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
    let gains = equal_time_gain::gains_vs_first(results);
    let Some(first) = results
        .first()
        .filter(|_| gains.iter().any(Option::is_some))
    else {
        return;
    };
    let _ = writeln!(
        md,
        "\n## Equal time over {} seeds: against `{}`\n",
        info.seeds, first.config.name
    );
    let header: Vec<String> = [
        "configuration",
        "per-frame MSE",
        "ms/frame (seeds' medians)",
        "equal-time gain[^g]",
        "verdict",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = results
        .iter()
        .zip(&gains)
        .enumerate()
        .map(|(i, (r, gain))| {
            let costs = SeedCosts::of(r);
            vec![
                format!("`{}`", r.config.name),
                match costs.as_ref().map(SeedCosts::mse) {
                    Some(mse) if mse.samples >= 2 => {
                        format!("{:.3e} ± {:.1e}", mse.mean, mse.half_width)
                    }
                    _ => "n/a".to_string(),
                },
                costs.map_or("n/a".into(), |c| c.ms().display(1)),
                match gain {
                    _ if i == 0 => "1 (the baseline)".to_string(),
                    Some(g) => format!("{:.2} [{:.2}–{:.2}]", g.value, g.low, g.high),
                    None => "n/a".to_string(),
                },
                match gain {
                    _ if i == 0 => "–",
                    Some(g) => g.verdict(),
                    None => "n/a",
                }
                .to_string(),
            ]
        })
        .collect();
    table(md, &header, &rows);
    let _ = writeln!(
        md,
        "\n[^g]: (per-frame MSE × ms/frame of `{}`) ÷ the row's, each the mean over the \
         seeds (a seed's MSE: its mean per-frame luma RMSE squared; its ms: its median frame \
         time). In brackets the 95 % interval: each mean's t-interval, relative, added in \
         quadrature on the log scale. \"better\" where the interval lies above 1, \"worse\" \
         below. Like every time here, a ratio within this run only.",
        first.config.name
    );
}

/// One row of figures over seeds per named configuration, with the footnotes that define
/// them (a bench's `results.md` and the merge of its jobs).
pub fn seed_figures_table(md: &mut String, rows: &[(&str, &SeedFigures)]) {
    let header: Vec<String> = [
        "configuration",
        "per-frame luma RMSE",
        "accumulated RGB RMSE",
        "luma ratio",
        "signed bias",
        "verdict (±0.5 %)",
        "squared bias[^b]",
        "variance[^b]",
        "effective frames[^e]",
        "frames to ±0.5 %[^e]",
        "`bias` view flags",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = rows
        .iter()
        .map(|(name, f)| {
            let spread = f.spread.as_ref();
            vec![
                format!("`{name}`"),
                f.frame_luma_rmse.display(4),
                f.accumulated_rgb_rmse
                    .map_or("n/a".into(), |i| i.display(4)),
                f.luma_ratio.display(4),
                format!(
                    "{:+.2} % ± {:.2} %",
                    100.0 * f.signed_bias.mean,
                    100.0 * f.signed_bias.half_width
                ),
                f.verdict.label().to_string(),
                spread.map_or("n/a".into(), |s| s.squared_bias.display(2)),
                spread.map_or("n/a".into(), |s| s.variance.display(2)),
                spread
                    .and_then(|s| s.effective_frames)
                    .map_or("n/a".into(), |e| format!("{e:.0} of {}", f.frames)),
                f.frames_to_half_percent
                    .map_or("n/a".into(), |n| format!("{n:.0}")),
                f.bias_view_flagged
                    .map_or("n/a".into(), |i| format!("{:.2} %", 100.0 * i.mean)),
            ]
        })
        .collect();
    table(md, &header, &rows);
    let _ = writeln!(
        md,
        "\n[^b]: Of the accumulated image's luminance, per pixel, over the seeds: squared bias = \
         (mean over seeds − reference)² less the noise of that mean and of the reference; \
         variance = the spread of one seed's accumulated image. Intervals by jackknife over \
         seeds.\n\n[^e]: Effective frames = one frame's variance / the accumulated image's: \
         how many independent frames the accumulated image is worth. Frames to ±0.5 % = how \
         many frames one seed needs for its mean luminance to lie within ±0.5 % at 95 %."
    );
}

/// Per configuration and event: the lag metrics (docs/bench.md, "Lag and ghosting").
fn lag_table(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
    if results.iter().all(|r| r.lag.is_empty()) {
        return;
    }
    let source = match info.event_source {
        Some("scene") => "the scene's own event list (STEP light keys)",
        _ => "detected where the references change",
    };
    let _ = writeln!(
        md,
        "\n## Lag around events ({} seed{}, events from {source})\n",
        info.seeds,
        if info.seeds == 1 { "" } else { "s, averaged" }
    );
    let _ = writeln!(
        md,
        "Steady = median error of the event's last 5 frames; recovery = frames until 5 in a row are ≤ 1.1 × steady; lag area = Σ max(error − steady, 0); signed bias = Σ(frame − reference) / Σ reference luminance where the reference changed > 10 %, first 5 frames (+ ghosting, − dark lag).\n"
    );
    let header: Vec<String> = [
        "configuration",
        "event (frame, time)",
        "peak error",
        "steady error",
        "peak / steady",
        "recovery frames",
        "lag area",
        "signed bias",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = results
        .iter()
        .flat_map(|r| {
            r.lag.iter().map(|e| {
                vec![
                    format!("`{}`", r.config.name),
                    format!("{}, {:.3} s", e.frame, e.time),
                    sig(e.peak_error),
                    sig(e.steady_error),
                    sig(e.peak_over_steady),
                    match e.recovery_frames {
                        Some(Some(v)) => format!("{v:.1}"),
                        Some(None) => "never".into(),
                        None => "n/a".into(),
                    },
                    sig(e.lag_area),
                    e.signed_bias
                        .map(|b| format!("{b:+.4}"))
                        .unwrap_or_else(|| "n/a".into()),
                ]
            })
        })
        .collect();
    table(md, &header, &rows);
}

/// Median time of each pass (columns) per labelled result (rows), and the frame's.
pub fn pass_table(md: &mut String, label: &str, labelled: &[(String, &ConfigResult)]) {
    let passes = pass_names(labelled.iter().map(|(_, r)| *r));
    let mut header = vec![label.to_string()];
    header.extend(passes.iter().cloned());
    header.push("frame".into());
    let rows: Vec<Vec<String>> = labelled
        .iter()
        .map(|(name, r)| {
            let mut row = vec![name.clone()];
            row.extend(passes.iter().map(|p| {
                r.times
                    .pass_ms_median
                    .get(p)
                    .map(|v| format!("{v:.2}"))
                    .unwrap_or_else(|| "–".into())
            }));
            row.push(ms(r.median_frame_ms()));
            row
        })
        .collect();
    table(md, &header, &rows);
}

fn on_off(b: bool) -> &'static str {
    if b { "on" } else { "off" }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_numbers_format_for_tables() {
        assert_eq!(sig(Some(0.145912)), "0.1459");
        assert_eq!(sig(Some(0.0041987)), "0.004199");
        assert_eq!(sig(Some(123.456)), "123.5");
        assert_eq!(sig(None), "n/a");
        assert_eq!(ms(Some(1.23456)), "1.23");
        assert_eq!(ratio(Some(0.5)), "0.50×");
        let mut out = String::new();
        table(
            &mut out,
            &["a".into(), "b".into()],
            &[vec!["1".into(), "2".into()]],
        );
        assert_eq!(out, "| a | b |\n| --- | --- |\n| 1 | 2 |\n");
    }
}
