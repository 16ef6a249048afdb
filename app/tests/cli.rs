//! The headless commands' contract: bad arguments and bad files exit non-zero with one
//! line naming the file (or argument) and the problem, never a panic; `scenes` and
//! `params` list what exists; `render` writes what it promises.

use std::path::{Path, PathBuf};
use std::process::Output;

mod cli_support;
use cli_support::{temp_dir, viewer};

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

/// The JSON a command wrote (`--stats`, a bench's summary).
fn json_file(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn assert_success(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn render(scene: &str, extra: &[&str], out: &Path) -> Output {
    let out = out.to_str().unwrap().to_string();
    let mut args = vec!["render", "--scene", scene, "--size", "16x12", "--out", &out];
    args.extend_from_slice(extra);
    viewer(&args)
}

/// `render --compare B --debug-view difference` of the Cornell box with `args`: whether
/// |A − B| is 0 everywhere, i.e. every pixel is viridis' first stop (heatmap(0) = (0.267,
/// 0.005, 0.329) linear, sRGB-encoded (141, 16, 155); 2 levels of slack for rounding).
fn difference_is_zero(dir: &Path, args: &[&str], b: &str) -> bool {
    let out = dir.join(format!("difference-{b}.png"));
    let extra = [args, &["--compare", b, "--debug-view", "difference"]].concat();
    let res = render("builtin:cornell", &extra, &out);
    assert_success(&res);
    let zero = [141u8, 16, 155];
    image::open(&out)
        .unwrap()
        .to_rgb8()
        .pixels()
        .all(|p| p.0.iter().zip(zero).all(|(a, b)| a.abs_diff(b) <= 2))
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
                |d| d["extensionsRequired"] = serde_json::json!(["EXT_unknown_compression"]),
                &good_bin,
            ),
            "uses EXT_unknown_compression",
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
    // The light samplers (docs/src/light-samplers.md): an unknown sampler or a number that
    // is none is refused in one line; ReGIR values out of range are clamped, with one line
    // saying so.
    for (set, name) in [
        ("light_sampler=octree", "light_sampler"),
        ("regir_jitter=nan", "regir_jitter"),
    ] {
        assert_one_line_error(&render("builtin:cornell", &["--set", set], &out), &[name]);
    }
    for (set, said) in [
        ("regir_grid=0", "regir_grid: 0 is outside 1..=32, using 1"),
        (
            "regir_slots=100000",
            "regir_slots: 100000 is outside 1..=1024, using 1024",
        ),
        ("regir_cell_size=-1", "regir_cell_size: -1 is outside"),
    ] {
        let res = render(
            "builtin:cornell",
            &["--set", set, "--set", "light_sampler=regir"],
            &out,
        );
        let stderr = String::from_utf8_lossy(&res.stderr);
        assert!(res.status.success(), "{set}: {stderr}");
        assert_eq!(
            stderr.lines().filter(|l| l.contains(said)).count(),
            1,
            "{set}: {stderr}"
        );
    }
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
    // Each line: the name (padded), two spaces, a one-line description.
    let entries: Vec<(&str, &str)> = text
        .lines()
        .map(|l| {
            let (name, line) = l.split_once("  ").unwrap_or((l, ""));
            (name.trim(), line.trim())
        })
        .collect();
    assert!(
        entries
            .iter()
            .all(|(n, line)| n.starts_with("builtin:") && !line.is_empty()),
        "every line names a scene and says what it is: {text}"
    );
    assert!(
        entries
            .iter()
            .any(|(n, _)| *n == "builtin:concourse (default)"),
        "the showcase is the marked default: {text}"
    );
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
            entries.iter().any(|(n, _)| *n == name),
            "{name} missing from `scenes`"
        );
    }
    // The families too, with their range, so that a newcomer finds the city.
    for family in [
        "builtin:city:N",
        "builtin:city-traffic:N",
        "builtin:many-lights:N",
    ] {
        assert!(
            entries
                .iter()
                .any(|(n, _)| *n == format!("{family} (N lights, 1 to 4194304)")),
            "{family} missing from `scenes`: {text}"
        );
    }
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
    assert_success(&res);
    let img = restir_render::LinearImage::load_exr(&exr).unwrap();
    assert_eq!((img.width, img.height), (16, 12));
    let json: serde_json::Value = json_file(&stats);
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
        "driver",
        "ray_backend",
        "ray_query_available",
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

