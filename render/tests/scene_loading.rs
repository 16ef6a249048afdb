//! Scene loading end to end: the two real-world Blender exports, hand-written .glb/.gltf
//! files, every kind of bad input (each must be a clean error naming the file), the built-in
//! scenes, and a mutation fuzz of a real file (the loader must never panic).

use std::path::{Path, PathBuf};

use glam::Vec3;
use restir_render::scene::builtin::{builtin_names, builtin_scene};
use restir_render::scene::gltf_loader::load_gltf;
use restir_render::scene::load::SceneError;
use restir_render::scene::{Camera, Scene, Wrap, load_scene};
use serde_json::{Value, json};

#[path = "scene_loading/animation.rs"]
mod animation;
#[path = "scene_loading/compressed.rs"]
mod compressed;
#[path = "scene_loading/compressed_files.rs"]
mod compressed_files;
#[path = "scene_loading/compressed_render.rs"]
mod compressed_render;
#[path = "scene_loading/corrupt.rs"]
mod corrupt;
#[path = "scene_loading/extensions.rs"]
mod extensions;
#[path = "scene_loading/files.rs"]
mod files;
#[path = "scene_loading/fuzz.rs"]
mod fuzz;
#[path = "scene_loading/twins.rs"]
mod twins;

use files::{TempDir, add_texture, base64, f32_bytes, glb, quad_document, write_gltf};

fn asset(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(relative)
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Σ area × luminance(emission) over the emissive triangles.
fn emitted_power(scene: &Scene) -> f64 {
    (0..scene.triangles.len())
        .map(|t| {
            let [a, b, c] = scene.triangle_positions(t);
            let emission = scene.materials[scene.triangles[t].material as usize].emission;
            0.5 * (b - a).cross(c - a).length() as f64 * luminance(emission) as f64
        })
        .sum()
}

fn check_blender_cornell(relative: &str) {
    let path = asset(relative);
    let scene = load_scene(path.to_str().unwrap()).unwrap();
    assert!(scene.triangles.len() > 100, "{}", scene.triangles.len());
    let emissive: Vec<&str> = scene
        .materials
        .iter()
        .filter(|m| m.is_emissive())
        .map(|m| m.name.as_str())
        .collect();
    assert_eq!(emissive, ["light.000"]);
    assert!(scene.emissive_triangle_count() > 0);
    let light = scene.materials.iter().find(|m| m.is_emissive()).unwrap();
    assert_eq!(light.emission, Vec3::ONE);
    // Both checker textures decoded, with the glTF default wrap.
    let sizes: Vec<(u32, u32)> = scene.textures.iter().map(|t| (t.width, t.height)).collect();
    assert_eq!(sizes, [(1024, 1024), (256, 256)]);
    for t in &scene.textures {
        assert_eq!(t.texels.len(), (t.width * t.height) as usize);
        assert_eq!((t.wrap_u, t.wrap_v), (Wrap::Repeat, Wrap::Repeat));
        assert!(
            t.texels.iter().any(|&p| p != t.texels[0]),
            "{} is flat",
            t.name
        );
    }
    let bloc = scene
        .materials
        .iter()
        .find(|m| m.name == "bloc.000")
        .unwrap();
    assert!(bloc.base_color_texture.is_some());
    assert!(scene.camera.is_none());
    assert_eq!(scene.default_camera(), Camera::framing(scene.bounds()));
    assert!(scene.vertices.iter().all(|v| v.normal.length() > 0.99));
}

#[test]
fn blender_2_79_cornell_loads() {
    check_blender_cornell("blender-2.79-cornell/cornellBox-2.79-Cycles-gltf.gltf");
}

#[test]
fn blender_2_80_cornell_loads() {
    check_blender_cornell("blender-2.80-cornell/cornellBox-2.80-Eevee-gltf.gltf");
}

#[test]
fn glb_round_trip_with_transforms_materials_camera_and_lights() {
    let (mut doc, mut bin) = quad_document(None);
    // A second, non-indexed strip primitive without normals or material, reusing the quad's
    // positions in strip order 0,1,3,2.
    bin.extend(f32_bytes(&[
        0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0,
    ]));
    doc["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "buffer": 0, "byteOffset": 140, "byteLength": 48 }));
    doc["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "bufferView": 4, "componentType": 5126,
        "count": 4, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0] }));
    doc["buffers"][0]["byteLength"] = json!(bin.len());
    doc["meshes"][0]["primitives"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "attributes": { "POSITION": 4 }, "mode": 5 }));
    doc["materials"][0] = json!({
        "name": "glow", "emissiveFactor": [1.0, 0.5, 0.25], "doubleSided": true,
        "alphaMode": "MASK", "alphaCutoff": 0.3,
        "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.3, 0.4, 1.0], "metallicFactor": 0.1, "roughnessFactor": 0.6 },
        "extensions": { "KHR_materials_emissive_strength": { "emissiveStrength": 4.0 },
                        "KHR_materials_specular": { "specularFactor": 0.5 } }
    });
    doc["extensionsUsed"] = json!([
        "KHR_materials_emissive_strength",
        "KHR_materials_specular",
        "KHR_lights_punctual"
    ]);
    doc["extensionsRequired"] = json!(["KHR_materials_specular"]);
    doc["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "spot", "color": [1.0, 0.5, 0.5], "intensity": 20.0, "range": 7.0,
          "spot": { "innerConeAngle": 0.2, "outerConeAngle": 0.5 } } ] } });
    doc["cameras"] =
        json!([{ "type": "perspective", "perspective": { "yfov": 0.7, "znear": 0.1 } }]);
    // Root mirrors x and moves up 2; its children: the camera (scaled, which must be
    // dropped), then the light.
    doc["nodes"] = json!([
        { "mesh": 0, "translation": [0.0, 2.0, 0.0], "scale": [-1.0, 1.0, 1.0], "children": [1, 2] },
        { "camera": 0, "translation": [0.0, 0.0, 5.0], "scale": [3.0, 3.0, 3.0] },
        { "translation": [0.0, 1.0, 0.0], "rotation": [-0.70710677, 0.0, 0.0, 0.70710677],
          "extensions": { "KHR_lights_punctual": { "light": 0 } } }
    ]);
    let dir = TempDir::new("glb");
    let path = dir.join("round-trip.glb");
    std::fs::write(&path, glb(&doc, &bin)).unwrap();
    let scene = load_gltf(&path).unwrap();

    assert_eq!(scene.name, "round-trip.glb");
    assert_eq!(scene.triangles.len(), 4);
    assert_eq!(
        scene.materials.len(),
        2,
        "the strip gets a default material"
    );
    let glow = &scene.materials[0];
    assert_eq!(glow.emission, Vec3::new(4.0, 2.0, 1.0));
    assert_eq!(glow.specular, 0.5);
    assert!(glow.double_sided);
    assert_eq!(glow.alpha_mode, restir_render::scene::AlphaMode::Mask(0.3));
    assert_eq!((glow.metallic, glow.roughness), (0.1, 0.6));
    assert_eq!(scene.materials[1].specular, 1.0);
    // World positions are mirrored and lifted; every triangle still faces +z (the mirror
    // flipped the winding back) and the normals point that way too.
    for t in 0..4 {
        let [a, b, c] = scene.triangle_positions(t);
        assert!((b - a).cross(c - a).z > 0.0, "triangle {t}");
        assert!(a.x <= 0.0 && a.y >= 2.0);
    }
    assert!(scene.vertices[..4].iter().all(|v| v.normal == Vec3::Z));
    assert!(scene.vertices[4..].iter().all(|v| v.normal == Vec3::ZERO));
    let camera = scene.camera.unwrap();
    assert!(camera.position.abs_diff_eq(Vec3::new(0.0, 2.0, 5.0), 1e-6));
    assert_eq!(camera.yfov, 0.7);
    assert!((camera.rotation.length() - 1.0).abs() < 1e-5);
    let light = scene.punctual_lights[0];
    assert!(light.position.abs_diff_eq(Vec3::new(0.0, 3.0, 0.0), 1e-6));
    assert!(
        light.direction.abs_diff_eq(Vec3::NEG_Y, 1e-5),
        "{}",
        light.direction
    );
    assert_eq!(light.intensity, Vec3::new(20.0, 10.0, 10.0));
    assert_eq!(light.range, Some(7.0));
}

