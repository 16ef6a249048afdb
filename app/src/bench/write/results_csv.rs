//! `results.csv` (one row per configuration, or per configuration and event on a dynamic
//! scene with events) and `frames.csv` (one row per measured frame). Times carry a `timing`
//! column that says whether they are GPU timestamps or CPU wall-clock (lavapipe: ratios
//! only).

use std::path::Path;

use super::events_csv::{LAG_COLUMNS, lag_rows};
use super::figure_columns::{GAIN_COLUMNS, SEED_COLUMNS, gain_cells, seed_cells};
use super::info::BenchInfo;
use super::passes::{pass_cells, pass_columns, pass_names};
use super::table::{Table, num};
use crate::bench::score::equal_time_gain::{SeedCosts, gains_vs_first};
use crate::bench::score::frame_figures::ScoreSummary;
use crate::bench::score::result::ConfigResult;

/// √(RMSE² − noise²): the error against the true image, when the reference's own noise
/// (independent of the frames) is known; E[RMSE²] = MSE + Var_ref.
pub fn without_noise(rmse: Option<f64>, noise: Option<f64>) -> Option<f64> {
    Some((rmse?.powi(2) - noise?.powi(2)).max(0.0).sqrt())
}

/// One row per configuration (per event where there are events): what it is and its
/// times, its scores, what its run counted, the bench's conditions, its figures over the
/// seeds, its equal-time gain and its lag.
pub fn write_results(
    path: &Path,
    info: &BenchInfo,
    results: &[ConfigResult],
) -> anyhow::Result<()> {
    let passes = pass_names(results);
    let pass_headers = pass_columns(&passes);
    let mut header: Vec<&str> = vec![
        "config",
        "mode",
        "description",
        "frames",
        "median_frame_ms",
        "time_vs_nee",
    ];
    header.extend(pass_headers.iter().map(String::as_str));
    header.extend(SCORE_COLUMNS);
    header.extend(RUN_COLUMNS);
    header.extend(BENCH_COLUMNS);
    header.extend(SEED_COLUMNS);
    header.extend(GAIN_COLUMNS);
    header.extend(LAG_COLUMNS);
    let mut table = Table::new(&header);
    let gains = gains_vs_first(results);
    for (r, gain) in results.iter().zip(gains) {
        let s = r.scores.clone().unwrap_or_default();
        let mut cells = vec![
            r.config.name.clone(),
            r.config.mode.name().to_string(),
            r.config.description.clone(),
            r.frames.len().to_string(),
            num(r.median_frame_ms()),
            num(r.time_vs_nee),
        ];
        cells.extend(pass_cells(&passes, r));
        cells.extend(score_cells(r, &s, info));
        cells.extend(run_cells(r, &s));
        cells.extend(bench_cells(info));
        cells.extend(seed_cells(r.over_seeds.as_ref()));
        cells.extend(gain_cells(gain, SeedCosts::of(r)));
        for lag in lag_rows(info.event_source, &r.lag) {
            let mut row = cells.clone();
            row.extend(lag);
            table.row(row);
        }
    }
    table.write(path)
}

/// A run's scores (docs/src/measured/how-the-bench-measures.md, "How it measures"), empty
/// where it was not scored.
const SCORE_COLUMNS: [&str; 22] = [
    "mean_luma_rmse",
    "mean_luma_rmse_antialiased",
    "mean_stability_rmse",
    "mean_low_frequency_rmse",
    "error_correlation",
    "temporal_flicker",
    "accumulated_rgb_rmse",
    "accumulated_rgb_rmse_minus_reference_noise",
    "accumulated_rel_mse",
    "luma_ratio",
    "mean_signed_bias",
    "black_pixel_fraction",
    "disoccluded_share",
    "disoccluded_luma_rmse",
    "disoccluded_signed_bias",
    "near_moving_share",
    "near_moving_luma_rmse",
    "near_moving_signed_bias",
    "detail_share",
    "detail_luma_rmse",
    "detail_kept",
    "detail_flip",
];

