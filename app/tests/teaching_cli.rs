//! The teaching tools headless (docs/src/tours.md, docs/src/viewer.md): every step of the
//! shipped tour renders (`render --tour FILE
//! --tour-step K`) with its settings, scene and camera, a broken tour gets one line; a
//! probed pixel's history drops when the lights switch off and recovers when they come
//! back, and equals that pixel in the per-frame images; a GIF decodes to its frames.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use image::AnimationDecoder;
use restir_render::LinearImage;

fn viewer(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run restir-viewer")
}

/// Runs `args`; fails with the command's output when it fails.
fn ok(args: &[&str]) -> Output {
    let out = viewer(args);
    assert!(
        out.status.success(),
        "{args:?} failed (GPU tests need a wgpu adapter, lavapipe in CI):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn temp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("teaching_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn tour_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/tours/restir.toml")
}

fn error_line(out: &Output) -> String {
    let lines: Vec<String> = String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| l.starts_with("error: "))
        .map(str::to_string)
        .collect();
    assert!(
        !out.status.success() && out.status.code() != Some(101),
        "{lines:?}"
    );
    assert_eq!(lines.len(), 1, "want one error line, got {lines:?}");
    lines[0].clone()
}

/// Asserts that each key of `table` that `settings` (a stats block) lists has the table's
/// value there; returns how many were checked.
fn check_settings(settings: &serde_json::Value, table: &toml::Table, step: &str) -> usize {
    let mut checked = 0;
    for (key, value) in table {
        let Some(shown) = settings[key].as_str() else {
            continue;
        };
        let wanted = match value {
            toml::Value::String(s) => s.clone(),
            other => other.to_string(),
        };
        let same = match (shown.parse::<f64>(), wanted.parse::<f64>()) {
            (Ok(a), Ok(b)) => a == b,
            _ => shown == wanted,
        };
        assert!(
            same,
            "step {step}: {key} is {shown}, the step says {wanted}"
        );
        checked += 1;
    }
    checked
}

