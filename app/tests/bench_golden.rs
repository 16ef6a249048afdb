//! What `bench` writes cannot change unnoticed: five small runs that between them reach
//! every writer (a still camera over two seeds with its strip and seed maps, a `--knob`
//! cost curve and the crossover map read from it, a panning camera, a scene with light
//! events, the light-count sweep) write the files stored under `app/tests/bench_golden/`,
//! with the same numbers but for times (`bench_golden_support` says what is compared and
//! within what tolerance). Each run also leaves `command.txt`, the command line that remakes
//! its folder (so does `bench-rays --out`). The planted twins at the end show the
//! comparison reports a changed number and ignores a changed time.
//!
//! Run time on two cores with lavapipe (the tests in parallel): about 15 s once Mesa's
//! shader cache holds the variants, about 100 s with an empty one
//! (`MESA_SHADER_CACHE_DIR` pointed at an empty folder: every variant compiles first).
//! GPU tests: they need a wgpu adapter, lavapipe in CI.
//!
//! The stored runs were written by the bench before its code was split into stages. To
//! store new ones after a change that is meant to change what the bench writes, run
//! `BENCH_GOLDEN_BLESS=1 cargo test -p restir-viewer --test bench_golden` and say why in
//! the commit.

use std::path::{Path, PathBuf};
use std::process::Command;

mod bench_golden_support;
mod bench_support;

use bench_golden_support::{
    COMMAND_FILE, MANIFEST, compare_dirs, compare_text, csv_rows, manifest,
};

fn stored(run: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/bench_golden")
        .join(run)
}

