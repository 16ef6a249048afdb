//! The bias matrix's table from its cells' outputs: `bias-matrix.csv` (one row per cell)
//! and `bias-matrix.md` (scenes × estimators, then the biased and undecided cells listed).
//! A cell's verdict is its confirmation run's where it has one (`mod.rs`, `Stage`).
//! Only what the seeds rendered goes in, never a time or a path, so the table of a sweep
//! run as independent jobs equals the one run in a single process.

use std::fmt::Write;
use std::path::Path;

use anyhow::{Context, bail};
use restir_render::metrics::seeds::{BIAS_TOLERANCE, Verdict};

use super::BiasMatrixArgs;
use super::cells::{Cell, scene_label};
use crate::bench::write::figures_json::{FIGURES_FILE, FigureRow, read_rows};
use crate::bench::write::table::Table;

/// What a cell that failed leaves in its folder.
pub const ERROR_FILE: &str = "error.txt";

enum Outcome {
    Done(Box<Runs>),
    Failed(String),
    Missing,
}

/// A cell's first run and, where it read biased, its confirmation's outcome.
struct Runs {
    first: FigureRow,
    confirm: Outcome,
}

impl Runs {
    /// The figures the table states: the confirmation's where it ran, else the first run's.
    fn last(&self) -> &FigureRow {
        match &self.confirm {
            Outcome::Done(c) => &c.first,
            _ => &self.first,
        }
    }

    fn confirmed(&self) -> Option<&FigureRow> {
        match &self.confirm {
            Outcome::Done(c) => Some(&c.first),
            _ => None,
        }
    }

    /// Whether a first run and its confirmation both read biased, but on opposite sides:
    /// then neither interval was honest (tails the seeds did not sample), and nothing is
    /// concluded.
    fn disagree(&self) -> bool {
        self.confirmed().is_some_and(|c| {
            let (a, b) = (&self.first.figures, &c.figures);
            a.verdict == Verdict::Biased
                && b.verdict == Verdict::Biased
                && a.signed_bias.mean.signum() != b.signed_bias.mean.signum()
        })
    }

    /// The verdict the table states: the confirmation's where it ran (undecided where the
    /// two runs disagree), else the first run's.
    fn verdict(&self) -> Verdict {
        if self.disagree() {
            Verdict::Undecided
        } else {
            self.last().figures.verdict
        }
    }
}

/// The first run's verdict of a cell that ran (None before it did or when it failed).
pub fn first_verdict(out: &Path, cell: &Cell) -> anyhow::Result<Option<Verdict>> {
    Ok(match outcome(&super::cell_dir(out, cell), cell)? {
        Outcome::Done(r) => Some(r.first.figures.verdict),
        _ => None,
    })
}

fn cell_outcome(out: &Path, cell: &Cell) -> anyhow::Result<Outcome> {
    let dir = super::cell_dir(out, cell);
    let mut o = outcome(&dir, cell)?;
    if let Outcome::Done(runs) = &mut o
        && runs.first.figures.verdict == Verdict::Biased
    {
        runs.confirm = outcome(&dir.join(super::CONFIRM_DIR), cell)?;
    }
    Ok(o)
}

