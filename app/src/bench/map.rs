//! `bench-map DIR`: the crossover map (docs/bench.md, "The crossover map at 384×256")
//! from the bench runs under DIR, one folder per (scene, size, camera), each a `--knob` run
//! whose first configuration is the baseline (denoised RIS). For each cell and configuration: the
//! milliseconds it needs to reach the baseline's best error and its middle error, as a
//! ratio to the baseline's own, read off its curve (equal_error.rs); the same in shadow
//! rays; its squared bias and variance at the top knob value. Each curve's milliseconds
//! are first smoothed by a straight-line fit over the knob: lavapipe's per-point medians
//! scatter when other work shares the cores, and a curve read in the order of noisy times
//! zig-zags. Where the cells kept each seed's timings, the ratio at the best error is also
//! read seed by seed (the error curves stay the seeds' mean, so only the load moves it),
//! and stated with its 95 % interval over the seeds: a verdict near a threshold such as
//! 0.8× holds only where the whole interval lies on one side. Writes `map.md` and
//! `map.csv` into DIR.

use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::Args;

use restir_render::metrics::seeds::Interval;

use super::csv::Table;
use super::equal_error::{CostPoint, Reach, cost_at, split_knob};

#[derive(Args, Debug)]
pub struct MapArgs {
    /// The folder holding one bench output folder per cell (docs/bench/crossover/map).
    pub dir: PathBuf,
    /// The knob the cells swept (`--knob NAME=...`).
    #[arg(long, default_value = "light_candidates")]
    pub knob: String,
}

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