/// `restir-viewer ARGS` with `{out}` and `{cache}` put in; fails with its stderr.
fn run(args: &[&str], out: &Path, cache: &Path) -> Vec<String> {
    let args: Vec<String> = args
        .iter()
        .map(|a| {
            a.replace("{out}", &out.to_string_lossy())
                .replace("{cache}", &cache.to_string_lossy())
        })
        .collect();
    let done = Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args(&args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("the restir-viewer binary runs");
    assert!(
        done.status.success(),
        "{args:?} failed (GPU tests need a wgpu adapter, lavapipe in CI):\n{}",
        String::from_utf8_lossy(&done.stderr)
    );
    args
}

/// The folder a command writes: its `--out`, or `bench-map`'s DIR.
fn folder_of(args: &[String]) -> PathBuf {
    match args.iter().position(|a| a == "--out") {
        Some(i) => PathBuf::from(&args[i + 1]),
        None => PathBuf::from(args.last().expect("bench-map DIR")),
    }
}

/// Runs `commands` in a fresh folder, then stores what they wrote (`BENCH_GOLDEN_BLESS`)
/// or compares it with what is stored under `run`.
fn check(run_name: &str, commands: &[&[&str]]) {
    let out = bench_support::temp(&format!("golden_{run_name}"));
    let cache = bench_support::temp(&format!("golden_{run_name}_cache"));
    let ran: Vec<Vec<String>> = commands.iter().map(|c| run(c, &out, &cache)).collect();
    if std::env::var_os("BENCH_GOLDEN_BLESS").is_some() {
        bless(run_name, &out);
        return;
    }
    let differences = compare_dirs(&stored(run_name), &out);
    assert!(
        differences.is_empty(),
        "{run_name} writes other numbers than before:\n{}",
        differences.join("\n")
    );
    for args in &ran {
        let written = std::fs::read_to_string(folder_of(args).join(COMMAND_FILE))
            .unwrap_or_else(|e| panic!("{args:?}: no {COMMAND_FILE}: {e}"));
        // These arguments need no quoting (a shell reads them back as they are).
        assert_eq!(
            written.trim_end(),
            format!("restir-viewer {}", args.join(" "))
        );
    }
}

/// Replaces the stored run with the text files of `out` and its manifest.
fn bless(run_name: &str, out: &Path) {
    let to = stored(run_name);
    let _ = std::fs::remove_dir_all(&to);
    let files = manifest(out);
    for f in files.iter().filter(|f| !f.contains(' ')) {
        let target = to.join(f);
        std::fs::create_dir_all(target.parent().unwrap()).unwrap();
        std::fs::copy(out.join(f), target).unwrap();
    }
    std::fs::create_dir_all(&to).unwrap();
    std::fs::write(to.join(MANIFEST), files.join("\n") + "\n").unwrap();
    eprintln!("stored {}", to.display());
}

const CONCOURSE: [&str; 7] = [
    "bench",
    "--scene",
    "builtin:concourse",
    "--size",
    "48x32",
    "--reference-spp",
    "64",
];

#[test]
fn the_still_bench_over_two_seeds_writes_what_it_wrote_before() {
    let mut still = CONCOURSE.to_vec();
    still.extend(["--frames", "4", "--configs", "nee,ris,restir-pairwise"]);
    still.extend(["--seeds", "2", "--out", "{out}", "--cache-dir", "{cache}"]);
    check("still", &[&still]);
}

#[test]
fn the_knob_bench_and_its_crossover_map_write_what_they_wrote_before() {
    let mut knob = CONCOURSE.to_vec();
    knob.extend(["--frames", "3", "--configs", "ris,restir-pairwise"]);
    knob.extend(["--knob", "light_candidates=4,8", "--seeds", "2"]);
    knob.extend(["--out", "{out}/concourse", "--cache-dir", "{cache}"]);
    check("knob", &[&knob, &["bench-map", "{out}"]]);
}

#[test]
fn the_panning_bench_writes_what_it_wrote_before() {
    let mut pan = CONCOURSE.to_vec();
    pan.extend(["--frames", "4", "--camera", "pan:0.5"]);
    pan.extend(["--configs", "ris,restir-pairwise"]);
    pan.extend(["--out", "{out}", "--cache-dir", "{cache}"]);
    check("pan", &[&pan]);
}

#[test]
fn the_bench_of_light_events_writes_what_it_wrote_before() {
    // 0.7 s + i/30: frame 9 is the blinking lights' switch at 1.0 s.
    let events = [
        "bench",
        "--scene",
        "builtin:dynamic:blinking-lights",
        "--size",
        "48x32",
        "--reference-spp",
        "8",
        "--frames",
        "24",
        "--time",
        "0.7",
        "--fps",
        "30",
        "--configs",
        "nee,restir-pairwise",
        "--out",
        "{out}",
        "--cache-dir",
        "{cache}",
    ];
    check("events", &[&events]);
}

#[test]
fn the_light_count_sweep_writes_what_it_wrote_before() {
    let sweep = [
        "bench",
        "--scene",
        "builtin:many-lights",
        "--size",
        "48x32",
        "--frames",
        "2",
        "--configs",
        "nee,ris",
        "--sweep-lights",
        "4,16",
        "--out",
        "{out}",
    ];
    check("sweep", &[&sweep]);
}

#[test]
fn bench_rays_writes_the_command_that_remakes_its_folder() {
    // Times alone, nothing to compare with a stored run: only the command file.
    let out = bench_support::temp("golden_rays");
    let args = [
        "bench-rays",
        "--scene",
        "builtin:cornell",
        "--size",
        "16x12",
        "--dispatches",
        "1",
        "--out",
        "{out}/rays",
    ];
    let ran = run(&args, &out, &out);
    let written = std::fs::read_to_string(out.join("rays").join(COMMAND_FILE)).unwrap();
    assert_eq!(
        written.trim_end(),
        format!("restir-viewer {}", ran.join(" "))
    );
}

/// The stored text of one file.
fn stored_text(path: &str) -> String {
    std::fs::read_to_string(stored(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `text` with the first occurrence of `from` (after `after`) replaced by `to`.
fn planted(text: &str, after: &str, from: &str, to: &str) -> String {
    let start = text.find(after).expect("the anchor is in the stored file") + after.len();
    let at = start
        + text[start..]
            .find(from)
            .expect("the value is in the stored file");
    format!("{}{to}{}", &text[..at], &text[at + from.len()..])
}

/// The value of `column` in the row of `config` of a stored CSV.
fn stored_cell(text: &str, config: &str, column: &str) -> String {
    let rows = csv_rows(text);
    let j = rows[0].iter().position(|c| c == column).unwrap();
    let row = rows.iter().find(|r| r[0] == config).unwrap();
    row[j].clone()
}

#[test]
fn planted_a_changed_error_is_reported_in_every_kind_of_file() {
    // results.csv: restir-pairwise's per-frame error 10 % higher.
    let csv = stored_text("still/results.csv");
    let value = stored_cell(&csv, "restir-pairwise", "mean_luma_rmse");
    let raised = (value.parse::<f64>().unwrap() * 1.1).to_string();
    let found = compare_text(
        "results.csv",
        &csv,
        &planted(&csv, "\nrestir-pairwise,", &value, &raised),
    );
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(
        found[0].contains("mean_luma_rmse") && found[0].contains(&raised),
        "{found:?}"
    );
    // figures.json: one seed's error.
    let json = stored_text("still/figures.json");
    let found = compare_text(
        "figures.json",
        &json,
        &planted(&json, "frame_luma_rmse_by_seed\": [", "0.", "0.9"),
    );
    assert_eq!(found.len(), 1, "{found:?}");
    // results.md: nee's per-frame error printed 20 % higher.
    let md = stored_text("still/results.md");
    let value = stored_md_cell(&md, "`nee`", 4);
    let raised = format!("{:.4}", value.parse::<f64>().unwrap() * 1.2);
    let found = compare_text(
        "results.md",
        &md,
        &planted(
            &md,
            "| `nee` | ",
            &format!(" {value} "),
            &format!(" {raised} "),
        ),
    );
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains(&raised), "{found:?}");
}

/// Cell `k` (from 1) of the first table row that starts with `name`.
fn stored_md_cell(md: &str, name: &str, k: usize) -> String {
    let line = md
        .lines()
        .find(|l| l.starts_with(&format!("| {name} |")))
        .unwrap();
    line.split(" | ").nth(k - 1).unwrap().to_string()
}

#[test]
fn planted_a_changed_time_is_not_reported() {
    let csv = stored_text("still/results.csv");
    let value = stored_cell(&csv, "ris", "median_frame_ms");
    let slower = (value.parse::<f64>().unwrap() * 3.0).to_string();
    let found = compare_text(
        "results.csv",
        &csv,
        &planted(&csv, "\nris,", &value, &slower),
    );
    assert!(found.is_empty(), "{found:?}");
    // results.md: `ris`'s ms/frame, the second cell of its row.
    let md = stored_text("still/results.md");
    let ms = stored_md_cell(&md, "`ris`", 2);
    let found = compare_text(
        "results.md",
        &md,
        &planted(&md, "| `ris` | ", &ms, "999.99"),
    );
    assert!(found.is_empty(), "{found:?}");
}