/// One run's outcome from the folder it wrote (a confirmation not looked for yet: Missing).
fn outcome(dir: &Path, cell: &Cell) -> anyhow::Result<Outcome> {
    let figures = dir.join(FIGURES_FILE);
    if figures.is_file() {
        let rows = read_rows(&figures)?;
        let row = rows
            .into_iter()
            .find(|r| r.config == cell.estimator)
            .with_context(|| format!("{}: no row for {}", figures.display(), cell.estimator))?;
        return Ok(Outcome::Done(Box::new(Runs {
            first: row,
            confirm: Outcome::Missing,
        })));
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
        .map(|c| cell_outcome(out, c))
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
        .filter_map(|(c, o)| match o {
            Outcome::Missing => Some(c.folder()),
            Outcome::Done(r)
                if args.confirm > 1
                    && r.first.figures.verdict == Verdict::Biased
                    && matches!(r.confirm, Outcome::Missing) =>
            {
                Some(format!("{}/{}", c.folder(), super::CONFIRM_DIR))
            }
            _ => None,
        })
        .collect();
    if !missing.is_empty() {
        bail!(
            "{} of {} cells (or their confirmations) have no output yet under {}: {}",
            missing.len(),
            cells.len(),
            out.join("cells").display(),
            missing.join(", ")
        );
    }
    Ok(())
}

fn write_csv(path: &Path, cells: &[Cell], outcomes: &[Outcome]) -> anyhow::Result<()> {
    const COLUMNS: [&str; 23] = [
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
        "confirm_frames",
        "confirm_signed_bias_mean",
        "confirm_signed_bias_ci95",
        "confirm_verdict",
        "final_verdict",
    ];
    let mut table = Table::new(&COLUMNS);
    let num = |x: Option<f64>| {
        x.filter(|v| v.is_finite())
            .map(|v| format!("{v}"))
            .unwrap_or_default()
    };
    for (cell, o) in cells.iter().zip(outcomes) {
        let mut row = vec![scene_label(&cell.scene), cell.estimator.clone()];
        match o {
            Outcome::Done(runs) => {
                let r = &runs.first;
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
                match &runs.confirm {
                    Outcome::Done(c) => {
                        let c = &c.first.figures;
                        row.extend([
                            c.frames.to_string(),
                            num(Some(c.signed_bias.mean)),
                            num(Some(c.signed_bias.half_width)),
                            c.verdict.label().to_string(),
                        ]);
                    }
                    other => {
                        let status = match other {
                            Outcome::Failed(e) => format!("error: {e}"),
                            _ if f.verdict == Verdict::Biased => "missing".into(),
                            _ => String::new(),
                        };
                        row.extend([String::new(), String::new(), String::new(), status]);
                    }
                }
                row.push(final_verdict(runs).to_string());
            }
            Outcome::Failed(e) => {
                row.push(format!("error: {e}"));
                row.extend(std::iter::repeat_n(String::new(), COLUMNS.len() - 3));
            }
            Outcome::Missing => {
                row.push("missing".into());
                row.extend(std::iter::repeat_n(String::new(), COLUMNS.len() - 3));
            }
        }
        table.row(row);
    }
    table.write(path)
}

/// The verdict the table states: the confirmation's where it ran; a first run that read
/// biased and whose confirmation is missing or failed stays "biased (unconfirmed)".
fn final_verdict(runs: &Runs) -> &'static str {
    match (runs.first.figures.verdict, &runs.confirm) {
        _ if runs.disagree() => "undecided (the runs disagree)",
        (_, Outcome::Done(_)) => runs.verdict().label(),
        (Verdict::Biased, _) => "biased (unconfirmed)",
        (v, _) => v.label(),
    }
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

/// A cell of the matrix: the last run's verdict and signed bias, marked ᶜ where it is the
/// confirmation's.
fn cell_text(o: &Outcome) -> String {
    match o {
        Outcome::Done(runs) => {
            let f = &runs.last().figures;
            if f.verdict == Verdict::NoLight {
                return format!("{} black", mark(f.verdict));
            }
            format!(
                "{} {:+.1}±{:.1}{}",
                mark(runs.verdict()),
                100.0 * f.signed_bias.mean,
                100.0 * f.signed_bias.half_width,
                if runs.confirmed().is_some() {
                    "ᶜ"
                } else {
                    ""
                }
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
            .filter(|o| matches!(o, Outcome::Done(r) if r.verdict() == v))
            .count()
    };
    let confirmations = outcomes
        .iter()
        .filter(|o| matches!(o, Outcome::Done(r) if r.confirmed().is_some()))
        .count();
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
         camera). A cell that read biased ran again with {confirm}× the frames ({long} per \
         seed) and states that run's figures, marked ᶜ: a real bias keeps its size, the \
         shortfall of rare huge samples does not. Animated scenes are measured at time 0.\n",
        tol = 100.0 * BIAS_TOLERANCE,
        confirm = args.confirm.max(1),
        long = args.frames * args.confirm.max(1),
    );
    let _ = writeln!(
        md,
        "**{} consistent with 0, {} biased, {} undecided, {} black, {} failed, {} missing** of {} \
         cells ({} confirmed at {}× the frames).\n",
        count(Verdict::Unbiased),
        count(Verdict::Biased),
        count(Verdict::Undecided),
        count(Verdict::NoLight),
        failed,
        missing,
        cells.len(),
        confirmations,
        args.confirm.max(1)
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
    crate::bench::write::markdown::table(&mut md, &header, &rows);
    list_cells(&mut md, "Biased cells", cells, outcomes, |r| {
        r.verdict() == Verdict::Biased
    });
    list_cells(
        &mut md,
        "Biased at first, not at more frames (rare large samples, a bias below the tolerance, \
         or runs that disagree in sign)",
        cells,
        outcomes,
        |r| r.confirmed().is_some() && r.verdict() != Verdict::Biased,
    );
    list_cells(&mut md, "Undecided cells", cells, outcomes, |r| {
        r.confirmed().is_none() && r.first.figures.verdict == Verdict::Undecided
    });
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

/// The cells `pick` chooses, each with its signed bias (first run, then the confirmation's
/// where it ran), the share of pixels the `bias` view flags, its effective frames and how
/// many frames one seed needs to resolve ±0.5 %.
fn list_cells(
    md: &mut String,
    title: &str,
    cells: &[Cell],
    outcomes: &[Outcome],
    pick: impl Fn(&Runs) -> bool,
) {
    let bias = |f: &restir_render::metrics::seeds::Interval| {
        format!("{:+.2} % ± {:.2} %", 100.0 * f.mean, 100.0 * f.half_width)
    };
    let lines: Vec<String> = cells
        .iter()
        .zip(outcomes)
        .filter_map(|(c, o)| match o {
            Outcome::Done(runs) if pick(runs) => {
                let f = &runs.first.figures;
                let confirmed = runs.confirmed().map_or(String::new(), |c| {
                    let c = &c.figures;
                    format!(
                        "; at {} frames {} ({})",
                        c.frames,
                        bias(&c.signed_bias),
                        c.verdict.label()
                    )
                });
                let last = &runs.last().figures;
                Some(format!(
                    "- `{}` · `{}`: at {} frames {}{confirmed}; `bias` view flags {}, effective \
                     frames {}, frames to ±0.5 % {}",
                    scene_label(&c.scene),
                    c.estimator,
                    f.frames,
                    bias(&f.signed_bias),
                    last.bias_view_flagged
                        .map_or("n/a".into(), |i| format!("{:.1} %", 100.0 * i.mean)),
                    last.spread
                        .and_then(|s| s.effective_frames)
                        .map_or("n/a".into(), |e| format!("{e:.0} of {}", last.frames)),
                    last.frames_to_half_percent
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
