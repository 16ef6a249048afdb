//! The map reads known curves back exactly: linear timings, errors that meet the
//! baseline's best at a measured point.

use super::*;

fn write_cell(dir: &Path, name: &str, rows: &[(&str, u32, f64, f64)]) {
    let cell = dir.join(name);
    std::fs::create_dir_all(&cell).unwrap();
    let mut csv = String::from(
        "config,light_candidates,median_frame_ms,shadow_rays_per_pixel,light_candidates_per_pixel,frame_luma_rmse_without_reference_noise,frame_luma_rmse_ci95\n",
    );
    let mut figures = Vec::new();
    for &(config, knob, ms, rmse) in rows {
        csv.push_str(&format!("{config},{knob},{ms},2.5,{knob},{rmse},0.0001\n"));
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

#[test]
fn a_cheaper_configuration_reads_its_known_ratio() {
    let dir = temp_dir("ratio");
    // Both timings linear in the knob (1.25 ms per candidate); the preset reaches the
    // baseline's best error (0.012, at 32 candidates and 130 ms) at 16 candidates, 100 ms.
    write_cell(
        &dir,
        "concourse-384x256-static",
        &[
            ("ris+denoise", 8, 100.0, 0.020),
            ("ris+denoise", 16, 110.0, 0.015),
            ("ris+denoise", 32, 130.0, 0.012),
            ("restir-denoised", 8, 90.0, 0.015),
            ("restir-denoised", 16, 100.0, 0.012),
            ("restir-denoised", 32, 120.0, 0.010),
        ],
    );
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
fn scattered_timings_are_read_along_their_fitted_line() {
    // Timings out of order (a busy machine): the fit restores the trend, so the curve is
    // read from cheap to dear in knob order.
    let mut points: Vec<CostPoint> = [(8, 120.0), (16, 100.0), (32, 140.0)]
        .iter()
        .map(|&(k, ms)| CostPoint {
            knob: k.to_string(),
            ms,
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
