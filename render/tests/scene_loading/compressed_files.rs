//! Compressed test files: the shipped twins of the Cornell box (assets/compressed, made by
//! gltf-transform, see its README), one small piece of them to corrupt, and a meshopt quad
//! encoded here with meshoptimizer-rs (every EXT mode, the EXPONENTIAL and OCTAHEDRAL
//! filters, a fallback buffer in a GLB).

use std::path::{Path, PathBuf};

use meshoptimizer_rs::Workspace;
use meshoptimizer_rs::codec::{
    ExpMode, IndexEncoding, VertexEncoding, encode_filter_exp, encode_filter_oct,
    encode_index_buffer, encode_index_sequence, encode_vertex_buffer,
};
use serde_json::{Value, json};

use super::asset;
use super::files::{f32_bytes, glb, quad_document};

pub const PLAIN: &str = "blender-2.79-cornell/cornellBox-2.79-Cycles-gltf.gltf";
pub const DRACO: &str = "compressed/cornell-draco.gltf";
pub const MESHOPT: &str = "compressed/cornell-meshopt.gltf";

pub fn read_json(path: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

/// Image URIs of a shipped twin made absolute, so the document can be written elsewhere.
pub fn absolute_image_uris(doc: &mut Value, relative_to: &Path) {
    for image in doc["images"].as_array_mut().into_iter().flatten() {
        if let Some(uri) = image["uri"].as_str() {
            let path = relative_to.parent().unwrap().join(uri);
            image["uri"] = json!(path.canonicalize().unwrap().to_str().unwrap());
        }
    }
}

/// The Draco twin cut down to its lamp (mesh 2, one 282-byte Draco stream, node 12) with
/// its textures removed: cheap to load hundreds of times. Returns the document, its buffer
/// and the byte range of the lamp's stream in it.
pub fn draco_lamp() -> (Value, Vec<u8>, std::ops::Range<usize>) {
    let path = asset(DRACO);
    let mut doc = read_json(&path);
    let bin = std::fs::read(path.with_extension("bin")).unwrap();
    doc["scenes"] = json!([{ "nodes": [12] }]);
    for key in ["textures", "images", "samplers"] {
        doc.as_object_mut().unwrap().remove(key);
    }
    for m in doc["materials"].as_array_mut().unwrap() {
        m["pbrMetallicRoughness"]
            .as_object_mut()
            .map(|p| p.remove("baseColorTexture"));
    }
    let view = &doc["bufferViews"][4];
    let start = view["byteOffset"].as_u64().unwrap() as usize;
    let end = start + view["byteLength"].as_u64().unwrap() as usize;
    (doc, bin, start..end)
}

/// Write `doc` as `name`.gltf with its one buffer beside it as `name`.bin.
pub fn write_with_buffer(dir: &Path, name: &str, doc: &Value, bin: &[u8]) -> PathBuf {
    let mut doc = doc.clone();
    doc["buffers"][0]["uri"] = json!(format!("{name}.bin"));
    super::files::write_gltf(dir, name, &doc, bin)
}

/// Where `meshopt_quad` keeps each compressed stream, for the corruption tests.
pub struct QuadStreams {
    pub positions: std::ops::Range<usize>,
    pub indices: std::ops::Range<usize>,
}

/// The test quad (`quad_document`) plus a triangle-strip copy of it, every view
/// meshopt-compressed into buffer 0 (the GLB BIN chunk), decoding into fallback buffer 1
/// (no URI, `"fallback": true`): positions f32 through EXPONENTIAL, normals i16 through
/// OCTAHEDRAL (KHR_mesh_quantization), uvs f32 unfiltered, list indices TRIANGLES and strip
/// indices INDICES. `list` is the triangle list's indices (`[0, 1, 2, 0, 2, 3]` for the
/// quad). Returns the document, the BIN chunk and where its streams are.
pub fn meshopt_quad(list: &[u32]) -> (Value, Vec<u8>, QuadStreams) {
    let (mut doc, _) = quad_document(None);
    let ws = &mut Workspace::default();
    let vertices = |bytes: &[u8], stride: usize| {
        let v0 = VertexEncoding::new(0, 0).unwrap(); // EXT allows vertex codec version 0 only
        encode_vertex_buffer(
            bytes,
            bytes.len() / stride,
            stride,
            v0,
            &mut Workspace::default(),
        )
        .unwrap()
    };
    let positions = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0];
    let exp = encode_filter_exp(4, 12, 15, &positions, ExpMode::Separate, ws).unwrap();
    let normals = [0.0f32, 0.0, 1.0, 0.0].repeat(4);
    let oct = encode_filter_oct(4, 8, 16, &normals, ws).unwrap();
    let uvs = f32_bytes(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]);
    let v1 = IndexEncoding::new(1).unwrap();
    let streams = [
        // (stream, mode, filter, count, stride)
        (vertices(&exp, 12), "ATTRIBUTES", "EXPONENTIAL", 4, 12),
        (vertices(&oct, 8), "ATTRIBUTES", "OCTAHEDRAL", 4, 8),
        (vertices(&uvs, 8), "ATTRIBUTES", "NONE", 4, 8),
        (
            encode_index_buffer(list, v1, ws).unwrap(),
            "TRIANGLES",
            "NONE",
            list.len(),
            2,
        ),
        (
            encode_index_sequence(&[0, 1, 3, 2], v1, ws).unwrap(),
            "INDICES",
            "NONE",
            4,
            2,
        ),
    ];
    let (mut bin, mut views, mut ranges) = (Vec::new(), Vec::new(), Vec::new());
    let mut decoded_offset = 0;
    for (stream, mode, filter, count, stride) in &streams {
        let length = count * stride;
        let mut view = json!({ "buffer": 1, "byteOffset": decoded_offset, "byteLength": length,
            "extensions": { "EXT_meshopt_compression": { "buffer": 0, "byteOffset": bin.len(),
            "byteLength": stream.len(), "byteStride": stride, "count": count, "mode": mode,
            "filter": filter } } });
        if *mode == "ATTRIBUTES" {
            view["byteStride"] = json!(stride);
        }
        ranges.push(bin.len()..bin.len() + stream.len());
        bin.extend(stream);
        bin.resize(bin.len().next_multiple_of(4), 0);
        decoded_offset = (decoded_offset + length).next_multiple_of(4);
        views.push(view);
    }
    doc["bufferViews"] = Value::Array(views);
    doc["buffers"] = json!([{ "byteLength": bin.len() },
        { "byteLength": decoded_offset, "extensions": { "EXT_meshopt_compression": { "fallback": true } } }]);
    doc["accessors"][1] = json!({ "bufferView": 1, "componentType": 5122, "normalized": true,
        "count": 4, "type": "VEC3" });
    doc["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "bufferView": 4, "componentType": 5123, "count": 4, "type": "SCALAR" }));
    doc["meshes"][0]["primitives"].as_array_mut().unwrap().push(
        json!({ "attributes": { "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2 },
            "indices": 4, "mode": 5, "material": 0 }),
    );
    doc["extensionsUsed"] = json!(["EXT_meshopt_compression", "KHR_mesh_quantization"]);
    doc["extensionsRequired"] = json!(["EXT_meshopt_compression", "KHR_mesh_quantization"]);
    let quad = QuadStreams {
        positions: ranges[0].clone(),
        indices: ranges[3].clone(),
    };
    (doc, bin, quad)
}

/// `meshopt_quad` as a .glb file in `dir`.
pub fn write_glb(dir: &Path, name: &str, doc: &Value, bin: &[u8]) -> PathBuf {
    let path = dir.join(format!("{name}.glb"));
    std::fs::write(&path, glb(doc, bin)).unwrap();
    path
}
