//! Figures over seeds and sweeps as independent jobs (docs/src/measured/how-the-bench-measures.md,
//! "Error bars"; docs/src/headless.md, "Sweeps as independent jobs"): `bench --seeds K` states
//! every image figure with an interval; `bench --list-jobs` / `--merge` and `bias-matrix
//! --list-jobs` / `--merge` run the same sweep as separate processes under GNU parallel,
//! and the merged table equals the one a single process writes.

use std::path::Path;
use std::process::Command;

mod bench_support;
mod cli_support;
use bench_support::{bench, csv, temp};
use cli_support::viewer;

fn stdout_of(args: &[&str]) -> String {
    let out = viewer(args);
    assert!(
        out.status.success(),
        "{args:?} failed (GPU tests need a wgpu adapter, lavapipe in CI):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Runs each line of `jobs` (one shell command each) under GNU parallel, two at a time.
fn run_under_parallel(jobs: &str) {
    let mut child = Command::new("parallel")
        .args(["--jobs", "2", "--halt", "now,fail=1"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| {
            panic!("GNU parallel is needed for this test (.ci/setup installs it): {e}")
        });
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(jobs.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "a job failed under parallel:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn bench_states_image_figures_over_seeds_and_its_jobs_merge_to_the_same_figures() {
    let dir = temp("seeds");
    let cache = dir.join("cache");
    let (out, cache_s) = (dir.join("one"), cache.to_str().unwrap().to_string());
    let args = |out: &Path| -> Vec<String> {
        [
            "--scene",
            "builtin:cornell",
            "--size",
            "24x16",
            "--frames",
            "32",
            "--seeds",
            "3",
            "--reference-spp",
            "256",
            "--configs",
            "nee,restir-pairwise",
            "--cache-dir",
            &cache_s,
            "--out",
            out.to_str().unwrap(),
        ]
        .map(String::from)
        .to_vec()
    };
    let one: Vec<String> = args(&out);
    bench(&strs(&one));
    let rows = csv(&out.join("results.csv"));
    for r in &rows {
        assert_eq!(r["image_seeds"], "3");
        // Every interval is there and finite.
        for column in ["frame_luma_rmse_ci95", "signed_bias_ci95", "variance"] {
            let v: f64 = r[column]
                .parse()
                .unwrap_or_else(|_| panic!("{column}: {:?}", r[column]));
            assert!(v.is_finite() && v >= 0.0, "{column} = {v}");
        }
        assert!(!r["bias_verdict"].is_empty());
    }
    // The equal-time gain over the first configuration, with its interval: exactly 1 for
    // the first, an interval around the second's.
    let gain = |r: &std::collections::HashMap<String, String>, c: &str| -> f64 {
        r[c].parse().unwrap_or_else(|_| panic!("{c}: {:?}", r[c]))
    };
    assert_eq!(gain(&rows[0], "equal_time_gain_vs_first"), 1.0);
    let (g, lo, hi) = (
        gain(&rows[1], "equal_time_gain_vs_first"),
        gain(&rows[1], "equal_time_gain_low"),
        gain(&rows[1], "equal_time_gain_high"),
    );
    assert!(
        0.0 < lo && lo < g && g < hi && hi.is_finite(),
        "{lo} {g} {hi}"
    );
    let md = read(&out.join("results.md"));
    assert!(md.contains("## Over 3 seeds"), "{md}");
    assert!(
        md.contains("## Equal time over 3 seeds: against `nee`")
            && md.contains("| `nee` |")
            && md.contains("1 (the baseline)"),
        "{md}"
    );
    assert!(out.join("seeds.png").is_file());

    // The same bench as one job per configuration under GNU parallel, then merged.
    let jobs_out = dir.join("jobs");
    let listed: Vec<String> = [
        &["bench".to_string()][..],
        &args(&jobs_out),
        &["--list-jobs".to_string()],
    ]
    .concat();
    let jobs = stdout_of(&strs(&listed));
    assert_eq!(
        jobs.lines().count(),
        2,
        "one job per configuration:\n{jobs}"
    );
    run_under_parallel(&jobs);
    let merge: Vec<String> = [
        &["bench".to_string()][..],
        &args(&jobs_out),
        &["--merge".to_string()],
    ]
    .concat();
    stdout_of(&strs(&merge));
    // Each job's figures are the single process's, number for number: the seeds render
    // the same frames whether or not other configurations interleave with them.
    let single: serde_json::Value = serde_json::from_str(&read(&out.join("figures.json"))).unwrap();
    let merged = csv(&jobs_out.join("figures.csv"));
    for (row, config) in merged.iter().zip(["nee", "restir-pairwise"]) {
        assert_eq!(row["config"], config);
        let figures = single
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["config"] == config)
            .unwrap();
        let mean = figures["figures"]["signed_bias"]["mean"].as_f64().unwrap();
        assert_eq!(
            row["signed_bias_mean"].parse::<f64>().unwrap(),
            mean,
            "{config}"
        );
    }
}

#[test]
fn the_bias_matrix_run_as_parallel_jobs_equals_the_single_process_table() {
    let dir = temp("matrix");
    let cache = dir.join("cache");
    let common = |out: &Path| -> Vec<String> {
        [
            "bias-matrix",
            "--scenes",
            "builtin:cornell,builtin:hard:no-emitters",
            "--estimators",
            "ris,restir-pairwise",
            "--size",
            "24x16",
            "--frames",
            "32",
            "--seeds",
            "2",
            "--reference-spp",
            "256",
            "--cache-dir",
            cache.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]
        .map(String::from)
        .to_vec()
    };
    let single = dir.join("single");
    let single_args = common(&single);
    stdout_of(&strs(&single_args));

    let jobs_out = dir.join("jobs");
    let mut list = common(&jobs_out);
    list.push("--list-jobs".into());
    let jobs = stdout_of(&strs(&list));
    assert_eq!(jobs.lines().count(), 4, "one job per cell:\n{jobs}");
    run_under_parallel(&jobs);
    let mut merge = common(&jobs_out);
    merge.push("--merge".into());
    stdout_of(&strs(&merge));

    for table in ["bias-matrix.md", "bias-matrix.csv"] {
        assert_eq!(
            read(&single.join(table)),
            read(&jobs_out.join(table)),
            "{table}: the merged table differs from the single process's"
        );
    }
    let rows = csv(&single.join("bias-matrix.csv"));
    assert_eq!(rows.len(), 4);
    for r in &rows {
        assert_eq!(r["status"], "ok", "{r:?}");
        let want = if r["scene"] == "builtin:hard:no-emitters" {
            "no light"
        } else {
            // Two seeds at 24×16 cannot resolve ±0.5 %: the honest verdict is "undecided"
            // or better, never "biased" for these unbiased estimators.
            ""
        };
        if want.is_empty() {
            assert_ne!(r["verdict"], "biased", "{r:?}");
        } else {
            assert_eq!(r["verdict"], want, "{r:?}");
        }
    }
}

#[test]
fn a_merge_before_the_jobs_ran_names_the_missing_cells_and_bad_values_get_one_line() {
    let dir = temp("matrix-missing");
    let out = viewer(&[
        "bias-matrix",
        "--scenes",
        "builtin:cornell",
        "--estimators",
        "ris",
        "--out",
        dir.to_str().unwrap(),
        "--merge",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("1 of 1 cells (or their confirmations) have no output")
            && err.contains("builtin_cornell/ris"),
        "{err}"
    );
    for (flag, value, needle) in [
        ("--seeds", "1", "two seeds"),
        ("--frames", "8", "two batches"),
        ("--estimators", "octree", "neither a configuration"),
        ("--scenes", "nowhere.gltf", "not found"),
        ("--confirm", "4000000000", "at most 64"),
    ] {
        let out = viewer(&["bias-matrix", "--out", dir.to_str().unwrap(), flag, value]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && out.status.code() != Some(101),
            "{flag} {value}: {err}"
        );
        assert!(err.contains(needle), "{flag} {value}: {err}");
    }
}
