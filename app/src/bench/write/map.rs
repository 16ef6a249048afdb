//! The crossover map's files (score/map.rs reads the cells): `map.md`, one table per image
//! size with each configuration's cost ratio to reach the baseline's best error and the
//! cheapest, `map.csv`, every reading, and `map.png`, drawn from map.csv (map_png.rs).

use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::Path;

use anyhow::Context;
use restir_render::metrics::seeds::Interval;

use super::table::Table;
use crate::bench::score::equal_error::Reach;
use crate::bench::score::map::{Cell, winner};

/// Writes `map.md`, `map.csv` and `map.png` into `dir` and prints the markdown.
pub fn write(dir: &Path, cells: &[Cell]) -> anyhow::Result<()> {
    std::fs::write(dir.join("map.md"), markdown(cells))
        .with_context(|| format!("{}: cannot write map.md", dir.display()))?;
    csv_table(cells).write(&dir.join("map.csv"))?;
    super::map_png::write(dir)?;
    print!("{}", markdown(cells));
    Ok(())
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

/// `map.md`: a table per image size.
pub fn markdown(cells: &[Cell]) -> String {
    let mut out = String::new();
    let mut by_size: BTreeMap<&str, Vec<&Cell>> = BTreeMap::new();
    for c in cells {
        by_size.entry(&c.size).or_default().push(c);
    }
    for (size, cells) in by_size {
        size_table(&mut out, size, &cells);
        out.push('\n');
    }
    out
}

/// One size's heading, what its cells say, and a row per cell: each configuration's
/// ratio at the baseline's best error and the cheapest.
fn size_table(out: &mut String, size: &str, cells: &[&Cell]) {
    let _ = writeln!(out, "### {size}\n");
    let _ = writeln!(
        out,
        "Each configuration's milliseconds to reach the baseline's best error, ÷ the \
         baseline's (≤: already there at its cheapest point; >: not within the sweep); \
         in square brackets, where each seed's timings were kept, the 95 % interval of \
         that ratio read seed by seed; in round brackets the lowest error it reaches ÷ \
         the baseline's lowest.\n"
    );
    let names = |c: &Cell| -> Vec<String> { c.readings.iter().map(|r| r.config.clone()).collect() };
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
    for c in cells {
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
                    .map_or(String::new(), |x| x.1.code().to_string()),
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
