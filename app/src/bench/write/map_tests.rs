//! The map reads known curves back exactly and prints what it read: linear timings,
//! errors that meet the baseline's best at a measured point.

use std::path::{Path, PathBuf};

use super::*;
use crate::bench::score::map::{read_cells, winner};

fn write_cell(dir: &Path, name: &str, rows: &[(&str, u32, f64, f64)]) {
    write_cell_with_seeds(dir, name, rows, &[]);
}

/// `seed_scale[k]`: seed k's timings are the row's times that factor (none: the older
/// seven-column file).
fn write_cell_with_seeds(
    dir: &Path,
    name: &str,
    rows: &[(&str, u32, f64, f64)],
    seed_scale: &[(f64, f64)],
) {
    let cell = dir.join(name);
    std::fs::create_dir_all(&cell).unwrap();
    let mut csv = String::from(
        "config,light_candidates,median_frame_ms,shadow_rays_per_pixel,light_candidates_per_pixel,frame_luma_rmse_without_reference_noise,frame_luma_rmse_ci95\n",
    );
    let mut figures = Vec::new();
    for &(config, knob, ms, rmse) in rows {
        csv.push_str(&format!("{config},{knob},{ms},2.5,{knob},{rmse},0.0001"));
        if !seed_scale.is_empty() {
            // (baseline's factor, the others' factor) per seed.
            let seeds: Vec<String> = seed_scale
                .iter()
                .map(|&(base, other)| {
                    let f = if config.starts_with("ris+denoise") {
                        base
                    } else {
                        other
                    };
                    format!("{}", ms * f)
                })
                .collect();
            csv.push_str(&format!(",{}", seeds.join(";")));
        }
        csv.push('\n');
        figures.push(serde_json::json!({
            "scene": "builtin:concourse", "size": [384, 256], "camera": "static",
            "config": format!("{config}[light_candidates={knob}]"),
            "figures": {"spread": {
                "squared_bias": {"value": rmse * rmse * 0.8, "half_width": 1e-6},
                "variance": {"value": rmse * rmse * 0.2, "half_width": 1e-6}}}
        }));
    }
    std::fs::write(cell.join("cost_curves.csv"), csv).unwrap();
    std::fs::write(
        cell.join("figures.json"),
        serde_json::to_string(&figures).unwrap(),
    )
    .unwrap();
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("restir-map-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Both timings linear in the knob (1.25 ms per candidate); the preset reaches the
/// baseline's best error (0.012, at 32 candidates and 130 ms) at 16 candidates, 100 ms.
const KNOWN_CURVES: [(&str, u32, f64, f64); 6] = [
    ("ris+denoise", 8, 100.0, 0.020),
    ("ris+denoise", 16, 110.0, 0.015),
    ("ris+denoise", 32, 130.0, 0.012),
    ("restir-denoised", 8, 90.0, 0.015),
    ("restir-denoised", 16, 100.0, 0.012),
    ("restir-denoised", 32, 120.0, 0.010),
];

#[test]
fn a_cheaper_configuration_reads_its_known_ratio() {
    let dir = temp_dir("ratio");
    write_cell(&dir, "concourse-384x256-static", &KNOWN_CURVES);
    let cells = read_cells(&dir, "light_candidates").unwrap();
    assert_eq!(cells.len(), 1);
    let c = &cells[0];
    assert_eq!(
        (c.scene.as_str(), c.size.as_str()),
        ("builtin:concourse", "384×256")
    );
    assert_eq!(c.best_rmse, 0.012);
    let preset = &c.readings[1];
    let (ratio, _) = preset.ms_at_best.unwrap();
    assert!((ratio - 100.0 / 130.0).abs() < 1e-9, "{ratio}");
    assert_eq!(winner(c).unwrap().0, "restir-denoised");
    let (bias, _) = preset.squared_bias.unwrap();
    assert!((bias - 0.01 * 0.01 * 0.8).abs() < 1e-12);
    let md = markdown(&cells);
    assert!(
        md.contains("0.77×") && md.contains("`restir-denoised` 0.77×"),
        "{md}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_ratio_read_seed_by_seed_carries_the_loads_spread() {
    let dir = temp_dir("seeds");
    let rows = KNOWN_CURVES;
    // Four seeds; in seeds 1 and 3 the preset's frames ran 10 % slower than the mean's,
    // in 0 and 2 10 % faster: the ratios are 100/130 × (0.9, 1.1, 0.9, 1.1).
    let scale = [(1.0, 0.9), (1.0, 1.1), (1.0, 0.9), (1.0, 1.1)];
    write_cell_with_seeds(&dir, "concourse-384x256-static", &rows, &scale);
    let cells = read_cells(&dir, "light_candidates").unwrap();
    let preset = &cells[0].readings[1];
    let known = 100.0 / 130.0;
    let seeds = preset
        .ms_at_best_over_seeds
        .expect("an interval over the seeds");
    assert_eq!(seeds.samples, 4);
    assert!((seeds.mean - known).abs() < 1e-9, "{seeds:?}");
    // Sample sd of (0.9, 1.1, 0.9, 1.1) × known is 0.1155 × known; t(3) = 3.182; √4 = 2.
    let half = restir_render::metrics::seeds::t95(3) * (0.1f64 * 0.1 * 4.0 / 3.0).sqrt() / 2.0;
    assert!((seeds.half_width - half * known).abs() < 1e-9, "{seeds:?}");
    // The baseline against itself reads 1 in every seed: no spread, no brackets.
    let base = cells[0].readings[0].ms_at_best_over_seeds.unwrap();
    assert!((base.mean - 1.0).abs() < 1e-12 && base.half_width.abs() < 1e-12);
    let md = markdown(&cells);
    let (lo, hi) = (known - half * known, known + half * known);
    assert!(
        md.contains(&format!("0.77× [{lo:.2}–{hi:.2}] (0.83)")),
        "{md}"
    );
    // Planted: a cell that kept no per-seed timings states no interval.
    write_cell(&dir, "detail-384x256-static", &rows);
    let cells = read_cells(&dir, "light_candidates").unwrap();
    assert_eq!(cells[1].readings[1].ms_at_best_over_seeds, None);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cells_run_at_their_own_settings_share_columns_by_bare_name() {
    let dir = temp_dir("settings");
    let at = |depth: u32| -> Vec<(String, u32, f64, f64)> {
        KNOWN_CURVES
            .iter()
            .map(|&(c, k, ms, rmse)| (format!("{c}[denoise_iterations={depth}]"), k, ms, rmse))
            .collect()
    };
    for (name, depth) in [
        ("concourse-384x256-static", 2),
        ("detail-384x256-static", 1),
    ] {
        let rows = at(depth);
        let rows: Vec<(&str, u32, f64, f64)> =
            rows.iter().map(|r| (r.0.as_str(), r.1, r.2, r.3)).collect();
        write_cell(&dir, name, &rows);
    }
    let md = markdown(&read_cells(&dir, "light_candidates").unwrap());
    assert!(
        md.contains("| scene | camera | settings | ris+denoise | restir-denoised | cheapest |"),
        "{md}"
    );
    // Both cells read their ratio: neither is left as "—" for a name the other ran.
    assert_eq!(
        md.matches("| 1.00× (1.00) | 0.77× (0.83) |").count(),
        2,
        "{md}"
    );
    assert!(md.contains("| `denoise_iterations=1` |"), "{md}");
    std::fs::remove_dir_all(&dir).unwrap();
}