/// `render --compare B`: the left half is this configuration's render, the right half
/// B's, pixel for pixel (each side has its own renderer and history, same seed), and the
/// stats JSON has a block per side.
#[test]
fn the_split_image_halves_match_single_configuration_renders() {
    let dir = temp_dir("compare");
    let frames = ["--frames", "4", "--set", "jitter=false"];
    let single = |mode: &str, name: &str| {
        let out = dir.join(name);
        let res = render(
            "builtin:cornell",
            &[&frames[..], &["--mode", mode]].concat(),
            &out,
        );
        assert_success(&res);
        restir_render::LinearImage::load_exr(&out).unwrap()
    };
    let restir = single("restir", "restir.exr");
    let ris = single("ris", "ris.exr");
    let split_path = dir.join("split.exr");
    let stats = dir.join("split.json");
    let extra = [
        &frames[..],
        &["--compare", "ris", "--stats", stats.to_str().unwrap()],
    ]
    .concat();
    let res = render("builtin:cornell", &extra, &split_path);
    assert_success(&res);
    let split = restir_render::LinearImage::load_exr(&split_path).unwrap();
    assert_eq!((split.width, split.height), (16, 12));
    // The two configurations differ, so matching halves prove where each side comes from.
    assert_ne!(restir.pixels, ris.pixels);
    for y in 0..12 {
        for x in 0..16 {
            let expected = if x < 8 {
                restir.get(x, y)
            } else {
                ris.get(x, y)
            };
            assert_eq!(split.get(x, y), expected, "pixel ({x}, {y})");
        }
    }
    let json: serde_json::Value = json_file(&stats);
    let compare = &json["compare"];
    assert_eq!(compare["divider_column"], 8);
    assert_eq!(compare["right_config"], "ris");
    assert_eq!(compare["left"]["mode"], "Restir");
    assert_eq!(compare["right"]["mode"], "Ris");
    assert_eq!(compare["right"]["frames"], 4);
    // The radius the renderer used at this height (30 px at 1080p → the 2 px floor).
    assert_eq!(json["effective_spatial_radius_px"], 2.0);
    // PNG: the display of each side, split the same way.
    let png = dir.join("split.png");
    let res = render(
        "builtin:cornell",
        &[&frames[..], &["--compare", "nee"]].concat(),
        &png,
    );
    assert_success(&res);
    // The difference view: B identical to A (same configuration and seed) is |A − B| = 0
    // everywhere (viridis' first stop), B = nee is not.
    assert!(
        difference_is_zero(&dir, &frames, "restir"),
        "|A − A| is not 0"
    );
    assert!(
        !difference_is_zero(&dir, &frames, "nee"),
        "|A − nee| is 0 everywhere"
    );
    let bad = render("builtin:cornell", &["--compare", "magic"], &png);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--compare 'magic'"));
}