pub fn run(args: MapArgs) -> anyhow::Result<()> {
    let cells = read_cells(&args.dir, &args.knob)?;
    anyhow::ensure!(
        !cells.is_empty(),
        "{}: no cell (a folder with cost_curves.csv and figures.json)",
        args.dir.display()
    );
    std::fs::write(args.dir.join("map.md"), markdown(&cells))
        .with_context(|| format!("{}: cannot write map.md", args.dir.display()))?;
    csv_table(&cells).write(&args.dir.join("map.csv"))?;
    print!("{}", markdown(&cells));
    Ok(())
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
pub fn read_curves(path: &Path) -> anyhow::Result<Vec<(String, Vec<CostPoint>)>> {
    let text = std::fs::read_to_string(path)?;
    let mut curves: Vec<(String, Vec<CostPoint>)> = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').collect();
        anyhow::ensure!(f.len() >= 7, "a row with {} fields: {line}", f.len());
        let num = |i: usize| f[i].trim().parse::<f64>().unwrap_or(f64::NAN);
        // The eighth column, each seed's median frame time, came later.
        let seed_ms = f
            .get(7)
            .map(|cell| {
                cell.split(';')
                    .filter(|x| !x.trim().is_empty())
                    .map(|x| x.trim().parse::<f64>().unwrap_or(f64::NAN))
                    .collect()
            })
            .unwrap_or_default();
        let point = CostPoint {
            knob: f[1].to_string(),
            ms: num(2),
            seed_ms,
            rays_per_pixel: num(3),
            candidates_per_pixel: num(4),
            rmse: num(5),
            rmse_ci95: num(6),
        };
        match curves.iter_mut().find(|(c, _)| c == f[0]) {
            Some((_, points)) => points.push(point),
            None => curves.push((f[0].to_string(), vec![point])),
        }
    }
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

/// "0.78×", "≤ 0.78×" (already below the target at its cheapest point), "> 1.9×" (never
/// reaches it within the sweep).
fn ratio_text(r: Option<(f64, Reach)>) -> String {
    match r {
        None => "—".into(),
        Some((x, Reach::At(_))) => format!("{x:.2}×"),
        Some((x, Reach::AtMost(_))) => format!("≤ {x:.2}×"),
        Some((x, Reach::Beyond(_))) => format!("> {x:.2}×"),
    }
}

/// " [0.71–0.83]": the 95 % interval of the ratio read seed by seed (nothing for the
/// baseline against itself, or without per-seed timings).
fn seeds_text(i: Option<Interval>) -> String {
    match i {
        Some(i) if i.half_width.is_finite() && i.half_width > 0.0 => {
            format!(" [{:.2}–{:.2}]", i.low(), i.high())
        }
        _ => String::new(),
    }
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

/// A configuration's name without its settings: `ris+denoise[denoise_iterations=2]` →
/// `ris+denoise`.
fn bare(config: &str) -> &str {
    config.split('[').next().unwrap_or(config)
}

/// A cell's settings where the map's cells ran the same configurations with other
/// settings (each scene at its own depth, say): `denoise_iterations=1`, or each
/// configuration's where they differ within the cell.
fn settings_text(cell: &Cell) -> String {
    let inner = |c: &str| {
        c.find('[').map_or(String::new(), |i| {
            c[i + 1..].trim_end_matches(']').to_string()
        })
    };
    let mut all: Vec<String> = cell.readings.iter().map(|r| inner(&r.config)).collect();
    all.dedup();
    match all.as_slice() {
        [one] if one.is_empty() => "—".into(),
        [one] => format!("`{one}`"),
        _ => cell
            .readings
            .iter()
            .map(|r| format!("`{}`", r.config))
            .collect::<Vec<_>>()
            .join(", "),
    }
}

pub fn markdown(cells: &[Cell]) -> String {
    let mut out = String::new();
    let mut by_size: BTreeMap<&str, Vec<&Cell>> = BTreeMap::new();
    for c in cells {
        by_size.entry(&c.size).or_default().push(c);
    }
    for (size, cells) in by_size {
        let _ = writeln!(out, "### {size}\n");
        let _ = writeln!(
            out,
            "Each configuration's milliseconds to reach the baseline's best error, ÷ the \
             baseline's (≤: already there at its cheapest point; >: not within the sweep); \
             in square brackets, where each seed's timings were kept, the 95 % interval of \
             that ratio read seed by seed; in round brackets the lowest error it reaches ÷ \
             the baseline's lowest.\n"
        );
        let names =
            |c: &Cell| -> Vec<String> { c.readings.iter().map(|r| r.config.clone()).collect() };
        // Cells that ran the same configurations with other settings share columns by
        // their bare names, and a column says what each cell ran.
        let by_settings = cells.iter().any(|c| names(c) != names(cells[0]));
        let configs: Vec<String> = names(cells[0])
            .iter()
            .map(|n| {
                if by_settings {
                    bare(n).to_string()
                } else {
                    n.clone()
                }
            })
            .collect();
        let settings_column = if by_settings { " settings |" } else { "" };
        let _ = writeln!(
            out,
            "| scene | camera |{settings_column} {} | cheapest |",
            configs.join(" | ")
        );
        let columns = configs.len() + 3 + usize::from(by_settings);
        let _ = writeln!(out, "|{}", " --- |".repeat(columns));
        for c in &cells {
            let ratios: Vec<String> = configs
                .iter()
                .map(|name| {
                    let found = c.readings.iter().find(|r| {
                        if by_settings {
                            bare(&r.config) == name
                        } else {
                            r.config == *name
                        }
                    });
                    match found {
                        Some(r) => format!(
                            "{}{} ({:.2})",
                            ratio_text(r.ms_at_best),
                            seeds_text(r.ms_at_best_over_seeds),
                            r.floor_ratio
                        ),
                        None => "—".to_string(),
                    }
                })
                .collect();
            let win = winner(c).map_or("—".to_string(), |(w, x)| format!("`{w}` {x:.2}×"));
            let settings = if by_settings {
                format!(" {} |", settings_text(c))
            } else {
                String::new()
            };
            let _ = writeln!(
                out,
                "| `{}` | {} |{settings} {} | {win} |",
                c.scene,
                c.camera,
                ratios.join(" | ")
            );
        }
        out.push('\n');
    }
    out
}

fn csv_table(cells: &[Cell]) -> Table {
    let mut t = Table::new(&[
        "folder",
        "scene",
        "size",
        "camera",
        "config",
        "baseline_best_rmse",
        "ms_vs_baseline_at_best",
        "ms_vs_baseline_at_best_seed_mean",
        "ms_vs_baseline_at_best_seed_ci95",
        "reach_at_best",
        "ms_vs_baseline_at_middle",
        "rays_per_pixel_at_best",
        "lowest_rmse_vs_baseline",
        "squared_bias",
        "squared_bias_ci95",
        "variance",
        "variance_ci95",
    ]);
    let code = |r: &Reach| match r {
        Reach::At(_) => "interpolated",
        Reach::AtMost(_) => "at_most",
        Reach::Beyond(_) => "beyond",
    };
    let num = |x: Option<f64>| x.map_or(String::new(), |x| x.to_string());
    for c in cells {
        for r in &c.readings {
            t.row(vec![
                c.folder.clone(),
                c.scene.clone(),
                c.size.clone(),
                c.camera.clone(),
                r.config.clone(),
                c.best_rmse.to_string(),
                num(r.ms_at_best.map(|x| x.0)),
                num(r.ms_at_best_over_seeds.map(|i| i.mean)),
                num(r
                    .ms_at_best_over_seeds
                    .map(|i| i.half_width)
                    .filter(|h| h.is_finite())),
                r.ms_at_best
                    .map_or(String::new(), |x| code(&x.1).to_string()),
                num(r.ms_at_middle.map(|x| x.0)),
                num(r.rays_at_best),
                r.floor_ratio.to_string(),
                num(r.squared_bias.map(|x| x.0)),
                num(r.squared_bias.map(|x| x.1)),
                num(r.variance.map(|x| x.0)),
                num(r.variance.map(|x| x.1)),
            ]);
        }
    }
    t
}

#[cfg(test)]
#[path = "map_tests.rs"]
mod tests;
