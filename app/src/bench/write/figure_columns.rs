//! The columns `results.csv` gives the figures scoring adds over the seeds: each image
//! figure's mean and 95 % half-width (score/seed_figures.rs) and the equal-time gain over the
//! first configuration with its interval (score/equal_time_gain.rs).

use restir_render::metrics::seeds::Interval;

use crate::bench::score::equal_time_gain::{Gain, SeedCosts};
use crate::bench::score::seed_figures::SeedFigures;

/// The `results.csv` columns of the figures over seeds (the `_ci95` columns are the 95 %
/// interval's half-width; empty with one seed).
pub const SEED_COLUMNS: [&str; 25] = [
    "image_seeds",
    "frame_luma_rmse_mean",
    "frame_luma_rmse_ci95",
    "accumulated_rgb_rmse_mean",
    "accumulated_rgb_rmse_ci95",
    "luma_ratio_mean",
    "luma_ratio_ci95",
    "signed_bias_mean",
    "signed_bias_ci95",
    "bias_verdict",
    "squared_bias",
    "squared_bias_ci95",
    "variance",
    "variance_ci95",
    "effective_frames",
    "frames_to_half_percent",
    "bias_view_flagged_share",
    "disoccluded_luma_rmse_mean",
    "disoccluded_luma_rmse_ci95",
    "near_moving_luma_rmse_mean",
    "near_moving_luma_rmse_ci95",
    "detail_kept_mean",
    "detail_kept_ci95",
    "detail_flip_mean",
    "detail_flip_ci95",
];

/// The `SEED_COLUMNS` cells of one configuration (all empty when it was not scored).
pub fn seed_cells(f: Option<&SeedFigures>) -> Vec<String> {
    let Some(f) = f else {
        return vec![String::new(); SEED_COLUMNS.len()];
    };
    let num = |x: Option<f64>| {
        x.filter(|v| v.is_finite())
            .map(|v| format!("{v}"))
            .unwrap_or_default()
    };
    let pair = |i: Option<&Interval>| [num(i.map(|i| i.mean)), num(i.map(|i| i.half_width))];
    let spread = f.spread.as_ref();
    let mut cells = vec![f.seeds.to_string()];
    cells.extend(pair(Some(&f.frame_luma_rmse)));
    cells.extend(pair(f.accumulated_rgb_rmse.as_ref()));
    cells.extend(pair(Some(&f.luma_ratio)));
    cells.extend(pair(Some(&f.signed_bias)));
    cells.push(f.verdict.label().to_string());
    cells.extend([
        num(spread.map(|s| s.squared_bias.value)),
        num(spread.and_then(|s| s.squared_bias.half_width)),
        num(spread.map(|s| s.variance.value)),
        num(spread.and_then(|s| s.variance.half_width)),
        num(spread.and_then(|s| s.effective_frames)),
        num(f.frames_to_half_percent),
        num(f.bias_view_flagged.map(|i| i.mean)),
    ]);
    cells.extend(pair(f.disoccluded_luma_rmse.as_ref()));
    cells.extend(pair(f.near_moving_luma_rmse.as_ref()));
    cells.extend(pair(f.detail_kept.as_ref()));
    cells.extend(pair(f.detail_flip.as_ref()));
    cells
}

/// The equal-time gain's columns, and the two means over seeds it is made of (per-frame
/// MSE less the reference noise², ms/frame of the seeds' medians) with their 95 % half-widths:
/// results.md's "Equal time over K seeds" table, as data.
pub const GAIN_COLUMNS: [&str; 7] = [
    "equal_time_gain_vs_first",
    "equal_time_gain_low",
    "equal_time_gain_high",
    "seeds_frame_mse_mean",
    "seeds_frame_mse_ci95",
    "seeds_frame_ms_mean",
    "seeds_frame_ms_ci95",
];

pub fn gain_cells(gain: Option<Gain>, costs: Option<SeedCosts>) -> Vec<String> {
    let mut cells = match gain {
        Some(g) => [g.value, g.low, g.high].map(|x| x.to_string()).to_vec(),
        None => vec![String::new(); 3],
    };
    for i in costs.iter().flat_map(|c| [c.mse(), c.ms()]) {
        cells.extend([i.mean, i.half_width].map(|x| {
            if i.samples >= 2 {
                x.to_string()
            } else {
                String::new()
            }
        }));
    }
    cells.resize(GAIN_COLUMNS.len(), String::new());
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The means the gain is made of come out as data beside it, the reference noise taken
    /// out of the MSE; one seed has no interval to state, so its cells stay empty.
    #[test]
    fn the_gain_columns_hold_the_means_it_is_made_of() {
        let costs = |rmse, ms| SeedCosts {
            frame_luma_rmse: rmse,
            frame_ms: ms,
            reference_noise: 0.03,
        };
        let cells = gain_cells(None, Some(costs(&[0.05, 0.05], &[10.0, 12.0])));
        let n = |i: usize| cells[i].parse::<f64>().unwrap();
        assert!((n(3) - (0.0025 - 0.0009)).abs() < 1e-12 && n(4).abs() < 1e-12);
        assert_eq!((n(5), cells.len()), (11.0, GAIN_COLUMNS.len()));
        let one = gain_cells(None, Some(costs(&[0.05], &[10.0])));
        assert!(one.iter().all(String::is_empty), "{one:?}");
        assert!(gain_cells(None, None).iter().all(String::is_empty));
    }
}
