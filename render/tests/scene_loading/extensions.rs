//! The glTF extensions (docs/src/scenes.md, "glTF extensions"), end to end: KHR_texture_transform
//! through the real GPU path, KHR_mesh_quantization's dequantized vertices, the compression
//! extensions accepted (and an unknown required one refused), and the per-scene extension report.

use glam::{Quat, Vec2, Vec3};
use restir_render::scene::gltf_loader::load_gltf;
use restir_render::scene::{ExtensionStatus, Scene};
use restir_render::{Camera, Gpu, Mode, Renderer, Settings};
use serde_json::{Value, json};

use super::files::{TempDir, quad_document, write_gltf};

/// A 2×2 PNG: red, green (top row), blue, white (bottom row), clamped nowhere (repeat).
fn write_checker(dir: &std::path::Path) {
    let texels = [
        [255, 0, 0, 255],
        [0, 255, 0, 255],
        [0, 0, 255, 255],
        [255; 4],
    ];
    let image = image::RgbaImage::from_fn(2, 2, |x, y| image::Rgba(texels[(y * 2 + x) as usize]));
    image.save(dir.join("checker.png")).unwrap();
}

const RED: [f32; 3] = [1.0, 0.0, 0.0];
const GREEN: [f32; 3] = [0.0, 1.0, 0.0];
const BLUE: [f32; 3] = [0.0, 0.0, 1.0];
const WHITE: [f32; 3] = [1.0, 1.0, 1.0];

/// The unit quad as a black emitter whose emissive texture is the checker, read through
/// `transform` (a KHR_texture_transform object) when given.
fn emissive_quad(name: &str, transform: Option<Value>) -> (Value, Vec<u8>) {
    let (mut doc, bin) = quad_document(Some(&format!("{name}.bin")));
    doc["images"] = json!([{ "uri": "checker.png" }]);
    doc["samplers"] = json!([{ "magFilter": 9728, "minFilter": 9728 }]);
    doc["textures"] = json!([{ "source": 0, "sampler": 0 }]);
    let mut info = json!({ "index": 0 });
    if let Some(t) = transform {
        info["extensions"] = json!({ "KHR_texture_transform": t });
        doc["extensionsUsed"] = json!(["KHR_texture_transform"]);
    }
    doc["materials"][0] = json!({
        "name": "screen",
        "emissiveFactor": [1.0, 1.0, 1.0],
        "emissiveTexture": info,
        "pbrMetallicRoughness": { "baseColorFactor": [0.0, 0.0, 0.0, 1.0] }
    });
    (doc, bin)
}

/// Renders the quad face-on, filling a 10×10 image exactly (camera at (0.5, 0.5, 2) looking
/// down −Z, yfov = 2·atan(1/4)), so pixel (2, 7) sees uv (0.25, 0.25) — a texel centre —
/// and pixel (7, 7) uv (0.75, 0.25), (2, 2) uv (0.25, 0.75), (7, 2) uv (0.75, 0.75).
/// Returns those four pixels' radiance in that order.
fn render_quadrants(scene: &Scene, planted: &[&str]) -> [[f32; 3]; 4] {
    let gpu = Gpu::new_headless().unwrap_or_else(|e| panic!("GPU tests need a wgpu adapter: {e}"));
    let mut settings = Settings::default();
    settings.apply_assignments(["jitter=false"]).unwrap();
    let mut r = Renderer::new(gpu, scene, 10, 10, settings).unwrap_or_else(|e| panic!("{e:#}"));
    r.plant_for_tests(planted);
    r.set_mode(Mode::Nee);
    r.set_camera(Camera {
        position: Vec3::new(0.5, 0.5, 2.0),
        rotation: Quat::IDENTITY,
        yfov: 2.0 * 0.25f32.atan(),
    });
    r.reset_accumulation();
    for _ in 0..2 {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
    }
    let img = r.read_accumulated();
    [(2, 7), (7, 7), (2, 2), (7, 2)].map(|(x, y)| img.rgb(x, y))
}

fn assert_colours(what: &str, got: [[f32; 3]; 4], expected: [[f32; 3]; 4]) {
    for (g, e) in got.iter().zip(&expected) {
        let close = g.iter().zip(e).all(|(a, b)| (a - b).abs() < 2e-3);
        assert!(close, "{what}: got {got:?}, expected {expected:?}");
    }
}