#[test]
fn gltf_with_external_and_embedded_buffers_load() {
    let dir = TempDir::new("buffers");
    let (doc, bin) = quad_document(Some("external.bin"));
    let external = load_gltf(&write_gltf(&dir, "external", &doc, &bin)).unwrap();
    let uri = format!("data:application/octet-stream;base64,{}", base64(&bin));
    let (doc, _) = quad_document(Some(&uri));
    let embedded = load_gltf(&write_gltf(&dir, "embedded", &doc, &[])).unwrap();
    assert_eq!(external.triangles.len(), 2);
    assert_eq!(external.vertices, embedded.vertices);
    assert_eq!(external.triangles, embedded.triangles);
}

/// Each broken variant of the quad file must fail with a message naming the file.
#[test]
fn bad_inputs_are_clean_errors_naming_the_file() {
    let dir = TempDir::new("bad");
    type Edit = fn(&mut Value, &mut Vec<u8>);
    let cases: &[(&str, Edit, &str)] = &[
        (
            "missing-bin",
            |d, _| d["buffers"][0]["uri"] = json!("nowhere.bin"),
            "cannot read buffer 0",
        ),
        ("short-bin", |_, b| b.truncate(100), "bytes but accessor"),
        (
            "accessor-ref",
            |d, _| d["meshes"][0]["primitives"][0]["indices"] = json!(9),
            "not valid glTF",
        ),
        (
            "index-range",
            |_, b| b[128..130].copy_from_slice(&40u16.to_le_bytes()),
            "index 40 is out of range",
        ),
        (
            "nan-position",
            |_, b| b[4..8].copy_from_slice(&f32::NAN.to_le_bytes()),
            "non-finite position",
        ),
        (
            "inf-position",
            |_, b| b[0..4].copy_from_slice(&f32::INFINITY.to_le_bytes()),
            "mesh 0 ('quad') primitive 0",
        ),
        (
            "points",
            |d, _| d["meshes"][0]["primitives"][0]["mode"] = json!(0),
            "Points",
        ),
        (
            "lines",
            |d, _| d["meshes"][0]["primitives"][0]["mode"] = json!(1),
            "Lines",
        ),
        (
            "required-ext",
            |d, _| d["extensionsRequired"] = json!(["EXT_unknown_compression"]),
            "uses EXT_unknown_compression",
        ),
        (
            "draco-stream",
            |d, _| {
                d["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
                d["meshes"][0]["primitives"][0]["extensions"] = json!({
                    "KHR_draco_mesh_compression": { "bufferView": 3, "attributes": { "POSITION": 0 } }
                });
            },
            "KHR_draco_mesh_compression (bufferView 3): the stream does not decode",
        ),
        (
            "no-triangles",
            |d, _| d["scenes"][0]["nodes"] = json!([]),
            "0 triangles",
        ),
        (
            "count-zero",
            |d, _| d["accessors"][3]["count"] = json!(0),
            "count 0",
        ),
        (
            "stride",
            |d, _| d["bufferViews"][0]["byteStride"] = json!(4),
            "byteStride",
        ),
        (
            "wrong-type",
            |d, _| d["accessors"][0]["type"] = json!("VEC2"),
            "expected Vec3",
        ),
        (
            "cycle",
            |d, _| d["nodes"][0]["children"] = json!([0]),
            "reached twice",
        ),
        (
            "missing-image",
            |d, _| add_texture(d, "nope.png"),
            "nope.png",
        ),
        (
            "corrupt-image",
            |d, _| add_texture(d, "corrupt-image.bin"),
            "image 0",
        ),
    ];
    for (name, edit, expected) in cases {
        let (mut doc, mut bin) = quad_document(Some(&format!("{name}.bin")));
        edit(&mut doc, &mut bin);
        let path = write_gltf(&dir, name, &doc, &bin);
        let message = load_gltf(&path).expect_err(name).to_string();
        assert!(
            message.contains(&format!("{name}.gltf")),
            "{name}: {message}"
        );
        assert!(message.contains(expected), "{name}: {message}");
        assert!(!message.contains('\n'), "{name}: {message}");
        assert_eq!(
            load_scene(path.to_str().unwrap()).unwrap_err().to_string(),
            message
        );
    }
    for (file, bytes) in [
        ("malformed.gltf", &b"{ \"asset\": "[..]),
        ("truncated.glb", &b"glTF\x02\0\0\0"[..]),
    ] {
        let path = dir.join(file);
        std::fs::write(&path, bytes).unwrap();
        let error = load_gltf(&path).unwrap_err();
        assert!(matches!(error, SceneError::Parse { .. }), "{error}");
        assert!(
            error.to_string().starts_with(path.to_str().unwrap()),
            "{error}"
        );
    }
    let error = load_scene("no/such/scene.gltf").unwrap_err().to_string();
    assert!(
        error.starts_with("no/such/scene.gltf: cannot read"),
        "{error}"
    );
    let error = load_scene("scene.obj").unwrap_err().to_string();
    assert!(error.starts_with("scene.obj: unsupported"), "{error}");
}

#[test]
fn every_builtin_scene_loads() {
    for name in builtin_names() {
        let scene = load_scene(&name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.name, name);
        assert!(scene.camera.is_some(), "{name} has no camera");
    }
}

#[test]
fn many_lights_keeps_total_power_for_every_count() {
    let reference = emitted_power(&builtin_scene("many-lights").unwrap());
    for n in [1usize, 3, 64, 4096, 50_000] {
        let scene = builtin_scene(&format!("many-lights:{n}")).unwrap();
        assert_eq!(scene.emissive_triangle_count(), 2 * n);
        let power = emitted_power(&scene);
        assert!(
            (power / reference - 1.0).abs() < 1e-3,
            "N={n}: {power} vs {reference}"
        );
    }
}

#[test]
fn a_million_lights_build_quickly() {
    let start = std::time::Instant::now();
    let scene = builtin_scene("many-lights:1048576").unwrap();
    let elapsed = start.elapsed();
    assert_eq!(scene.emissive_triangle_count(), 2 * 1_048_576);
    // Generous: the release build takes a small fraction of this; this catches O(N²) or
    // per-light allocation regressions even in the dev profile.
    assert!(elapsed.as_secs_f32() < 5.0, "{elapsed:?}");
}
