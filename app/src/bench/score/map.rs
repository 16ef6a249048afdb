//! `bench-map DIR`: the crossover map (docs/src/measured/denoiser.md, "The crossover map at
//! 384×256") from the bench runs under DIR, one folder per (scene, size, camera), each a
//! `--knob` run whose first configuration is the baseline (denoised RIS). For each cell and
//! configuration: the milliseconds it needs to reach the baseline's best error and its middle
//! error, as a ratio to the baseline's own, read off its curve (equal_error.rs); the same in
//! shadow rays; its squared bias and variance at the top knob value. Each curve's milliseconds
//! are first smoothed by a straight-line fit over the knob: lavapipe's per-point medians
//! scatter when other work shares the cores, and a curve read in the order of noisy times
//! zig-zags. Where the cells kept each seed's timings, the ratio at the best error is also read
//! seed by seed (the error curves stay the seeds' mean, so only the load moves it), and stated
//! with its 95 % interval over the seeds: a verdict near a threshold such as 0.8× holds only
//! where the whole interval lies on one side. write/map.rs writes `map.md` and `map.csv` into
//! DIR.

use std::path::{Path, PathBuf};

use anyhow::Context;
use restir_render::metrics::seeds::Interval;

use super::cost_curves_file::{self, NamedCurve};
use super::equal_error::{CostPoint, Reach, cost_at, split_knob};

/// A cell's reading of one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Reading {
    pub config: String,
    /// Cost to reach the baseline's best (lowest) error and its middle-knob error, each
    /// ÷ the baseline's cost there (ms, then shadow rays); `None`: no usable point.
    pub ms_at_best: Option<(f64, Reach)>,
    /// `ms_at_best` read with each seed's own timings, over the seeds (none where the cell
    /// kept no per-seed timings).
    pub ms_at_best_over_seeds: Option<Interval>,
    pub ms_at_middle: Option<(f64, Reach)>,
    pub rays_at_best: Option<f64>,
    /// The lowest error the curve reaches ÷ the baseline's lowest: where errors stop falling
    /// with the knob (a blur floor), the cost to reach the baseline says little and this
    /// says which floor is lower.
    pub floor_ratio: f64,
    /// At the top knob value: squared bias and variance (over seeds), with half-widths.
    pub squared_bias: Option<(f64, f64)>,
    pub variance: Option<(f64, f64)>,
}

/// One (scene, size, camera) of the map.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    pub folder: String,
    pub scene: String,
    pub size: String,
    pub camera: String,
    pub baseline: String,
    pub best_rmse: f64,
    pub readings: Vec<Reading>,
}

/// Every cell under `dir`, in folder order.
pub fn read_cells(dir: &Path, knob: &str) -> anyhow::Result<Vec<Cell>> {
    let mut folders: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("{}: cannot read", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("cost_curves.csv").is_file() && p.join("figures.json").is_file())
        .collect();
    folders.sort();
    folders.iter().map(|f| read_cell(f, knob)).collect()
}

fn read_cell(folder: &Path, knob: &str) -> anyhow::Result<Cell> {
    let name = folder.display().to_string();
    let curves = read_curves(&folder.join("cost_curves.csv"))
        .with_context(|| format!("{name}/cost_curves.csv"))?;
    let text = std::fs::read_to_string(folder.join("figures.json"))?;
    let figures: serde_json::Value =
        serde_json::from_str(&text).with_context(|| format!("{name}/figures.json"))?;
    let entries = figures.as_array().context("figures.json: not a list")?;
    let first = entries.first().context("figures.json: empty")?;
    let (baseline, base_points) = curves.first().context("no curve")?.clone();
    let best_rmse = base_points
        .iter()
        .map(|p| p.rmse)
        .filter(|r| r.is_finite())
        .fold(f64::INFINITY, f64::min);
    let middle_rmse = base_points[base_points.len() / 2].rmse;
    let base_best = cost_at(&base_points, best_rmse);
    let base_middle = cost_at(&base_points, middle_rmse);
    let ratio = |reach: Option<Reach>, base: Option<Reach>| -> Option<(f64, Reach)> {
        let (r, b) = (reach?, base?);
        Some((r.cost().ms / b.cost().ms, r))
    };
    let top_value = |config: &str| {
        curves
            .iter()
            .find(|(c, _)| c == config)
            .and_then(|(_, p)| p.last())
            .map(|p| p.knob.clone())
    };
    let lowest = |points: &[CostPoint]| {
        points
            .iter()
            .map(|p| p.rmse)
            .filter(|r| r.is_finite())
            .fold(f64::INFINITY, f64::min)
    };
    let mut readings = Vec::new();
    for (config, points) in &curves {
        let at_best = cost_at(points, best_rmse);
        let spread = top_value(config).and_then(|v| spread_of(entries, knob, config, &v));
        readings.push(Reading {
            config: config.clone(),
            ms_at_best: ratio(at_best, base_best),
            ms_at_best_over_seeds: ratio_over_seeds(points, &base_points, best_rmse),
            ms_at_middle: ratio(cost_at(points, middle_rmse), base_middle),
            rays_at_best: at_best.map(|r| r.cost().rays_per_pixel),
            floor_ratio: lowest(points) / best_rmse,
            squared_bias: spread.map(|s| s.0),
            variance: spread.map(|s| s.1),
        });
    }
    let size = first["size"]
        .as_array()
        .map(|s| format!("{}×{}", s[0], s[1]))
        .unwrap_or_default();
    Ok(Cell {
        folder: folder
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default(),
        scene: first["scene"].as_str().unwrap_or("?").to_string(),
        size,
        camera: first["camera"].as_str().unwrap_or("?").to_string(),
        baseline,
        best_rmse,
        readings,
    })
}

