//! The bias matrix's table from its cells' outputs: `bias-matrix.csv` (one row per cell)
//! and `bias-matrix.md` (scenes × estimators, then the biased and undecided cells listed).
//! Only what the seeds rendered goes in, never a time or a path, so the table of a sweep
//! run as independent jobs equals the one run in a single process.

use std::fmt::Write;
use std::path::Path;

use anyhow::{Context, bail};
use restir_render::metrics::seeds::{BIAS_TOLERANCE, Verdict};

use super::BiasMatrixArgs;
use super::cells::{Cell, scene_label};
use crate::bench::csv::Table;
use crate::bench::seed_figures::{FIGURES_FILE, FigureRow, read_rows};

/// What a cell that failed leaves in its folder.
pub const ERROR_FILE: &str = "error.txt";

enum Outcome {
    Done(Box<FigureRow>),
    Failed(String),
    Missing,
}

fn outcome(out: &Path, cell: &Cell) -> anyhow::Result<Outcome> {
    let dir = super::cell_dir(out, cell);
    let figures = dir.join(FIGURES_FILE);
    if figures.is_file() {
        let rows = read_rows(&figures)?;
        let row = rows
            .into_iter()
            .find(|r| r.config == cell.estimator)
            .with_context(|| format!("{}: no row for {}", figures.display(), cell.estimator))?;
        return Ok(Outcome::Done(Box::new(row)));
    }
    if let Ok(text) = std::fs::read_to_string(dir.join(ERROR_FILE)) {
        return Ok(Outcome::Failed(
            text.lines().next().unwrap_or("").to_string(),
        ));
    }
    Ok(Outcome::Missing)
}

/// Writes `bias-matrix.csv` and `bias-matrix.md` under `out` from every cell's output;
/// fails naming the cells that never ran (the table is still written, marking them).
pub fn merge(out: &Path, cells: &[Cell], args: &BiasMatrixArgs) -> anyhow::Result<()> {
    let outcomes: Vec<Outcome> = cells
        .iter()
        .map(|c| outcome(out, c))
        .collect::<anyhow::Result<_>>()?;
    write_csv(&out.join("bias-matrix.csv"), cells, &outcomes)?;
    let md = markdown(cells, &outcomes, args);
    let md_path = out.join("bias-matrix.md");
    std::fs::write(&md_path, &md)
        .with_context(|| format!("{}: cannot write", md_path.display()))?;
    println!("{md}");
    let missing: Vec<String> = cells
        .iter()
        .zip(&outcomes)
        .filter(|(_, o)| matches!(o, Outcome::Missing))
        .map(|(c, _)| c.folder())
        .collect();
    if !missing.is_empty() {
        bail!(
            "{} of {} cells have no output yet under {}: {}",
            missing.len(),
            cells.len(),
            out.join("cells").display(),
            missing.join(", ")
        );
    }
    Ok(())
}

fn write_csv(path: &Path, cells: &[Cell], outcomes: &[Outcome]) -> anyhow::Result<()> {
    let mut table = Table::new(&[
        "scene",
        "estimator",
        "status",
        "seeds",
        "frames",
        "size",
        "reference_spp",
        "luma_ratio_mean",
        "signed_bias_mean",
        "signed_bias_ci95",
        "verdict",
        "bias_view_flagged_share",
        "effective_frames",
        "frames_to_half_percent",
        "squared_bias",
        "variance",
        "frame_luma_rmse_mean",
        "non_finite_pixels",
    ]);
    let num = |x: Option<f64>| {
        x.filter(|v| v.is_finite())
            .map(|v| format!("{v}"))
            .unwrap_or_default()
    };
    for (cell, o) in cells.iter().zip(outcomes) {
        let mut row = vec![scene_label(&cell.scene), cell.estimator.clone()];
        match o {
            Outcome::Done(r) => {
                let f = &r.figures;
                let spread = f.spread.as_ref();
                row.extend([
                    "ok".to_string(),
                    f.seeds.to_string(),
                    f.frames.to_string(),
                    format!("{}x{}", r.size.0, r.size.1),
                    r.reference_spp.to_string(),
                    num(Some(f.luma_ratio.mean)),
                    num(Some(f.signed_bias.mean)),
                    num(Some(f.signed_bias.half_width)),
                    f.verdict.label().to_string(),
                    num(f.bias_view_flagged.map(|i| i.mean)),
                    num(spread.and_then(|s| s.effective_frames)),
                    num(f.frames_to_half_percent),
                    num(spread.map(|s| s.squared_bias.value)),
                    num(spread.map(|s| s.variance.value)),
                    num(Some(f.frame_luma_rmse.mean)),
                    f.non_finite_pixels.to_string(),
                ]);
            }
            Outcome::Failed(e) => {
                row.push(format!("error: {e}"));
                row.extend(std::iter::repeat_n(String::new(), 15));
            }
            Outcome::Missing => {
                row.push("missing".into());
                row.extend(std::iter::repeat_n(String::new(), 15));
            }
        }
        table.row(row);
    }
    table.write(path)
}

/// The mark of a verdict in the matrix.
fn mark(v: Verdict) -> &'static str {
    match v {
        Verdict::Unbiased => "✓",
        Verdict::Biased => "✗",
        Verdict::Undecided => "?",
        Verdict::OneSeed => "1",
        Verdict::NoLight => "·",
    }
}