#[test]
fn texture_transform_moves_the_sampled_texels_on_the_gpu() {
    let dir = TempDir::new("texture-transform");
    write_checker(&dir);
    // Untransformed: each quadrant shows its own texel.
    let (doc, bin) = emissive_quad("plain", None);
    let plain = load_gltf(&write_gltf(&dir, "plain", &doc, &bin)).unwrap();
    let identity = [RED, GREEN, BLUE, WHITE];
    assert_colours("no transform", render_quadrants(&plain, &[]), identity);

    // Rotation π/2 then offset (0.5, 0), repeat wrap, by hand with u' = cos·u + sin·v + 0.5,
    // v' = −sin·u + cos·v: (¼,¼) → (¾,−¼ ≡ ¾) white, (¾,¼) → (¾,−¾ ≡ ¼) green,
    // (¼,¾) → (1¼ ≡ ¼, ¾) blue, (¾,¾) → (1¼ ≡ ¼, ¼) red.
    let transform = json!({ "offset": [0.5, 0.0], "rotation": std::f64::consts::FRAC_PI_2 });
    let (doc, bin) = emissive_quad("turned", Some(transform));
    let turned = load_gltf(&write_gltf(&dir, "turned", &doc, &bin)).unwrap();
    assert_eq!(turned.textures.len(), 1, "one image, one scene texture");
    let expected = [WHITE, GREEN, BLUE, RED];
    assert_colours(
        "rotation + offset",
        render_quadrants(&turned, &[]),
        expected,
    );
    // Planted twin: the shader ignoring the transform shows the untransformed texels.
    let ignored = render_quadrants(&turned, &["PLANTED_NO_UV_TRANSFORM"]);
    assert_colours("planted: transform ignored", ignored, identity);
    assert!(
        (ignored[0][1] - 1.0).abs() > 0.5,
        "the twin must differ: {ignored:?}"
    );
}

#[test]
fn texture_transform_and_texcoord_override_reach_the_material() {
    let dir = TempDir::new("texture-transform-cpu");
    write_checker(&dir);
    let t = json!({ "offset": [0.5, 0.25], "rotation": 0.0, "scale": [2.0, 3.0], "texCoord": 0 });
    let (doc, bin) = emissive_quad("cpu", Some(t));
    let scene = load_gltf(&write_gltf(&dir, "cpu", &doc, &bin)).unwrap();
    let r = scene.materials[0].emissive_texture.unwrap();
    assert_eq!(r.transform.apply(Vec2::new(0.5, 0.5)), Vec2::new(1.5, 1.75));
    // A non-finite transform (1e39 overflows f32) falls back to none instead of failing.
    let (doc, bin) = emissive_quad("huge", Some(json!({ "offset": [1e39, 0.0] })));
    let scene = load_gltf(&write_gltf(&dir, "huge", &doc, &bin)).unwrap();
    assert!(
        scene.materials[0]
            .emissive_texture
            .unwrap()
            .transform
            .is_identity()
    );
}