/// `light_sampler=auto` (the default; docs/src/light-samplers.md) presamples tiles only from
/// the measured break-even light count on, and takes the light BVH where the load-time
/// probe finds the lights local; the stats JSON says which and why.
#[test]
fn light_sampler_auto_drops_tiles_for_few_lights_and_keeps_them_for_many() {
    let dir = temp_dir("tiles");
    let effects_of = |scene: &str, extra: &[&str]| {
        let stats = dir.join("stats.json");
        let out = dir.join("frame.exr");
        let args = [&["--stats", stats.to_str().unwrap()][..], extra].concat();
        let res = render(scene, &args, &out);
        assert_success(&res);
        let json: serde_json::Value = json_file(&stats);
        let effects = json["effects"].as_str().unwrap().to_string();
        let reason = json["effect_reasons"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r[0] == "light-tiles")
            .map(|r| r[1].as_str().unwrap().to_string())
            .unwrap();
        (effects.split(',').any(|e| e == "light-tiles"), reason)
    };
    let (cornell, why) = effects_of("builtin:cornell", &[]);
    assert!(!cornell, "cornell keeps tiles: {why}");
    assert!(why.contains("2 lights <"), "{why}");
    let (many, why) = effects_of("builtin:many-lights:65536", &[]);
    assert!(many, "many-lights:65536 drops tiles: {why}");
    let (forced, _) = effects_of("builtin:cornell", &["--set", "light_sampler=tiles"]);
    assert!(forced, "light_sampler=tiles forces them");
    // The light BVH by the load-time probe: the city's lights are local, the room's are
    // not; the figure is in the reason, the same on every run (a fixed seed).
    let (_, city) = effects_of("builtin:city:4096", &[]);
    assert!(
        city.contains("the light sampler is bvh") && city.contains("the probe at 256 points"),
        "{city}"
    );
    let candidates = || {
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("stats.json")).unwrap())
                .unwrap();
        json["light_candidates_per_pixel"].as_f64().unwrap()
    };
    // auto's BVH draws its measured count (effects::AUTO_BVH_CANDIDATES), not 32.
    let auto = restir_render::effects::AUTO_BVH_CANDIDATES as f64;
    assert!((candidates() - auto).abs() < 1e-6, "{}", candidates());
    let probe: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("stats.json")).unwrap()).unwrap();
    let locality = probe["light_probe"]["locality_x100"].as_u64().unwrap();
    assert!(
        locality >= 1200,
        "the probe's figure in --stats: {locality}"
    );
    let (_, again) = effects_of("builtin:city:4096", &[]);
    assert_eq!(city, again, "the probe is deterministic");
    effects_of("builtin:city:4096", &["--set", "light_sampler=bvh"]);
    assert!((candidates() - 32.0).abs() < 1e-6, "{}", candidates());
    let (_, room) = effects_of("builtin:many-lights:65536", &[]);
    assert!(room.contains("not worth the walk"), "{room}");
}

