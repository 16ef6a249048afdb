//! The bench with the camera or the scene moving (docs/src/measured/how-the-bench-measures.md,
//! "Errors where the view moves"): a pan and a walk get a reference per frame that follows the
//! camera, the denoiser stays finite there, and the error is stated within each frame's disoccluded
//! pixels and around moving triangles.

mod bench_support;
mod cli_support;
use bench_support::{quick_bench, temp};
use cli_support::viewer;

fn number(row: &std::collections::HashMap<String, String>, column: &str) -> f64 {
    row[column]
        .parse()
        .unwrap_or_else(|_| panic!("{column}: {:?} is not a number", row[column]))
}

/// `bench` on concourse at 48×32 with `camera`, ris and the default ReSTIR, each denoised
/// too; returns the rows of results.csv.
fn run(name: &str, camera: &str) -> Vec<std::collections::HashMap<String, String>> {
    quick_bench(
        name,
        "builtin:concourse",
        "48x32",
        &[
            "--frames",
            "6",
            "--warmup",
            "4",
            "--reference-spp",
            "64",
            "--camera",
            camera,
            "--configs",
            "ris,ris+denoise,restir-pairwise+denoise",
        ],
    )
}

#[test]
fn a_pan_and_a_walk_follow_the_camera_and_state_the_error_where_the_view_is_new() {
    let still = run("still", "static");
    let ris_still = number(&still[0], "mean_luma_rmse");
    assert!(
        still[0]["disoccluded_share"].is_empty(),
        "no masks when nothing moves"
    );
    for camera in ["pan:2", "walk:0.2"] {
        let rows = run(&camera.replace(':', "_"), camera);
        for r in &rows {
            assert_eq!(r["non_finite_pixels"], "0", "{camera}: {r:?}");
            for column in [
                "mean_luma_rmse",
                "disoccluded_share",
                "disoccluded_luma_rmse",
            ] {
                let v = number(r, column);
                assert!(v.is_finite() && v >= 0.0, "{camera} {column} = {v}");
            }
        }
        // Each frame is scored against the reference of its own camera: moving costs RIS
        // (which keeps no history) no accuracy. A reference left at the first camera
        // would put every edge of the hall two pixels off: several times the error.
        let ris = number(&rows[0], "mean_luma_rmse");
        assert!(
            ris < 1.5 * ris_still,
            "{camera}: ris per-frame RMSE {ris} against {ris_still} still"
        );
        // A pan of 2° a frame at a 48-pixel width brings in a column or two each frame.
        let share = number(&rows[0], "disoccluded_share");
        assert!(share > 0.01 && share < 0.5, "{camera}: disoccluded {share}");
    }
}

#[test]
fn a_moving_occluder_marks_the_pixels_around_it() {
    let rows = quick_bench(
        "occluder",
        "builtin:dynamic:moving-occluder",
        "48x32",
        &[
            "--frames",
            "4",
            "--warmup",
            "2",
            "--reference-spp",
            "16",
            "--configs",
            "ris",
        ],
    );
    let near = number(&rows[0], "near_moving_share");
    assert!(near > 0.0 && near < 0.8, "near moving {near}");
    assert!(number(&rows[0], "near_moving_luma_rmse").is_finite());
}

#[test]
fn bad_camera_paths_knobs_and_targets_get_one_line() {
    let out = temp("bad_motion");
    let o = out.to_str().unwrap();
    let bad = |extra: &[&str]| {
        let mut args = vec![
            "bench",
            "--scene",
            "builtin:cornell",
            "--size",
            "8x8",
            "--frames",
            "1",
            "--out",
            o,
        ];
        args.extend(extra);
        let run = viewer(&args);
        let err = String::from_utf8_lossy(&run.stderr).into_owned();
        assert!(
            !run.status.success() && run.status.code() != Some(101),
            "{extra:?}: {err}"
        );
        assert!(err.trim().lines().count() <= 3, "{extra:?}: {err}");
        err
    };
    for (flag, value, needle) in [
        ("--camera", "pan:200", "leaves nothing to reuse"),
        ("--camera", "walk:x", "walk:UNITS_PER_FRAME"),
        ("--knob", "light_candidates=4", "two values at least"),
        ("--knob", "nope=1,2", "nope"),
        ("--configs", "ris[light_candidates=4", "brackets"),
    ] {
        let err = bad(&[flag, value]);
        assert!(err.contains(needle), "{flag} {value}: {err}");
    }
    let err = bad(&["--knob", "light_candidates=1,2", "--target-rmse=-1"]);
    assert!(err.contains("--target-rmse"), "{err}");
}

/// A knob the renderer overrides is refused before anything renders: under `auto` the city
/// samples with the light BVH at most `AUTO_BVH_CANDIDATES`, so a sweep from there to twice
/// as many would measure one frame twice. Named (`light_sampler=bvh`), the same sweep runs.
#[test]
fn a_knob_that_auto_overrides_is_refused_and_a_named_sampler_runs() {
    let out = temp("knob_overridden");
    let o = out.to_str().unwrap();
    let auto = restir_render::effects::AUTO_BVH_CANDIDATES;
    let knob = format!("light_candidates={auto},{}", 2 * auto);
    let run = |extra: &[&str]| {
        let mut args = vec![
            "bench",
            "--scene",
            "builtin:city:4096",
            "--size",
            "8x8",
            "--frames",
            "1",
            "--warmup",
            "0",
            "--reference-spp",
            "8",
            "--configs",
            "ris",
            "--knob",
            &knob,
            "--quiet",
            "--out",
            o,
        ];
        args.extend(extra);
        viewer(&args)
    };
    let refused = run(&[]);
    let err = String::from_utf8_lossy(&refused.stderr).into_owned();
    assert!(
        !refused.status.success() && refused.status.code() != Some(101),
        "{err}"
    );
    assert!(
        err.contains("--knob light_candidates")
            && err.contains(&format!("would render with {auto}")),
        "{err}"
    );
    let named = run(&["--set", "light_sampler=bvh", "--seeds", "2"]);
    assert!(
        named.status.success(),
        "{}",
        String::from_utf8_lossy(&named.stderr)
    );
    // Each point keeps both seeds' median frame times (bench-map reads its cost ratios
    // seed by seed from them), and its milliseconds are their mean.
    let curves = std::fs::read_to_string(out.join("cost_curves.csv")).unwrap();
    let mut lines = curves.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (ms, seeds) = (column("median_frame_ms"), column("seed_median_frame_ms"));
    let points: Vec<&str> = lines.collect();
    assert_eq!(points.len(), 2, "{curves}");
    for line in points {
        let f: Vec<&str> = line.split(',').collect();
        let each: Vec<f64> = f[seeds].split(';').map(|x| x.parse().unwrap()).collect();
        assert_eq!(each.len(), 2, "{line}");
        let mean: f64 = f[ms].parse().unwrap();
        assert!(each.iter().all(|&x| x > 0.0), "{line}");
        assert!(
            (mean - (each[0] + each[1]) / 2.0).abs() < 1e-9 * mean,
            "{line}"
        );
    }
}