fn cell_text(o: &Outcome) -> String {
    match o {
        Outcome::Done(r) => {
            let f = &r.figures;
            if f.verdict == Verdict::NoLight {
                return format!("{} black", mark(f.verdict));
            }
            format!(
                "{} {:+.1}±{:.1}",
                mark(f.verdict),
                100.0 * f.signed_bias.mean,
                100.0 * f.signed_bias.half_width
            )
        }
        Outcome::Failed(_) => "error".into(),
        Outcome::Missing => "—".into(),
    }
}

fn markdown(cells: &[Cell], outcomes: &[Outcome], args: &BiasMatrixArgs) -> String {
    let mut md = String::new();
    let mut scenes: Vec<&str> = Vec::new();
    let mut estimators: Vec<&str> = Vec::new();
    for c in cells {
        if !scenes.contains(&c.scene.as_str()) {
            scenes.push(&c.scene);
        }
        if !estimators.contains(&c.estimator.as_str()) {
            estimators.push(&c.estimator);
        }
    }
    let _ = writeln!(
        md,
        "# Bias matrix: {} scenes × {} estimators, {} seeds × {} frames at {}, {}-spp references\n",
        scenes.len(),
        estimators.len(),
        args.seeds,
        args.frames,
        args.size,
        args.reference_spp
    );
    let count = |v: Verdict| {
        outcomes
            .iter()
            .filter(|o| matches!(o, Outcome::Done(r) if r.figures.verdict == v))
            .count()
    };
    let failed = outcomes
        .iter()
        .filter(|o| matches!(o, Outcome::Failed(_)))
        .count();
    let missing = outcomes
        .iter()
        .filter(|o| matches!(o, Outcome::Missing))
        .count();
    let _ = writeln!(
        md,
        "Each cell: signed bias of the accumulated image's mean luminance against the reference, \
         in %, mean ± 95 % interval over the seeds (the reference's own uncertainty included). \
         ✓ consistent with 0 (the interval lies within ±{tol} %), ✗ biased (it lies beyond \
         ±{tol} %), ? undecided (more seeds or frames needed), · black (no light reaches the \
         camera). Animated scenes are measured at time 0.\n",
        tol = 100.0 * BIAS_TOLERANCE
    );
    let _ = writeln!(
        md,
        "**{} consistent with 0, {} biased, {} undecided, {} black, {} failed, {} missing** of {} cells.\n",
        count(Verdict::Unbiased),
        count(Verdict::Biased),
        count(Verdict::Undecided),
        count(Verdict::NoLight),
        failed,
        missing,
        cells.len()
    );
    let mut header = vec!["scene".to_string()];
    header.extend(estimators.iter().map(|e| format!("`{e}`")));
    let rows: Vec<Vec<String>> = scenes
        .iter()
        .map(|s| {
            let mut row = vec![format!("`{}`", scene_label(s))];
            row.extend(estimators.iter().map(|e| {
                cells
                    .iter()
                    .zip(outcomes)
                    .find(|(c, _)| c.scene == *s && c.estimator == *e)
                    .map_or("—".into(), |(_, o)| cell_text(o))
            }));
            row
        })
        .collect();
    crate::bench::markdown::table(&mut md, &header, &rows);
    list_cells(&mut md, "Biased cells", cells, outcomes, Verdict::Biased);
    list_cells(
        &mut md,
        "Undecided cells",
        cells,
        outcomes,
        Verdict::Undecided,
    );
    let errors: Vec<String> = cells
        .iter()
        .zip(outcomes)
        .filter_map(|(c, o)| match o {
            Outcome::Failed(e) => Some(format!(
                "- `{}` · `{}`: {e}",
                scene_label(&c.scene),
                c.estimator
            )),
            _ => None,
        })
        .collect();
    if !errors.is_empty() {
        let _ = writeln!(md, "\n## Cells that failed\n\n{}", errors.join("\n"));
    }
    md
}

/// The cells with verdict `v`, each with its size, the share of pixels the `bias` view
/// flags and how many frames one seed needs to resolve ±0.5 %.
fn list_cells(md: &mut String, title: &str, cells: &[Cell], outcomes: &[Outcome], v: Verdict) {
    let lines: Vec<String> = cells
        .iter()
        .zip(outcomes)
        .filter_map(|(c, o)| match o {
            Outcome::Done(r) if r.figures.verdict == v => {
                let f = &r.figures;
                Some(format!(
                    "- `{}` · `{}`: {:+.2} % ± {:.2} %, `bias` view flags {}, effective frames {}, \
                     frames to ±0.5 % {}",
                    scene_label(&c.scene),
                    c.estimator,
                    100.0 * f.signed_bias.mean,
                    100.0 * f.signed_bias.half_width,
                    f.bias_view_flagged
                        .map_or("n/a".into(), |i| format!("{:.1} %", 100.0 * i.mean)),
                    f.spread
                        .and_then(|s| s.effective_frames)
                        .map_or("n/a".into(), |e| format!("{e:.0} of {}", f.frames)),
                    f.frames_to_half_percent
                        .map_or("n/a".into(), |n| format!("{n:.0}")),
                ))
            }
            _ => None,
        })
        .collect();
    if !lines.is_empty() {
        let _ = writeln!(md, "\n## {title} ({})\n\n{}", lines.len(), lines.join("\n"));
    }
}