/// The JSON a command wrote (`--stats`).
fn json_file(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The camera position a `--stats` file reports.
fn camera_position(stats: &serde_json::Value) -> Vec<f64> {
    stats["camera"]["position"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}
#[test]
fn every_step_of_the_shipped_tour_renders_with_its_settings_and_scene() {
    let dir = temp("tour");
    let text = std::fs::read_to_string(tour_file()).unwrap();
    let tour: toml::Table = text.parse().unwrap();
    let steps = tour["step"].as_array().unwrap();
    assert!(steps.len() >= 10);
    let (mut checked, mut cameras) = (0, 0);
    for (k, step) in steps.iter().enumerate() {
        let step = step.as_table().unwrap();
        let number = (k + 1).to_string();
        let png = dir.join(format!("step{number}.png"));
        let stats = dir.join(format!("step{number}.json"));
        ok(&[
            "render",
            "--tour",
            s(&tour_file()),
            "--tour-step",
            &number,
            "--size",
            "32x24",
            "--frames",
            "2",
            "--out",
            s(&png),
            "--stats",
            s(&stats),
            // The bias view's reference (the 1/M step), small and in this test's folder.
            "--reference-spp",
            "64",
            "--cache-dir",
            s(&dir.join("cache")),
        ]);
        assert!(png.is_file(), "step {number} wrote no image");
        let doc: serde_json::Value = json_file(&stats);
        let mode = step
            .get("mode")
            .and_then(|m| m.as_str())
            .unwrap_or("restir");
        assert_eq!(
            doc["mode"].as_str().unwrap().to_lowercase(),
            mode,
            "step {number}"
        );
        if let Some(scene) = step.get("scene").and_then(|v| v.as_str()) {
            assert_eq!(
                doc["scene"]["name"].as_str().unwrap(),
                scene,
                "step {number}"
            );
        }
        if let Some(camera) = step.get("camera").and_then(|c| c.as_table()) {
            let wanted: Vec<f64> = camera["position"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_float().or(v.as_integer().map(|i| i as f64)).unwrap())
                .collect();
            let shown: Vec<f64> = camera_position(&doc);
            let apart = wanted.iter().zip(&shown).map(|(a, b)| (a - b).abs());
            assert!(
                apart.fold(0.0, f64::max) < 1e-4,
                "step {number}: camera at {shown:?}"
            );
            cameras += 1;
        }
        // Every key of the step that is a parameter (the stats list them all), and of an
        // inline B in B's block.
        checked += check_settings(&doc["settings"], step, &number);
        match step.get("compare") {
            Some(toml::Value::Table(b)) => {
                checked += check_settings(&doc["compare"]["right"]["settings"], b, &number)
            }
            Some(_) => assert!(doc["compare"].is_object(), "step {number}"),
            None => assert!(doc["compare"].is_null(), "step {number}"),
        }
    }
    assert!(checked >= 8, "only {checked} parameters checked");
    assert!(cameras >= 1, "no step of the shipped tour sets a camera");
}

#[test]
fn a_step_sets_the_camera_and_a_broken_tour_gets_one_line() {
    let dir = temp("tour_camera");
    let tour = dir.join("camera.toml");
    std::fs::write(
        &tour,
        "[[step]]\ntitle = \"look\"\nscene = \"builtin:cornell\"\n\
         camera = { position = [0.1, 1.2, 2.5], look_at = [0.1, 1.2, 0.0], yfov_degrees = 30 }\n\
         m_cap = 7\n",
    )
    .unwrap();
    let stats = dir.join("camera.json");
    ok(&[
        "render",
        "--tour",
        s(&tour),
        "--size",
        "16x12",
        "--out",
        s(&dir.join("c.png")),
        "--stats",
        s(&stats),
        "--set",
        "spatial=false",
    ]);
    let doc: serde_json::Value = json_file(&stats);
    let position: Vec<f64> = camera_position(&doc);
    assert!((position[0] - 0.1).abs() < 1e-5 && (position[2] - 2.5).abs() < 1e-5);
    assert!((doc["camera"]["yfov_degrees"].as_f64().unwrap() - 30.0).abs() < 1e-3);
    // The step's parameter, and --set on top of it.
    assert_eq!(doc["settings"]["m_cap"], "7");
    assert_eq!(doc["settings"]["spatial"], "false");

    let broken = dir.join("broken.toml");
    std::fs::write(&broken, "[[step]]\ntitle = \"bad\"\nm_capp = 1\n").unwrap();
    let e = error_line(&viewer(&["render", "--tour", s(&broken), "--out", "x.png"]));
    assert!(
        e.contains("broken.toml") && e.contains("step 1 (\"bad\")") && e.contains("m_capp"),
        "{e}"
    );
    let e = error_line(&viewer(&[
        "render",
        "--tour",
        s(&tour),
        "--tour-step",
        "4",
        "--out",
        "x.png",
    ]));
    assert!(e.contains("--tour-step 4") && e.contains("1..=1"), "{e}");
}

/// A lit surface pixel (not a light seen directly, which goes black) with the largest
/// relative luminance drop across the first switch-off, from the images.
fn switching_pixel(frames: &[LinearImage], event: usize) -> (u32, u32) {
    let mean = |x: u32, y: u32, r: std::ops::Range<usize>| {
        let n = r.len() as f32;
        frames[r].iter().map(|f| f.luminance_at(x, y)).sum::<f32>() / n
    };
    let (w, h) = (frames[0].width, frames[0].height);
    let drop = |&(x, y): &(u32, u32)| {
        let before = mean(x, y, event - 6..event);
        let after = mean(x, y, event + 10..event + 25);
        if after > 0.1 * before && before < 2.0 {
            1.0 - after / before
        } else {
            0.0
        }
    };
    (0..w * h)
        .map(|i| (i % w, i / w))
        .max_by(|a, b| drop(a).total_cmp(&drop(b)))
        .unwrap()
}

#[test]
fn a_probed_pixel_drops_at_the_switch_off_recovers_and_matches_the_frames() {
    let dir = temp("probe");
    // From 0.7 s at 30 fps: half the lights go off at 1 s (frame 9) and on at 2 s (39).
    // M cap 5: the switch-off's ghost is gone within a few frames.
    let common = [
        "render",
        "--scene",
        "builtin:dynamic:blinking-lights",
        "--size",
        "48x32",
        "--frames",
        "52",
        "--time",
        "0.7",
        "--set",
        "m_cap=5",
        "--set",
        "jitter=false",
        "--seed",
        "3",
    ];
    let seq = dir.join("seq");
    let mut args = common.to_vec();
    args.extend(["--out-sequence", s(&seq), "--sequence-format", "exr"]);
    ok(&args);
    let frames: Vec<LinearImage> = (0..52)
        .map(|i| LinearImage::load_exr(&seq.join(format!("frame-{i:05}.exr"))).unwrap())
        .collect();
    let (x, y) = switching_pixel(&frames, 9);
    let csv = dir.join("probe.csv");
    let pixel = format!("{x},{y}");
    let mut args = common.to_vec();
    args.extend(["--probe", &pixel, "--probe-out", s(&csv)]);
    ok(&args);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 52);
    let luminance: Vec<f32> = rows
        .iter()
        .map(|r| r[column("luminance")].parse().unwrap())
        .collect();
    let events: Vec<usize> = (0..52)
        .filter(|&i| rows[i][column("event")] == "1")
        .collect();
    assert_eq!(events, vec![9, 39], "the light events of the scene");
    // The same seed renders the same frames: the series is the pixel in every image.
    for (i, f) in frames.iter().enumerate() {
        let p = f.get(x, y);
        let rgb: Vec<f32> = ["r", "g", "b"]
            .iter()
            .map(|c| rows[i][column(c)].parse().unwrap())
            .collect();
        assert_eq!(rgb, p[..3].to_vec(), "frame {i} at {x},{y}");
    }
    let mean =
        |r: std::ops::Range<usize>| luminance[r.clone()].iter().sum::<f32>() / r.len() as f32;
    let (before, off, on) = (mean(0..9), mean(25..39), mean(42..52));
    eprintln!("pixel {x},{y}: before {before:.4}, lights off {off:.4}, back on {on:.4}");
    // Single-pixel values: ReSTIR's per-frame noise here is ~30 %, hence the margins.
    let first = luminance[9..12].iter().copied().fold(f32::MAX, f32::min);
    assert!(
        first < 0.5 * before,
        "no drop at the switch-off frame: {luminance:?}"
    );
    assert!(
        off < 0.3 * before,
        "the pixel does not settle dark: {luminance:?}"
    );
    assert!(
        (0.6 * before..1.6 * before).contains(&on),
        "no recovery after the switch-on: {luminance:?}"
    );
    // M and the survivor's source are there on every row.
    assert!(
        rows.iter()
            .all(|r| r[column("m")].parse::<f32>().unwrap() >= 1.0)
    );
}

#[test]
fn a_gif_and_a_png_sequence_hold_every_frame_of_the_split_image() {
    let dir = temp("gif");
    let gif = dir.join("clip.gif");
    let seq = dir.join("frames");
    ok(&[
        "render",
        "--scene",
        "builtin:cornell",
        "--size",
        "24x16",
        "--frames",
        "6",
        "--compare",
        "ris",
        "--gif",
        s(&gif),
        "--out-sequence",
        s(&seq),
        "--exposure",
        "0",
    ]);
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(&gif).unwrap(),
    ))
    .unwrap();
    let frames = decoder.into_frames().collect_frames().unwrap();
    assert_eq!(frames.len(), 6);
    assert!(frames.iter().all(|f| f.buffer().dimensions() == (24, 16)));
    let pngs = std::fs::read_dir(&seq).unwrap().count();
    assert_eq!(pngs, 6);
    let last = image::open(seq.join("frame-00005.png")).unwrap();
    assert_eq!((last.width(), last.height()), (24, 16));
    // Bad destinations and probes are one-line errors before anything renders.
    // A small cornell render with `extra` appended: its one-line error.
    let refused = |extra: &[&str]| {
        let mut args = vec!["render", "--scene", "builtin:cornell", "--size", "24x16"];
        args.extend(extra);
        error_line(&viewer(&args))
    };
    let e = refused(&["--gif", s(&dir.join("a.png"))]);
    assert!(e.contains("--gif") && e.contains(".gif"), "{e}");
    let e = refused(&["--probe", "30,2", "--probe-out", s(&dir.join("p.csv"))]);
    assert!(e.contains("--probe 30,2: outside the 24x16 image"), "{e}");
    let e = error_line(&viewer(&["render", "--scene", "builtin:cornell"]));
    assert!(e.contains("nothing to write"), "{e}");
}