#[test]
fn env_flags_render_a_sky_and_bad_environments_fail_with_one_line() {
    let dir = temp_dir("env");
    let png = dir.join("sky.png");
    let stats = dir.join("sky.json");
    let stats_arg = stats.to_str().unwrap().to_string();
    let ok = render(
        "builtin:cornell",
        &[
            "--env",
            "builtin:sky",
            "--env-strength",
            "2",
            "--env-rotation",
            "-90",
            "--stats",
            &stats_arg,
        ],
        &png,
    );
    assert_success(&ok);
    let json: serde_json::Value = json_file(&stats);
    let env = &json["scene"]["environment"];
    assert_eq!(env["name"], "builtin:sky");
    assert_eq!(env["strength"], 2.0);
    assert_eq!(env["rotation_deg"], -90.0);
    assert!(json["effects"].as_str().unwrap().contains("environment"));

    let bad = dir.join("bad.hdr");
    std::fs::write(
        &bad,
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n\x02",
    )
    .unwrap();
    let bad_arg = bad.to_str().unwrap().to_string();
    for (args, needles) in [
        (
            vec!["--env", bad_arg.as_str()],
            vec![bad_arg.as_str(), "cannot decode"],
        ),
        (
            vec!["--env", "/no/such/sky.exr"],
            vec!["/no/such/sky.exr", "cannot read"],
        ),
        (
            vec!["--env", "builtin:sky", "--env-strength", "-1"],
            vec!["--env-strength"],
        ),
        (vec!["--env-rotation", "10"], vec!["need --env"]),
    ] {
        assert_one_line_error(&render("builtin:cornell", &args, &png), &needles);
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
    assert_success(&out);
    let doc: serde_json::Value = json_file(&stats);
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
    let doc: serde_json::Value = json_file(&stats);
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

/// `render --stats` reports the file's extensions (what the loader did with each) and
/// whether the camera was chosen automatically; a file requiring a compression this build
/// does not decode is refused in one line naming it.
#[test]
fn render_stats_report_the_files_extensions_and_automatic_camera() {
    let dir = temp_dir("extensions");
    let bin: Vec<u8> = bytemuck_cast(TRIANGLE_BIN);
    let scene = write_gltf(
        &dir,
        "ext",
        |d| {
            d["extensionsUsed"] =
                serde_json::json!(["KHR_texture_transform", "KHR_texture_basisu", "EXT_other"]);
            d["materials"] = serde_json::json!([{ "emissiveFactor": [1.0, 1.0, 1.0] }]);
            d["meshes"][0]["primitives"][0]["material"] = 0.into();
        },
        &bin,
    );
    let stats = dir.join("stats.json");
    let res = render(
        scene.to_str().unwrap(),
        &["--frames", "1", "--stats", stats.to_str().unwrap()],
        &dir.join("out.exr"),
    );
    assert_success(&res);
    let json: serde_json::Value = json_file(&stats);
    assert_eq!(json["scene"]["camera_automatic"], true);
    let extensions = json["scene"]["extensions"]
        .as_array()
        .expect("extensions array");
    let pairs: Vec<(&str, &str)> = extensions
        .iter()
        .map(|e| (e["name"].as_str().unwrap(), e["status"].as_str().unwrap()))
        .collect();
    assert_eq!(
        pairs,
        [
            ("KHR_texture_transform", "used"),
            ("KHR_texture_basisu", "partly_used"),
            ("EXT_other", "ignored")
        ]
    );
    assert!(
        extensions[1]["detail"]
            .as_str()
            .unwrap()
            .contains("ETC1S and UASTC LDR")
    );
    let required = write_gltf(
        &dir,
        "unknown",
        |d| {
            d["extensionsUsed"] = serde_json::json!(["EXT_unknown_compression"]);
            d["extensionsRequired"] = serde_json::json!(["EXT_unknown_compression"]);
        },
        &bin,
    );
    let out = render(
        required.to_str().unwrap(),
        &["--frames", "1"],
        &dir.join("d.exr"),
    );
    assert_one_line_error(
        &out,
        &[
            "unknown.gltf",
            "uses EXT_unknown_compression (not implemented",
        ],
    );
}

/// `--set ray_backend=ray-query` (docs/src/ray-tracing.md, "Choosing a backend") where the device
/// has no ray queries (here: the device created without them, `RESTIR_NO_RAY_QUERY=1`) is one line;
/// with them it renders and the stats name the backend; `bench-rays` measures both backends.
#[test]
fn ray_backends_are_named_refused_clearly_and_measured() {
    let dir = temp_dir("rays");
    let png = dir.join("rq.png");
    let png_arg = png.to_str().unwrap();
    let refused = std::process::Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args([
            "render",
            "--scene",
            "builtin:cornell",
            "--size",
            "16x12",
            "--out",
            png_arg,
        ])
        .args(["--set", "ray_backend=ray-query"])
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .env("RESTIR_NO_RAY_QUERY", "1")
        .output()
        .unwrap();
    assert_one_line_error(
        &refused,
        &[
            "ray_backend=ray-query",
            "ray queries",
            "RESTIR_NO_RAY_QUERY=1",
        ],
    );
    let stats = dir.join("rq.json");
    let res = render(
        "builtin:cornell",
        &[
            "--frames",
            "2",
            "--set",
            "ray_backend=ray-query",
            "--stats",
            stats.to_str().unwrap(),
        ],
        &png,
    );
    assert!(
        res.status.success(),
        "this test needs ray queries (Mesa 25 lavapipe, docs/src/getting-started.md): {}",
        String::from_utf8_lossy(&res.stderr)
    );
    let json: serde_json::Value = json_file(&stats);
    assert_eq!(json["ray_backend"], "ray-query");
    assert_eq!(json["ray_query_available"], true);
    let out = dir.join("bench");
    let res = viewer(&[
        "bench-rays",
        "--scene",
        "builtin:cornell",
        "--size",
        "16x12",
        "--dispatches",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_success(&res);
    let csv = std::fs::read_to_string(out.join("rays.csv")).unwrap();
    for row in [
        "software,shadow",
        "software,closest-hit",
        "ray-query,shadow",
        "ray-query,closest-hit",
    ] {
        assert!(csv.contains(row), "rays.csv lacks {row}:\n{csv}");
    }
    // Every row counted rays (16 per surface pixel; most of the box's pixels see a surface).
    for line in csv.lines().skip(1) {
        let rays: u64 = line.split(',').nth(4).unwrap().parse().unwrap();
        assert!(rays >= 16 * 16 * 12 / 2, "{line}");
    }
}

/// `bench-load` prints and writes each phase from file to first frame and the compile table
/// (by pass and effect set; docs/src/compile-time.md), and `render --stats` has the same
/// phases in its `load` block, each pipeline with its first dispatch.
#[test]
fn load_phases_are_printed_written_and_in_the_stats() {
    let dir = temp_dir("load");
    let csv = dir.join("load.csv");
    let compile_csv = dir.join("compile.csv");
    let res = viewer(&[
        "bench-load",
        "builtin:cornell",
        "--size",
        "16x12",
        "--csv",
        csv.to_str().unwrap(),
        "--compile-csv",
        compile_csv.to_str().unwrap(),
    ]);
    assert_success(&res);
    let text = std::fs::read_to_string(&csv).unwrap();
    for phase in [
        "build",
        "validate",
        "BVH build",
        "light table",
        "pipelines",
        "first frame",
    ] {
        assert!(
            text.contains(&format!(",{phase},")),
            "load.csv lacks {phase}:\n{text}"
        );
    }
    let stdout = String::from_utf8_lossy(&res.stdout);
    assert!(stdout.contains("| pipelines |"));
    // The compile table: one row per pipeline the frames compiled, named by pass, with the
    // effect set (not timed here: only present and named).
    assert!(stdout.contains("Compile time by pass"), "{stdout}");
    let table = std::fs::read_to_string(&compile_csv).unwrap();
    let mut lines = table.lines();
    assert_eq!(
        lines.next(),
        Some("scene,pass,variant,compile_ms,creation_ms,first_dispatch_ms,steady_ms")
    );
    let passes: Vec<&str> = lines.map(|l| l.split(',').nth(1).unwrap()).collect();
    for pass in ["gbuffer resolve", "initial", "temporal", "spatial", "shade"] {
        assert!(passes.contains(&pass), "compile.csv lacks {pass}:\n{table}");
        assert!(stdout.contains(&format!("| {pass} |")), "{stdout}");
    }
    assert!(
        table.contains("AREA_LIGHTS"),
        "the effect set is named:\n{table}"
    );
    let png = dir.join("x.png");
    let stats = dir.join("x.json");
    let res = render(
        "builtin:cornell",
        &["--frames", "2", "--stats", stats.to_str().unwrap()],
        &png,
    );
    assert_success(&res);
    assert!(
        String::from_utf8_lossy(&res.stderr).contains("BVH build"),
        "render prints the phases as they finish"
    );
    let json: serde_json::Value = json_file(&stats);
    let names: Vec<&str> = json["load"]["phases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names.first(), Some(&"build"));
    assert_eq!(names.last(), Some(&"first frame"));
    assert!(json["load"]["total_ms"].as_f64().unwrap() > 0.0);
    let pipelines = json["load"]["pipelines"].as_array().unwrap();
    assert!(!pipelines.is_empty());
    // Two still frames dispatch every pipeline they compiled.
    for p in pipelines {
        assert!(p["first_dispatch_ms"].as_f64().is_some(), "{p}");
    }
}

/// `bench-shifts` (docs/src/restir-pt.md, "The CPU model") prints one row per place and shift
/// (against the place's reference) and writes the same rows as CSV; a bad count is a one-line
/// error.
#[test]
fn bench_shifts_prints_and_writes_a_row_per_place_and_shift() {
    let dir = temp_dir("shifts");
    let csv = dir.join("shifts.csv");
    let res = viewer(&[
        "bench-shifts",
        "--trials",
        "200",
        "--reference-paths",
        "20000",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert_success(&res);
    let stdout = String::from_utf8_lossy(&res.stdout);
    assert!(stdout.contains("| place | shift |"), "{stdout}");
    let text = std::fs::read_to_string(&csv).unwrap();
    // A header and 4 places × 3 shifts.
    assert_eq!(text.lines().count(), 1 + 4 * 3, "{text}");
    for shift in ["reconnection", "random replay", "hybrid"] {
        assert!(text.contains(&format!(",{shift},")), "{text}");
        assert!(stdout.contains(&format!("| {shift} |")), "{stdout}");
    }
    // Every row's neighbours were shifted at least once (200 trials × 4 neighbours).
    for line in text.lines().skip(1) {
        let counts: u64 = line
            .rsplit(',')
            .skip(1)
            .take(6)
            .map(|c| c.parse::<u64>().unwrap())
            .sum();
        assert!(counts > 0, "{line}");
    }
    assert_one_line_error(&viewer(&["bench-shifts", "--trials", "1"]), &["--trials"]);
}

/// The denoiser from the command line: its views render, and a split screen against
/// `restir+raw` is raw | denoised (the difference view is not zero there, and is against
/// `restir+denoise`, the same configuration).
#[test]
fn denoised_renders_draw_their_views_and_split_against_raw() {
    let dir = temp_dir("denoise");
    let frames = [
        "--frames",
        "4",
        "--set",
        "jitter=false",
        "--set",
        "denoise=true",
    ];
    for view in [
        "denoise-input",
        "history-length",
        "denoise-variance",
        "temporal-gradient",
    ] {
        let png = dir.join(format!("{view}.png"));
        let extra = [&frames[..], &["--debug-view", view]].concat();
        let res = render("builtin:cornell", &extra, &png);
        assert!(
            res.status.success(),
            "{view}: {}",
            String::from_utf8_lossy(&res.stderr)
        );
        assert_eq!(image::open(&png).unwrap().to_rgba8().dimensions(), (16, 12));
    }
    assert!(
        difference_is_zero(&dir, &frames, "restir+denoise"),
        "|A − A| is not 0"
    );
    assert!(
        !difference_is_zero(&dir, &frames, "restir+raw"),
        "denoised = raw everywhere"
    );
}

/// `bench-map` on a folder with no bench run says so in one line, and on a missing folder
/// names it.
#[test]
fn bench_map_without_cells_fails_in_one_line() {
    let dir = std::env::temp_dir().join(format!("restir-map-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    assert_one_line_error(&viewer(&["bench-map", dir.to_str().unwrap()]), &["no cell"]);
    assert_one_line_error(
        &viewer(&["bench-map", "/nonexistent/map"]),
        &["/nonexistent/map"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `bench-plot` on a folder with no table to draw from says so in one line, and on a
/// missing folder names it.
#[test]
fn bench_plot_without_tables_fails_in_one_line() {
    let dir = std::env::temp_dir().join(format!("restir-plot-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    assert_one_line_error(
        &viewer(&["bench-plot", dir.to_str().unwrap()]),
        &["no cost_curves.csv or map.csv"],
    );
    assert_one_line_error(
        &viewer(&["bench-plot", "/nonexistent/plots"]),
        &["/nonexistent/plots"],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `bench-bvh` prints a row per scene time with the split tree (moving triangles apart,
/// `scene::bvh::split`) beside the single tree and the two-level one; the renderer's
/// `--stats` name the same moving triangles; a static scene is refused in one line.
#[test]
fn bench_bvh_measures_the_split_tree_the_renderer_builds() {
    let out = viewer(&[
        "bench-bvh",
        "--scene",
        "builtin:city-traffic:1024",
        "--times",
        "0,0.5",
        "--repeats",
        "1",
        "--rays",
        "16x10",
    ]);
    assert_success(&out);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let moving: u64 = text
        .lines()
        .find_map(|l| l.strip_prefix("split tree: "))
        .and_then(|l| l.split(" and ").nth(1)?.split(' ').next()?.parse().ok())
        .unwrap_or_else(|| panic!("no split tree line: {text}"));
    assert!(moving > 0);
    let cells = |l: &str| -> Vec<String> {
        l.trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let header = cells(text.lines().find(|l| l.starts_with("| time")).unwrap());
    let rows: Vec<Vec<String>> = text
        .lines()
        .filter(|l| l.starts_with("| 0"))
        .map(cells)
        .collect();
    assert_eq!(rows.len(), 2, "{text}");
    for row in &rows {
        assert_eq!(row.len(), header.len());
        // The split tree's nodes per ray: the 13th column, a positive count.
        assert_eq!(header[12], "split");
        let visits: f64 = row[12].parse().unwrap();
        assert!(visits > 0.0, "{row:?}");
    }
    let dir = temp_dir("bench_bvh");
    let stats = dir.join("stats.json");
    let rendered = render(
        "builtin:city-traffic:1024",
        &["--stats", stats.to_str().unwrap()],
        &dir.join("city.png"),
    );
    assert_success(&rendered);
    let doc = json_file(&stats);
    assert_eq!(doc["scene"]["bvh_moving_triangles"].as_u64(), Some(moving));
    assert_one_line_error(
        &viewer(&["bench-bvh", "--scene", "builtin:cornell"]),
        &["not an animated scene"],
    );
}