/// The quad with `KHR_mesh_quantization` attributes appended to its buffer: i16 normalized
/// positions, i8 normalized normals, TEXCOORD_0 float (garbage) and TEXCOORD_1 u8
/// normalized, the material's texture reading TEXCOORD_1 through the transform's override;
/// the node scales by (2, 4, 1) (the dequantization matrix lives in the node).
fn quantized_quad(name: &str) -> (Value, Vec<u8>) {
    let (mut doc, mut bin) = quad_document(Some(&format!("{name}.bin")));
    let push_view = |doc: &mut Value, bin: &mut Vec<u8>, bytes: Vec<u8>| -> usize {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let views = doc["bufferViews"].as_array_mut().unwrap();
        views.push(json!({ "buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len() }));
        bin.extend(bytes);
        views.len() - 1
    };
    // Positions (x, y, z) as i16 with a 2-byte pad per element (4-byte aligned stride 8).
    let positions: [[i16; 3]; 4] = [
        [0, 0, 0],
        [32767, 0, -32767],
        [16384, 32767, 0],
        [-32768, 16384, 0],
    ];
    let pos_bytes: Vec<u8> = positions
        .iter()
        .flat_map(|p| p.iter().flat_map(|c| c.to_le_bytes()).chain([0, 0]))
        .collect();
    let pos_view = push_view(&mut doc, &mut bin, pos_bytes);
    doc["bufferViews"][pos_view]["byteStride"] = json!(8);
    let normals: [[i8; 3]; 4] = [[0, 0, 127], [0, 0, 127], [127, 0, 0], [-128, 0, 0]];
    let normal_view = push_view(
        &mut doc,
        &mut bin,
        normals
            .iter()
            .flat_map(|n| n.iter().map(|&c| c as u8).chain([0]))
            .collect(),
    );
    doc["bufferViews"][normal_view]["byteStride"] = json!(4);
    let uvs: [[u8; 2]; 4] = [[0, 0], [255, 0], [255, 51], [0, 255]];
    let uv_view = push_view(&mut doc, &mut bin, uvs.iter().flatten().copied().collect());
    let accessors = doc["accessors"].as_array_mut().unwrap();
    accessors.push(
        json!({ "bufferView": pos_view, "componentType": 5122, "normalized": true,
        "count": 4, "type": "VEC3", "min": [-32768, 0, -32767], "max": [32767, 32767, 0] }),
    );
    accessors.push(
        json!({ "bufferView": normal_view, "componentType": 5120, "normalized": true,
        "count": 4, "type": "VEC3" }),
    );
    accessors.push(
        json!({ "bufferView": uv_view, "componentType": 5121, "normalized": true,
        "count": 4, "type": "VEC2" }),
    );
    doc["meshes"][0]["primitives"][0]["attributes"] =
        json!({ "POSITION": 4, "NORMAL": 5, "TEXCOORD_0": 2, "TEXCOORD_1": 6 });
    doc["nodes"][0]["scale"] = json!([2.0, 4.0, 1.0]);
    doc["buffers"][0]["byteLength"] = json!(bin.len());
    doc["extensionsUsed"] = json!(["KHR_mesh_quantization", "KHR_texture_transform"]);
    doc["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
    doc["images"] = json!([{ "uri": "checker.png" }]);
    doc["textures"] = json!([{ "source": 0 }]);
    doc["materials"][0]["pbrMetallicRoughness"] = json!({ "baseColorTexture": { "index": 0,
        "extensions": { "KHR_texture_transform": { "texCoord": 1 } } } });
    (doc, bin)
}

/// The glTF rule for normalized integers, or the integer itself.
fn dequantize(c: f32, max: f32, normalized: bool) -> f32 {
    if normalized { (c / max).max(-1.0) } else { c }
}

#[test]
fn quantized_attributes_are_dequantized_then_transformed() {
    let dir = TempDir::new("quantized");
    write_checker(&dir);
    let (doc, bin) = quantized_quad("q");
    let scene = load_gltf(&write_gltf(&dir, "q", &doc, &bin)).unwrap();
    let expected_position = |p: [f32; 3], normalized: bool| {
        Vec3::from_array(p.map(|c| dequantize(c, 32767.0, normalized))) * Vec3::new(2.0, 4.0, 1.0)
    };
    let raw_positions = [
        [0.0, 0.0, 0.0],
        [32767.0, 0.0, -32767.0],
        [16384.0, 32767.0, 0.0],
        [-32768.0, 16384.0, 0.0],
    ];
    // Hand-computed: (16384/32767·2, 4, 0) and (max(−32768/32767, −1)·2, 16384/32767·4, 0).
    assert!((scene.vertices[2].position - Vec3::new(1.000_031, 4.0, 0.0)).length() < 1e-5);
    assert!((scene.vertices[3].position - Vec3::new(-2.0, 2.000_061, 0.0)).length() < 1e-5);
    for (v, raw) in scene.vertices.iter().zip(raw_positions) {
        assert!(
            (v.position - expected_position(raw, true)).length() < 1e-5,
            "{v:?}"
        );
        // Planted twin: the integers taken as they are (normalization skipped) do not match.
        if raw != [0.0; 3] {
            assert!((v.position - expected_position(raw, false)).length() > 1.0);
        }
    }
    // Normals: i8 normalized, then the inverse transpose of the scale, renormalised.
    assert!((scene.vertices[0].normal - Vec3::Z).length() < 1e-6);
    assert!((scene.vertices[2].normal - Vec3::X).length() < 1e-6);
    assert!(
        (scene.vertices[3].normal + Vec3::X).length() < 1e-6,
        "{:?}",
        scene.vertices[3]
    );
    // uvs: TEXCOORD_1 (the override), u8 normalized: 51/255 = 0.2.
    let uvs: Vec<Vec2> = scene.vertices.iter().map(|v| v.uv).collect();
    assert_eq!(uvs, [Vec2::ZERO, Vec2::X, Vec2::new(1.0, 0.2), Vec2::Y]);
    assert_eq!(scene.materials[0].uv_set(), 1);
    // Slots that disagree: the base colour slot's set wins (the loader warns).
    let (mut doc, bin) = quantized_quad("q2");
    doc["materials"][0]["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
    doc["materials"][0]["emissiveTexture"] = json!({ "index": 0, "texCoord": 0 });
    let mixed = load_gltf(&write_gltf(&dir, "q2", &doc, &bin)).unwrap();
    assert_eq!(mixed.materials[0].emissive_texture.unwrap().tex_coord, 0);
    assert_eq!(mixed.materials[0].uv_set(), 1);
    assert_eq!(mixed.vertices[2].uv, Vec2::new(1.0, 0.2));
    // The report: both extensions used; quantization was required and is accepted.
    let report: Vec<String> = scene.extensions.iter().map(|e| e.to_string()).collect();
    assert_eq!(
        report,
        [
            "KHR_mesh_quantization (required): used",
            "KHR_texture_transform: used"
        ]
    );
}

#[test]
fn bad_quantized_accessors_are_clean_errors() {
    let dir = TempDir::new("quantized-bad");
    write_checker(&dir);
    type Edit = fn(&mut Value);
    let cases: &[(&str, Edit, &str)] = &[
        (
            "u32-positions",
            |d| d["accessors"][4]["componentType"] = json!(5125),
            "expected Vec3",
        ),
        (
            "u8-normals",
            |d| d["accessors"][5]["componentType"] = json!(5121),
            "NORMAL",
        ),
        (
            "raw-normals",
            |d| d["accessors"][5]["normalized"] = json!(false),
            "not normalized",
        ),
        (
            "vec3-uvs",
            |d| d["accessors"][6]["type"] = json!("VEC3"),
            "TEXCOORD_1",
        ),
    ];
    for (name, edit, expected) in cases {
        let (mut doc, bin) = quantized_quad(name);
        edit(&mut doc);
        let message = load_gltf(&write_gltf(&dir, name, &doc, &bin))
            .expect_err(name)
            .to_string();
        assert!(message.contains(expected), "{name}: {message}");
        assert!(
            message.contains(&format!("{name}.gltf")) && !message.contains('\n'),
            "{message}"
        );
    }
}

/// The compression extensions are decoded (scene_loading/compressed.rs): a file may list or
/// require them and load; one requiring a compression this build does not know is refused in
/// one line naming it.
#[test]
fn compression_extensions_load_when_required_and_an_unknown_one_is_refused() {
    let dir = TempDir::new("compression");
    for ext in [
        "KHR_draco_mesh_compression",
        "EXT_meshopt_compression",
        "KHR_texture_basisu",
        "EXT_texture_webp",
    ] {
        // Listed and required, with no compressed data: nothing to decode, it loads.
        let (mut doc, bin) = quad_document(Some(&format!("{ext}.bin")));
        doc["extensionsUsed"] = json!([ext]);
        doc["extensionsRequired"] = json!([ext]);
        let scene = load_gltf(&write_gltf(&dir, ext, &doc, &bin)).unwrap();
        assert_eq!(scene.triangles.len(), 2);
        let e = &scene.extensions[0];
        assert!(
            matches!(
                &e.status,
                ExtensionStatus::Used | ExtensionStatus::PartlyUsed(_)
            ),
            "{e}"
        );
    }
    let (mut doc, bin) = quad_document(Some("unknown.bin"));
    doc["extensionsUsed"] = json!(["EXT_unknown_compression"]);
    doc["extensionsRequired"] = json!(["EXT_unknown_compression"]);
    let message = load_gltf(&write_gltf(&dir, "unknown", &doc, &bin))
        .unwrap_err()
        .to_string();
    assert!(message.contains("unknown.gltf"), "{message}");
    assert!(
        message.contains("uses EXT_unknown_compression (not implemented"),
        "{message}"
    );
    assert!(!message.contains('\n'), "{message}");
}

#[test]
fn the_report_lists_every_extension_of_the_file() {
    let dir = TempDir::new("report");
    let (mut doc, bin) = quad_document(Some("report.bin"));
    doc["extensionsUsed"] = json!([
        "KHR_materials_volume",
        "KHR_materials_specular",
        "EXT_unknown_thing",
        "KHR_lights_punctual"
    ]);
    let scene = load_gltf(&write_gltf(&dir, "report", &doc, &bin)).unwrap();
    let report: Vec<String> = scene.extensions.iter().map(|e| e.to_string()).collect();
    assert_eq!(
        report,
        [
            "KHR_materials_volume: partly used — thickness and attenuation ignored (thin-walled)",
            "KHR_materials_specular: partly used — specularTexture, specularColorFactor and specularColorTexture ignored",
            "EXT_unknown_thing: ignored",
            "KHR_lights_punctual: used",
        ]
    );
    // Required and unknown: refused in one line.
    doc["extensionsRequired"] = json!(["EXT_unknown_thing"]);
    let message = load_gltf(&write_gltf(&dir, "report", &doc, &bin))
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("uses EXT_unknown_thing (not implemented"),
        "{message}"
    );
}
