//! The headless commands' contract: bad arguments and bad files exit non-zero with one
//! line naming the file (or argument) and the problem, never a panic; `scenes` and
//! `params` list what exists; `render` writes what it promises.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn viewer(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run restir-viewer")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("restir-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The error line (stderr lines that are not the Vulkan loader's noise).
fn error_lines(out: &Output) -> Vec<String> {
    String::from_utf8_lossy(&out.stderr)
        .lines()
        .filter(|l| l.starts_with("error: ") && !l.contains("XDG_RUNTIME_DIR"))
        .map(str::to_string)
        .collect()
}

fn assert_one_line_error(out: &Output, must_contain: &[&str]) {
    assert!(
        !out.status.success(),
        "should fail: {:?}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_ne!(
        out.status.code(),
        Some(101),
        "panicked: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines = error_lines(out);
    assert_eq!(lines.len(), 1, "want one error line, got {lines:?}");
    for needle in must_contain {
        assert!(
            lines[0].contains(needle),
            "'{}' does not mention '{needle}'",
            lines[0]
        );
    }
}

fn render(scene: &str, extra: &[&str], out: &Path) -> Output {
    let out = out.to_str().unwrap().to_string();
    let mut args = vec!["render", "--scene", scene, "--size", "16x12", "--out", &out];
    args.extend_from_slice(extra);
    viewer(&args)
}

const TRIANGLE_BIN: &[f32] = &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

/// A minimal one-triangle glTF whose JSON `tweak` can break.
fn write_gltf(
    dir: &Path,
    name: &str,
    tweak: impl Fn(&mut serde_json::Value),
    bin: &[u8],
) -> PathBuf {
    let mut doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"uri": format!("{name}.bin"), "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                        "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]}]
    });
    tweak(&mut doc);
    std::fs::write(dir.join(format!("{name}.bin")), bin).unwrap();
    let path = dir.join(format!("{name}.gltf"));
    std::fs::write(&path, serde_json::to_string(&doc).unwrap()).unwrap();
    path
}