/// The curves of a `cost_curves.csv`, in file order, each point's milliseconds replaced by
/// the least-squares line through the curve's (knob, ms) pairs (kept as measured where the
/// knob is not a number or the line is not positive).
pub fn read_curves(path: &Path) -> anyhow::Result<Vec<NamedCurve>> {
    let (_, mut curves) = cost_curves_file::read(path)?;
    for (_, points) in &mut curves {
        smooth_ms(points);
    }
    Ok(curves)
}

/// The cost ratio at `target` read once per seed: every point's milliseconds replaced by
/// that seed's (then smoothed as the mean's are), on both curves. None unless every point
/// of both curves holds the same number of seeds, at least two.
fn ratio_over_seeds(points: &[CostPoint], base: &[CostPoint], target: f64) -> Option<Interval> {
    let seeds = points.first()?.seed_ms.len();
    let all = points.iter().chain(base);
    if seeds < 2 || all.clone().any(|p| p.seed_ms.len() != seeds) {
        return None;
    }
    let of_seed = |curve: &[CostPoint], k: usize| -> Vec<CostPoint> {
        let mut points: Vec<CostPoint> = curve
            .iter()
            .map(|p| CostPoint {
                ms: p.seed_ms[k],
                ..p.clone()
            })
            .collect();
        smooth_ms(&mut points);
        points
    };
    let ratios: Vec<f64> = (0..seeds)
        .filter_map(|k| {
            let own = cost_at(&of_seed(points, k), target)?;
            let base = cost_at(&of_seed(base, k), target)?;
            Some(own.cost().ms / base.cost().ms)
        })
        .collect();
    (ratios.len() == seeds).then(|| Interval::of(&ratios))
}

fn smooth_ms(points: &mut [CostPoint]) {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| Some((p.knob.parse::<f64>().ok()?, p.ms)))
        .filter(|(_, y)| y.is_finite())
        .collect();
    if xy.len() < 2 || xy.len() != points.len() {
        return;
    }
    let n = xy.len() as f64;
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / n,
        xy.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return;
    }
    let slope = sxy / sxx;
    let fitted: Vec<f64> = xy.iter().map(|p| my + slope * (p.0 - mx)).collect();
    if fitted.iter().all(|&y| y > 0.0) {
        for (p, y) in points.iter_mut().zip(fitted) {
            p.ms = y;
        }
    }
}

/// Squared bias and variance of `config` at knob value `value` (from figures.json).
fn spread_of(
    entries: &[serde_json::Value],
    knob: &str,
    config: &str,
    value: &str,
) -> Option<((f64, f64), (f64, f64))> {
    let entry = entries.iter().find(|e| {
        e["config"]
            .as_str()
            .and_then(|c| split_knob(c, knob))
            .is_some_and(|(c, v)| c == config && v == value)
    })?;
    let spread = &entry["figures"]["spread"];
    let pair = |key: &str| {
        Some((
            spread[key]["value"].as_f64()?,
            spread[key]["half_width"].as_f64()?,
        ))
    };
    Some((pair("squared_bias")?, pair("variance")?))
}

/// The configuration that reaches the baseline's best error at the least cost (a bound
/// counts at its value), and that cost ÷ the baseline's.
pub fn winner(cell: &Cell) -> Option<(&str, f64)> {
    cell.readings
        .iter()
        .filter_map(|r| match r.ms_at_best {
            Some((x, Reach::At(_) | Reach::AtMost(_))) => Some((r.config.as_str(), x)),
            _ => None,
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scattered_timings_are_read_along_their_fitted_line() {
        // Timings out of order (a busy machine): the fit restores the trend, so the curve is
        // read from cheap to dear in knob order.
        let mut points: Vec<CostPoint> = [(8, 120.0), (16, 100.0), (32, 140.0)]
            .iter()
            .map(|&(k, ms)| CostPoint {
                knob: k.to_string(),
                ms,
                seed_ms: Vec::new(),
                rays_per_pixel: 1.0,
                candidates_per_pixel: k as f64,
                rmse: 0.01,
                rmse_ci95: 0.0,
            })
            .collect();
        smooth_ms(&mut points);
        assert!(points[0].ms < points[1].ms && points[1].ms < points[2].ms);
        let mean: f64 = points.iter().map(|p| p.ms).sum::<f64>() / 3.0;
        assert!((mean - 120.0).abs() < 1e-9, "the fit keeps the mean");
    }
}