fn score_cells(r: &ConfigResult, s: &ScoreSummary, info: &BenchInfo) -> Vec<String> {
    let scored = r.scores.is_some();
    vec![
        num(scored.then_some(s.mean_luma_rmse)),
        num(s.antialiased_luma_rmse),
        num(scored.then_some(s.mean_stability)),
        num(scored.then_some(s.mean_low_frequency_rmse)),
        num(scored.then_some(s.error_correlation())),
        num(r.flicker),
        num(s.accumulated_rgb_rmse),
        num(without_noise(
            s.accumulated_rgb_rmse,
            info.reference_noise_rgb,
        )),
        num(s.accumulated_rel_mse),
        num(scored.then_some(s.luma_ratio)),
        num(scored.then_some(s.signed_bias)),
        num(scored.then_some(s.black_pixel_fraction)),
        num(s.disoccluded.map(|m| m.share)),
        num(s.disoccluded.and_then(|m| m.luma_rmse)),
        num(s.disoccluded.and_then(|m| m.signed_bias)),
        num(s.near_moving.map(|m| m.share)),
        num(s.near_moving.and_then(|m| m.luma_rmse)),
        num(s.near_moving.and_then(|m| m.signed_bias)),
        num(s.detail.map(|d| d.share)),
        num(s.detail.map(|d| d.luma_rmse)),
        num(s.detail.map(|d| d.kept)),
        num(s.detail.map(|d| d.flip)),
    ]
}

/// What the run counted: rays, the tracing backend, the denoiser's depth, the ratio to
/// `nee`, the equal-time budget and non-finite pixels.
const RUN_COLUMNS: [&str; 10] = [
    "shadow_rays_per_pixel",
    "useful_candidate_share",
    "ray_backend",
    "denoise_auto_depth",
    "frame_mse_vs_nee",
    "budget_ms",
    "budget_used_ms",
    "budget_capped",
    "budget_mse_vs_nee",
    "non_finite_pixels",
];

fn run_cells(r: &ConfigResult, s: &ScoreSummary) -> Vec<String> {
    vec![
        num(Some(r.times.shadow_rays_per_pixel_total)),
        num(Some(r.times.useful_candidate_share)),
        r.ray_backend.map_or("", |b| b.name()).to_string(),
        r.denoise_auto_depth
            .map(|d| d.to_string())
            .unwrap_or_default(),
        num(r.frame_mse_vs_nee),
        num(r.budget.map(|b| b.budget.ms)),
        num(r.budget.map(|b| b.used_ms)),
        r.budget.map(|b| b.capped().to_string()).unwrap_or_default(),
        num(r.budget_mse_vs_nee),
        s.non_finite_pixels.to_string(),
    ]
}

/// The bench's conditions, the same on every row.
const BENCH_COLUMNS: [&str; 10] = [
    "scene",
    "size",
    "camera",
    "seed",
    "reference_spp",
    "reference_noise_luma_rmse",
    "reference_noise_rgb_rmse",
    "frame_reference_noise_luma_rmse",
    "device",
    "timing",
];

fn bench_cells(info: &BenchInfo) -> Vec<String> {
    vec![
        info.scene.clone(),
        format!("{}x{}", info.size.0, info.size.1),
        info.camera.label(),
        info.seed.to_string(),
        info.reference_spp.to_string(),
        num(info.reference_noise_luma),
        num(info.reference_noise_rgb),
        num(info.frame_reference_noise_luma),
        info.device.clone(),
        info.timing_note().to_string(),
    ]
}

pub fn write_frames(path: &Path, results: &[ConfigResult]) -> anyhow::Result<()> {
    let mut table = Table::new(&[
        "config",
        "frame",
        "frame_ms",
        "cumulative_ms",
        "luma_rmse",
        "stability_rmse",
        "accumulated_rgb_rmse",
    ]);
    for r in results {
        for f in &r.frames {
            table.row([
                r.config.name.clone(),
                f.index.to_string(),
                f.ms.to_string(),
                f.cumulative_ms.to_string(),
                num(f.scores.luma_rmse),
                num(f.scores.stability),
                num(f.scores.accumulated_rgb_rmse),
            ]);
        }
    }
    table.write(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_noise_comes_out_in_quadrature_and_never_below_zero() {
        assert_eq!(without_noise(Some(0.5), Some(0.3)), Some(0.4));
        assert_eq!(without_noise(Some(0.1), Some(0.3)), Some(0.0));
        assert_eq!(without_noise(Some(0.1), None), None);
    }
}
