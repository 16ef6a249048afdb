//! `bench`'s lag metrics on `builtin:dynamic:blinking-lights` end to end
//! (docs/src/measured/how-the-bench-measures.md, "Light events: lag and ghosting"): the lag columns
//! of `results.csv` are there and finite for the switch-off at 1 s, `events.csv`, `lag.png`,
//! `lag_vs_noise.png` and `event_strip.png` are written, and — test power — a configuration that
//! cannot let go of its history (M cap 10⁶, ratio clamp off) shows far more lag than one without
//! history (M cap 1). GPU test (lavapipe in CI); ~15 s there.

mod bench_support;

use std::path::PathBuf;

use bench_support::{assert_png, bench, csv, temp};

fn preset(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/bench/lag")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

#[test]
fn bench_lag_metrics_see_the_switch_off_and_the_planted_lag() {
    let out = temp("lag");
    let cache = temp("lag_cache");
    let configs = format!(
        "{},{}",
        preset("mcap-1.toml"),
        preset("mcap-1e6-no-clamp.toml")
    );
    // 0.7 s + i/30: frame 9 is the switch-off at 1.0 s; 24 frames leave a 15-frame segment
    // (a steady window needs 10) and 5 frames before it for the carried-over level.
    bench(&[
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
        "--seeds",
        "2",
        "--configs",
        &configs,
        "--out",
        out.to_str().unwrap(),
        "--cache-dir",
        cache.to_str().unwrap(),
    ]);
    let rows = csv(&out.join("results.csv"));
    assert_eq!(rows.len(), 2);
    let value = |r: &std::collections::HashMap<String, String>, column: &str| -> f64 {
        let v: f64 = r[column]
            .parse()
            .unwrap_or_else(|_| panic!("{}: {column} = '{}'", r["config"], r[column]));
        assert!(v.is_finite(), "{}: {column} = {v}", r["config"]);
        v
    };
    for r in &rows {
        assert_eq!(
            (r["events"].as_str(), r["event_source"].as_str()),
            ("1", "scene")
        );
        assert_eq!((r["event_frame"].as_str(), r["seeds"].as_str()), ("9", "2"));
        // One row per configuration and event: this run has one event, event 0.
        assert_eq!(r["event"], "0");
        assert_eq!(value(r, "event_time"), 1.0);
        for column in ["peak_error", "steady_error", "peak_over_steady", "lag_area"] {
            assert!(value(r, column) >= 0.0);
        }
        value(r, "signed_bias");
        let recovery = r["recovery_frames"].as_str();
        assert!(
            recovery == "never" || recovery.parse::<f64>().is_ok_and(|v| v >= 0.0),
            "{recovery}"
        );
    }
    // Test power. M cap 1 has no history: its error drops with the image (lag area is
    // only the noise above its steady median, ~0.1 at 96×64). M cap 10⁶ keeps the
    // pre-event reservoirs' weight and never recovers: measured here 2.67 against 0.083
    // (32×; 78× at 96×64 with 64-spp references); 3× leaves room for the 8-spp references'
    // noise and other seeds.
    let (free, stuck) = (value(&rows[0], "lag_area"), value(&rows[1], "lag_area"));
    assert!(stuck > 3.0 * free, "M cap 1e6 {stuck} vs M cap 1 {free}");
    assert_eq!(rows[1]["recovery_frames"], "never");
    assert_eq!(csv(&out.join("events.csv")).len(), 2);
    assert!(
        std::fs::read_to_string(out.join("results.md"))
            .unwrap()
            .contains("## Lag around events (2 seeds")
    );
    // No running average with a reference per frame.
    assert!(!out.join("error_vs_time.png").exists());
    assert_png(&out.join("lag.png"));
    assert_png(&out.join("lag_vs_noise.png"));
    assert_png(&out.join("event_strip.png"));
}
