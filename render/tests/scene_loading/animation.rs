//! glTF animations end to end: node TRS channels through a parent chain, and
//! KHR_animation_pointer channels (which the gltf crate cannot parse) on material emission
//! and punctual lights, in .gltf and .glb containers, plus broken animation data.

use glam::Vec3;
use restir_render::scene::animation::ClipChoice;
use restir_render::scene::gltf_loader::load_gltf;
use serde_json::{Value, json};

use super::files::{TempDir, f32_bytes, glb, quad_document, write_gltf};

/// The quad on a child node 1 m above a parent that slides +x 2 m over 2 s (LINEAR), one
/// animation switching the material's emissiveFactor on at 1 s (STEP, pointer) with
/// emissiveStrength 2, and a point light whose intensity ramps 0 → 10 (LINEAR, pointer).
fn animated_document() -> (Value, Vec<u8>) {
    let (mut doc, mut bin) = quad_document(Some("anim.bin"));
    let base = bin.len();
    let mut push = |values: &[f32]| {
        let offset = bin.len();
        bin.extend(f32_bytes(values));
        offset
    };
    let views = [
        (push(&[0.0, 2.0]), 8),
        (push(&[0.0, 0.0, 0.0, 2.0, 0.0, 0.0]), 24),
        (push(&[0.0, 1.0]), 8),
        (push(&[0.0, 0.0, 0.0, 1.0, 0.5, 0.25]), 24),
        (push(&[0.0, 10.0]), 8),
    ];
    assert_eq!(views[0].0, base);
    doc["buffers"][0]["byteLength"] = json!(bin.len());
    let first_view = doc["bufferViews"].as_array().unwrap().len();
    for (offset, length) in views {
        doc["bufferViews"]
            .as_array_mut()
            .unwrap()
            .push(json!({ "buffer": 0, "byteOffset": offset, "byteLength": length }));
    }
    let first_accessor = doc["accessors"].as_array().unwrap().len();
    let kinds = ["SCALAR", "VEC3", "SCALAR", "VEC3", "SCALAR"];
    for (i, kind) in kinds.iter().enumerate() {
        let count = 2;
        doc["accessors"].as_array_mut().unwrap().push(json!({
            "bufferView": first_view + i, "componentType": 5126, "count": count, "type": kind
        }));
    }
    let a = |i: usize| first_accessor + i;
    doc["nodes"] = json!([
        { "children": [1] },
        { "mesh": 0, "translation": [0.0, 1.0, 0.0] },
        { "translation": [0.0, 3.0, 0.0],
          "extensions": { "KHR_lights_punctual": { "light": 0 } } }
    ]);
    doc["scenes"] = json!([{ "nodes": [0, 2] }]);
    doc["extensionsUsed"] = json!([
        "KHR_animation_pointer",
        "KHR_materials_emissive_strength",
        "KHR_lights_punctual"
    ]);
    doc["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "point", "color": [1.0, 1.0, 1.0], "intensity": 0.0 }
    ]}});
    doc["materials"][0]["extensions"] =
        json!({ "KHR_materials_emissive_strength": { "emissiveStrength": 2.0 } });
    let pointer = |p: &str| json!({ "path": "pointer", "extensions": { "KHR_animation_pointer": { "pointer": p } } });
    doc["animations"] = json!([
        { "name": "slide",
          "samplers": [{ "input": a(0), "output": a(1), "interpolation": "LINEAR" }],
          "channels": [{ "sampler": 0, "target": { "node": 0, "path": "translation" } }] },
        { "name": "lights",
          "samplers": [
              { "input": a(2), "output": a(3), "interpolation": "STEP" },
              { "input": a(0), "output": a(4), "interpolation": "LINEAR" }],
          "channels": [
              { "sampler": 0, "target": pointer("/materials/0/emissiveFactor") },
              { "sampler": 1,
                "target": pointer("/extensions/KHR_lights_punctual/lights/0/intensity") }] }
    ]);
    (doc, bin)
}

