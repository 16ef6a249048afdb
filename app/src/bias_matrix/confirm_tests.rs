//! The confirmation stage on cells written by hand: a cell that read biased is listed for a
//! confirmation run, and the table states the confirmation's verdict, whichever it is.

use std::path::{Path, PathBuf};

use clap::Parser;
use restir_render::metrics::seeds::{Interval, Verdict};

use super::cells::{Cell, cells};
use super::{BiasMatrixArgs, Stage, to_confirm};
use crate::bench::score::seed_figures::SeedFigures;
use crate::bench::write::figures_json::{FIGURES_FILE, FigureRow, write_rows};

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    args: BiasMatrixArgs,
}

fn args(out: &Path) -> BiasMatrixArgs {
    Cli::parse_from(["bias-matrix", "--out", out.to_str().unwrap()]).args
}

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("restir-confirm-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A cell's figures whose four seeds read `ratios` over `frames` frames.
fn row(cell: &Cell, frames: usize, ratios: &[f64]) -> FigureRow {
    let luma_ratio = Interval::of(ratios);
    let signed_bias = luma_ratio.shifted(1.0);
    FigureRow {
        scene: cell.scene.clone(),
        size: (48, 32),
        camera: "static".into(),
        config: cell.estimator.clone(),
        description: String::new(),
        first_seed: 0,
        reference_spp: 4096,
        figures: SeedFigures {
            seeds: ratios.len(),
            frames,
            frame_luma_rmse: Interval::of(&[0.1, 0.1]),
            frame_luma_rmse_by_seed: vec![0.1, 0.1],
            low_frequency_rmse: Interval::of(&[0.01, 0.01]),
            accumulated_rgb_rmse: None,
            luma_ratio,
            signed_bias,
            black_pixel_fraction: Interval::of(&[0.0, 0.0]),
            spread: None,
            bias_view_flagged: None,
            frames_to_half_percent: None,
            verdict: Verdict::of(&signed_bias),
            non_finite_pixels: 0,
            reference_mean_luma: 1.0,
            disoccluded_luma_rmse: None,
            near_moving_luma_rmse: None,
            detail_kept: None,
            detail_flip: None,
        },
    }
}

fn write(args: &BiasMatrixArgs, cell: &Cell, stage: Stage, ratios: &[f64]) {
    let dir = stage.dir(args, cell);
    std::fs::create_dir_all(&dir).unwrap();
    let frames = stage.frames(args) as usize;
    write_rows(&dir.join(FIGURES_FILE), &[row(cell, frames, ratios)]).unwrap();
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn a_biased_cell_is_confirmed_at_more_frames_and_the_table_states_the_longer_run() {
    let out = out_dir("table");
    let args = args(&out);
    let scenes = ["builtin:cornell".to_string()];
    let estimators = ["ris", "restir", "nee", "restir-pairwise"].map(String::from);
    let all = cells(&scenes, &estimators);
    let (ris, restir, nee, flip) = (&all[0], &all[1], &all[2], &all[3]);
    // ris unbiased; restir (1/M) 2 % dark and still so at 4× the frames; nee 20 % dark at
    // first (its rare huge samples not drawn yet) and undecided at 4× the frames.
    write(&args, ris, Stage::First, &[1.001, 0.999, 1.0, 1.0005]);
    write(&args, restir, Stage::First, &[0.98, 0.981, 0.979, 0.98]);
    write(&args, nee, Stage::First, &[0.79, 0.80, 0.78, 0.79]);
    // Biased both times, but bright at first and dark at more frames: the intervals were
    // not honest, and the table concludes nothing.
    write(&args, flip, Stage::First, &[1.02, 1.021, 1.019, 1.02]);
    let listed: Vec<String> = to_confirm(&args, &all)
        .unwrap()
        .iter()
        .map(|c| c.estimator.clone())
        .collect();
    assert_eq!(
        listed,
        ["restir", "nee", "restir-pairwise"],
        "only the biased cells are confirmed"
    );

    // Before the confirmations ran the merge names them as missing.
    let err = super::table::merge(&out, &all, &args)
        .unwrap_err()
        .to_string();
    assert!(err.contains("builtin_cornell/restir/confirm"), "{err}");

    write(&args, restir, Stage::Confirm, &[0.98, 0.9805, 0.9795, 0.98]);
    write(&args, nee, Stage::Confirm, &[0.79, 1.61, 0.85, 0.80]);
    write(&args, flip, Stage::Confirm, &[0.98, 0.981, 0.979, 0.98]);
    super::table::merge(&out, &all, &args).unwrap();
    let csv = read(&out.join("bias-matrix.csv"));
    let verdicts: Vec<(&str, &str)> = csv
        .lines()
        .skip(1)
        .map(|l| {
            let cols: Vec<&str> = l.split(',').collect();
            (cols[10], cols[cols.len() - 1])
        })
        .collect();
    assert_eq!(
        verdicts,
        [
            ("consistent with 0", "consistent with 0"),
            ("biased", "biased"),
            ("biased", "undecided"),
            ("biased", "undecided (the runs disagree)"),
        ]
    );
    let md = read(&out.join("bias-matrix.md"));
    assert!(md.contains("✗ -2.0±0.1ᶜ"), "{md}");
    assert!(md.contains("## Biased cells (1)"), "{md}");
    assert!(
        md.contains("## Biased at first, not at more frames"),
        "{md}"
    );
    assert!(
        md.contains("or runs that disagree in sign) (2)"),
        "nee and the disagreeing cell are listed: {md}"
    );
    assert!(
        md.contains("`nee`: at 64 frames -21.00 %") && md.contains("at 256 frames"),
        "{md}"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn without_confirmation_a_biased_cell_says_it_was_not_confirmed() {
    let out = out_dir("off");
    let mut args = args(&out);
    args.confirm = 1;
    let all = cells(&["builtin:cornell".into()], &["restir".into()]);
    write(&args, &all[0], Stage::First, &[0.98, 0.981, 0.979, 0.98]);
    assert!(to_confirm(&args, &all).unwrap().is_empty());
    super::table::merge(&out, &all, &args).unwrap();
    let csv = read(&out.join("bias-matrix.csv"));
    assert!(csv.contains("biased (unconfirmed)"), "{csv}");
    let _ = std::fs::remove_dir_all(&out);
}
