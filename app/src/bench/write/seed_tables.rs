//! results.md's tables over the seeds: every image figure with its 95 % interval
//! (docs/src/results.md, "Error bars"), also what a merge of jobs prints, and each
//! configuration's equal-time gain over the first (score/equal_time_gain.rs).

use std::fmt::Write;

use super::info::BenchInfo;
use super::markdown::table;
use crate::bench::score::equal_time_gain::{self, SeedCosts};
use crate::bench::score::result::ConfigResult;
use crate::bench::score::seed_figures::SeedFigures;

/// The image figures over the seeds (seed_figures.rs; docs/src/results.md, "Error bars"),
/// when there are two or more.
pub fn seeds_table(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
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