fn check_animated(path: &std::path::Path) {
    let mut scene = load_gltf(path).unwrap();
    let anim = scene.animation.clone().expect("the file has animations");
    assert_eq!(anim.clips.len(), 2);
    assert_eq!(anim.duration(ClipChoice::All), 2.0);
    assert_eq!(anim.light_events(ClipChoice::All), vec![1.0]);
    // Rest pose as loaded: the quad's (1,0,0) corner sits at (1,1,0), the emission is off.
    assert_eq!(scene.vertices[1].position, Vec3::new(1.0, 1.0, 0.0));
    assert!(!scene.materials[0].is_emissive());
    // The moving mesh's placement (the ray-query backend's instance transform) is recorded
    // with the vertices: as loaded, and after a pose.
    let placed_where_posed = |scene: &restir_render::Scene| {
        let mesh = &anim.meshes[0];
        let m = scene.mesh_transforms[0];
        mesh.local.iter().enumerate().all(|(i, v)| {
            (m.transform_point3(v.position) - scene.vertices[mesh.first as usize + i].position)
                .length()
                < 1e-5
        })
    };
    assert!(placed_where_posed(&scene), "as loaded");
    let change = anim.pose(&mut scene, 1.5, ClipChoice::All);
    assert!(placed_where_posed(&scene), "after a pose");
    assert!(change.geometry && change.lights);
    // Parent at x = 1.5 (LINEAR 0 → 2 over 2 s), child 1 m up.
    let corner = scene.vertices[1].position;
    assert!(
        (corner - Vec3::new(2.5, 1.0, 0.0)).length() < 1e-5,
        "{corner}"
    );
    // emissiveFactor (1, 0.5, 0.25) × emissiveStrength 2.
    assert_eq!(scene.materials[0].emission, Vec3::new(2.0, 1.0, 0.5));
    // Intensity 7.5 at 1.5 s, times the white colour.
    let light = scene.punctual_lights[0];
    assert!(
        (light.intensity - Vec3::splat(7.5)).length() < 1e-4,
        "{light:?}"
    );
    assert_eq!(light.position, Vec3::new(0.0, 3.0, 0.0));
    // Only the chosen clip plays: the slide alone leaves the light dark.
    anim.pose(&mut scene, 1.5, ClipChoice::One(0));
    assert!(!scene.materials[0].is_emissive());
}

#[test]
fn gltf_animations_and_pointer_channels_load_and_play() {
    let dir = TempDir::new("animation");
    let (doc, bin) = animated_document();
    check_animated(&write_gltf(&dir, "anim", &doc, &bin));
    let mut glb_doc = doc.clone();
    glb_doc["buffers"][0].as_object_mut().unwrap().remove("uri");
    let path = dir.join("anim.glb");
    std::fs::write(&path, glb(&glb_doc, &bin)).unwrap();
    check_animated(&path);
}

#[test]
fn broken_animation_data_is_a_clear_error() {
    let dir = TempDir::new("animation-broken");
    let (doc, mut bin) = animated_document();
    // Key times of the slide become (0, NaN).
    let times = doc["bufferViews"][4]["byteOffset"].as_u64().unwrap() as usize;
    bin[times + 4..times + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = load_gltf(&write_gltf(&dir, "anim", &doc, &bin))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("animations[0].channels[0]") && e.contains("not finite"),
        "{e}"
    );
    // Equal key times.
    bin[times + 4..times + 8].copy_from_slice(&0f32.to_le_bytes());
    let e = load_gltf(&write_gltf(&dir, "anim", &doc, &bin))
        .unwrap_err()
        .to_string();
    assert!(e.contains("strictly increasing"), "{e}");
    // A channel with no node and no pointer.
    let (mut doc, bin) = animated_document();
    doc["animations"][1]["channels"][0]["target"] = json!({ "path": "pointer" });
    let e = load_gltf(&write_gltf(&dir, "anim", &doc, &bin))
        .unwrap_err()
        .to_string();
    assert!(e.contains("KHR_animation_pointer"), "{e}");
    // A pointer to a material that does not exist.
    let (mut doc, bin) = animated_document();
    doc["animations"][1]["channels"][0]["target"]["extensions"]["KHR_animation_pointer"]["pointer"] =
        json!("/materials/9/emissiveFactor");
    let e = load_gltf(&write_gltf(&dir, "anim", &doc, &bin))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no material 9"), "{e}");
}