#[test]
fn bad_files_fail_with_one_line_naming_the_file() {
    let dir = temp_dir("bad");
    let good_bin: Vec<u8> = bytemuck_cast(TRIANGLE_BIN);
    let nan_bin: Vec<u8> = bytemuck_cast(&[f32::NAN, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let out = dir.join("out.png");
    let malformed = dir.join("malformed.gltf");
    std::fs::write(&malformed, "{ \"asset\": { \"version\": ").unwrap();
    let cases: Vec<(PathBuf, &str)> = vec![
        (malformed, "malformed.gltf"),
        (write_gltf(&dir, "short", |_| {}, &good_bin[..20]), "short"),
        (write_gltf(&dir, "nan", |_| {}, &nan_bin), "nan.gltf"),
        (
            write_gltf(
                &dir,
                "required",
                |d| d["extensionsRequired"] = serde_json::json!(["KHR_draco_mesh_compression"]),
                &good_bin,
            ),
            "KHR_draco_mesh_compression",
        ),
        (
            write_gltf(
                &dir,
                "lines",
                |d| d["meshes"][0]["primitives"][0]["mode"] = 1.into(),
                &good_bin,
            ),
            "lines.gltf",
        ),
        (
            write_gltf(
                &dir,
                "empty",
                |d| d["scenes"][0]["nodes"] = serde_json::json!([]),
                &good_bin,
            ),
            "empty.gltf",
        ),
        (
            write_gltf(
                &dir,
                "badindex",
                |d| {
                    d["meshes"][0]["primitives"][0]["indices"] = 1.into();
                    // Indices read from the bytes of the float 1.0: 1065353216, far out of range.
                    d["accessors"].as_array_mut().unwrap().push(serde_json::json!({"bufferView": 0, "byteOffset": 12, "componentType": 5125, "count": 3, "type": "SCALAR"}));
                },
                &good_bin,
            ),
            "badindex.gltf",
        ),
        (dir.join("does-not-exist.glb"), "does-not-exist.glb"),
    ];
    for (file, needle) in cases {
        let res = render(file.to_str().unwrap(), &[], &out);
        assert!(
            !res.status.success(),
            "{} should be refused",
            file.display()
        );
        assert_one_line_error(&res, &[needle]);
    }
    let res = render("builtin:nope", &[], &out);
    assert_one_line_error(&res, &["nope"]);
}

fn bytemuck_cast(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

#[test]
fn bad_arguments_and_presets_fail_with_one_line() {
    let dir = temp_dir("args");
    let out = dir.join("out.png");
    let unknown = dir.join("unknown.toml");
    std::fs::write(&unknown, "m_cup = 3\n").unwrap();
    let wrong = dir.join("wrong.toml");
    std::fs::write(&wrong, "temporal = \"yes\"\n").unwrap();
    let garbage = dir.join("garbage.toml");
    std::fs::write(&garbage, "this is [not toml").unwrap();
    for (preset, needle) in [
        (&unknown, "m_cup"),
        (&wrong, "temporal"),
        (&garbage, "garbage.toml"),
    ] {
        let res = render(
            "builtin:cornell",
            &["--preset", preset.to_str().unwrap()],
            &out,
        );
        assert_one_line_error(&res, &[needle]);
    }
    assert_one_line_error(
        &render("builtin:cornell", &["--set", "m_cap=banana"], &out),
        &["m_cap"],
    );
    assert_one_line_error(
        &render("builtin:cornell", &["--set", "nope=1"], &out),
        &["nope"],
    );
    assert_one_line_error(
        &render("builtin:cornell", &["--mode", "magic"], &out),
        &["--mode"],
    );
    assert_one_line_error(
        &render("builtin:cornell", &["--debug-view", "magic"], &out),
        &["--debug-view"],
    );
    assert_one_line_error(
        &render("builtin:cornell", &["--size", "0x5"], &out),
        &["--size"],
    );
    assert_one_line_error(
        &render("builtin:cornell", &[], &dir.join("out.jpg")),
        &["--out"],
    );
}

#[test]
fn scenes_and_params_list_everything() {
    let scenes = viewer(&["scenes"]);
    assert!(scenes.status.success());
    let text = String::from_utf8_lossy(&scenes.stdout);
    for name in [
        "builtin:cornell",
        "builtin:many-lights",
        "builtin:hard:mirror",
        "builtin:hard:no-emitters",
        "builtin:dynamic:moving-light",
        "builtin:dynamic:blinking-lights",
        "builtin:dynamic:moving-occluder",
        "builtin:dynamic:many-lights",
    ] {
        assert!(
            text.lines().any(|l| l == name),
            "{name} missing from `scenes`"
        );
    }
    assert!(text.lines().all(|l| l.starts_with("builtin:")));
    let params = viewer(&["params"]);
    assert!(params.status.success());
    let text = String::from_utf8_lossy(&params.stdout);
    for def in restir_render::settings::PARAMS {
        assert!(
            text.contains(&format!("{} = ", def.name)),
            "{} missing from `params`",
            def.name
        );
    }
}

#[test]
fn render_writes_exr_png_debug_views_and_stats() {
    let dir = temp_dir("render");
    let exr = dir.join("frame.exr");
    let stats = dir.join("stats.json");
    let res = render(
        "builtin:cornell",
        &[
            "--frames",
            "3",
            "--accumulate",
            "--stats",
            stats.to_str().unwrap(),
        ],
        &exr,
    );
    assert!(
        res.status.success(),
        "{}",
        String::from_utf8_lossy(&res.stderr)
    );
    let img = restir_render::LinearImage::load_exr(&exr).unwrap();
    assert_eq!((img.width, img.height), (16, 12));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(json["frames"], 3);
    assert_eq!(json["nan_inf_pixels"], 0);
    for key in [
        "pass_ms_median",
        "temporal_rejections",
        "spatial_rejections",
        "source_fractions",
        "temporal_cap_fired_fraction",
        "fallback_tried",
        "effects",
        "passes",
    ] {
        assert!(!json[key].is_null(), "stats JSON lacks {key}");
    }
    for view in ["final", "source", "m", "rejection", "w"] {
        let png = dir.join(format!("{view}.png"));
        let res = render(
            "builtin:cornell",
            &["--frames", "2", "--debug-view", view],
            &png,
        );
        assert!(
            res.status.success(),
            "{view}: {}",
            String::from_utf8_lossy(&res.stderr)
        );
        let decoded = image::open(&png).unwrap().to_rgba8();
        assert_eq!(decoded.dimensions(), (16, 12));
    }
}

#[test]
fn render_takes_scene_time_and_reports_the_update_cost() {
    let dir = temp_dir("time");
    let png = dir.join("blink.png");
    let stats = dir.join("stats.json");
    let out = render(
        "builtin:dynamic:blinking-lights",
        &[
            "--frames",
            "3",
            "--time",
            "0.95",
            "--fps",
            "30",
            "--stats",
            stats.to_str().unwrap(),
        ],
        &png,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    let time = &doc["scene_time"];
    assert!((time["first_time"].as_f64().unwrap() - 0.95).abs() < 1e-6);
    // Frames at 0.95, 0.983, 1.017 s: the blink at 1 s changes the lights once.
    assert!((time["last_time"].as_f64().unwrap() - (0.95 + 2.0 / 30.0)).abs() < 1e-5);
    assert_eq!(time["updated_frames"].as_u64(), Some(1));
    assert!(doc["effects"].as_str().unwrap().contains("animation"));
    // A static scene has no scene_time block and no animation effect.
    let out = render(
        "builtin:cornell",
        &["--stats", stats.to_str().unwrap()],
        &png,
    );
    assert!(out.status.success());
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert!(doc.get("scene_time").is_none());
    assert!(!doc["effects"].as_str().unwrap().contains("animation"));
    for (arg, flag) in [
        ("--fps=-1", "--fps"),
        ("--time=nan", "--time"),
        ("--fps=inf", "--fps"),
    ] {
        assert_one_line_error(&render("builtin:cornell", &[arg], &png), &[flag]);
    }
}
