//! Corrupt compressed data, each kind: truncated streams, flipped bytes, counts out of range,
//! indices past the vertex count. Every outcome is either a scene that passed validation
//! (a flipped byte inside a stream may still decode: neither codec carries a checksum) or one
//! line naming the file and the extension — never a panic (caught or not), never a
//! non-finite vertex.

use std::path::Path;

use restir_render::scene::gltf_loader::load_gltf;
use restir_render::scene::load::SceneError;
use serde_json::{Value, json};

use super::asset;
use super::compressed_files::{draco_lamp, meshopt_quad, write_glb, write_with_buffer};
use super::files::{TempDir, quad_document, write_gltf};

/// Load `path`; an error must be one line naming the file and `extension`, and not a
/// (caught) panic. Returns whether it loaded.
fn loads_or_names(path: &Path, extension: &str, case: &str) -> bool {
    match load_gltf(path) {
        Ok(scene) => {
            assert!(
                scene.vertices.iter().all(|v| v.position.is_finite()),
                "{case}: non-finite vertex"
            );
            true
        }
        Err(e) => {
            let message = e.to_string();
            assert!(
                !matches!(e, SceneError::Panicked { .. }),
                "{case}: {message}"
            );
            assert!(!message.contains("crashed"), "{case}: {message}");
            let name = path.file_name().unwrap().to_str().unwrap();
            assert!(message.contains(name), "{case}: {message}");
            assert!(message.contains(extension), "{case}: {message}");
            assert!(!message.contains('\n'), "{case}: {message}");
            false
        }
    }
}

const DRACO: &str = "KHR_draco_mesh_compression";
const MESHOPT: &str = "EXT_meshopt_compression";

#[test]
fn corrupt_draco_streams_are_one_line_naming_the_extension() {
    let dir = TempDir::new("corrupt-draco");
    let (doc, bin, stream) = draco_lamp();
    assert!(loads_or_names(
        &write_with_buffer(&dir, "lamp", &doc, &bin),
        DRACO,
        "intact"
    ));
    // Truncated: every shorter stream fails.
    for length in 1..stream.len() {
        let mut d = doc.clone();
        d["bufferViews"][4]["byteLength"] = json!(length);
        let path = write_with_buffer(&dir, "truncated", &d, &bin);
        assert!(!loads_or_names(
            &path,
            DRACO,
            &format!("truncated to {length}")
        ));
    }
    // The buffer itself cut short inside the stream.
    let path = write_with_buffer(&dir, "short-bin", &doc, &bin[..stream.start + 100]);
    assert!(!loads_or_names(&path, DRACO, "short buffer"));
    // Flipped bytes, every byte of the stream, all bits and the lowest.
    let mut failed = 0;
    for i in stream.clone() {
        for mask in [0xFF, 0x01] {
            let mut b = bin.clone();
            b[i] ^= mask;
            let path = write_with_buffer(&dir, "flipped", &doc, &b);
            failed += !loads_or_names(&path, DRACO, &format!("byte {i} ^ {mask:#x}")) as usize;
        }
    }
    println!("Draco: {failed} of {} flips refused", 2 * stream.len());
    assert!(failed > 0);
    // Counts out of range: a huge varint (2^32 − 1) over each byte where the 11-byte header
    // ends and the connectivity's counts begin, and an attribute id the stream lacks.
    for at in stream.start + 11..stream.start + 16 {
        let mut b = bin.clone();
        b[at..at + 5].copy_from_slice(&[0xFF, 0xFF, 0xFF, 0xFF, 0x0F]);
        let path = write_with_buffer(&dir, "counts", &doc, &b);
        assert!(!loads_or_names(
            &path,
            DRACO,
            &format!("huge count at {at}")
        ));
    }
    let mut d = doc.clone();
    d["meshes"][2]["primitives"][0]["extensions"][DRACO]["attributes"]["POSITION"] = json!(99);
    let path = write_with_buffer(&dir, "attribute", &d, &bin);
    assert!(!loads_or_names(
        &path,
        "POSITION is Draco attribute 99, which the stream lacks",
        "id"
    ));
}

fn quad_path(
    dir: &Path,
    name: &str,
    edit: impl FnOnce(&mut Value, &mut Vec<u8>),
) -> std::path::PathBuf {
    let (mut doc, mut bin, _) = meshopt_quad(&[0, 1, 2, 0, 2, 3]);
    edit(&mut doc, &mut bin);
    write_glb(dir, name, &doc, &bin)
}

#[test]
fn corrupt_meshopt_streams_are_one_line_naming_the_extension() {
    let dir = TempDir::new("corrupt-meshopt");
    let (doc, bin, streams) = meshopt_quad(&[0, 1, 2, 0, 2, 3]);
    assert!(loads_or_names(
        &write_glb(&dir, "quad", &doc, &bin),
        MESHOPT,
        "intact"
    ));
    // Truncated: the positions' and the indices' streams, every shorter length.
    for (view, range) in [(0, &streams.positions), (3, &streams.indices)] {
        for length in 1..range.len() {
            let path = quad_path(&dir, "truncated", |d, _| {
                d["bufferViews"][view]["extensions"][MESHOPT]["byteLength"] = json!(length);
            });
            assert!(!loads_or_names(
                &path,
                MESHOPT,
                &format!("view {view} to {length}")
            ));
        }
    }
    // Flipped bytes: every byte of both streams.
    let mut failed = 0;
    for i in streams.positions.clone().chain(streams.indices.clone()) {
        let path = quad_path(&dir, "flipped", |_, b| b[i] ^= 0xFF);
        failed += !loads_or_names(&path, MESHOPT, &format!("byte {i}")) as usize;
    }
    println!("meshopt: {failed} flips refused");
    assert!(failed > 0);
    // Counts, strides, modes and filters out of range.
    type Edit = fn(&mut Value);
    let cases: [(&str, Edit, &str); 6] = [
        (
            "count",
            |e| e["count"] = json!(5),
            "decodes to 5 × 12 = 60 bytes but the view has byteLength 48",
        ),
        (
            "huge-count",
            |e| e["count"] = json!(1u64 << 40),
            "bytes but the view has byteLength 48",
        ),
        ("stride", |e| e["byteStride"] = json!(7), "byteStride 7"),
        (
            "mode",
            |e| e["mode"] = json!("STRIPS"),
            "mode 'STRIPS' is not one of",
        ),
        (
            "filter",
            |e| e["filter"] = json!("COLOR"),
            "unknown filter 'COLOR'",
        ),
        (
            "source",
            |e| e["byteOffset"] = json!(1 << 20),
            "past the end of the buffer",
        ),
    ];
    for (name, edit, expected) in cases {
        let path = quad_path(&dir, name, |d, _| {
            edit(&mut d["bufferViews"][0]["extensions"][MESHOPT])
        });
        assert!(!loads_or_names(&path, expected, name));
        assert!(!loads_or_names(&path, MESHOPT, name));
    }
    // A fallback buffer's claimed size and offsets are not trusted (its views are laid out
    // again): a terabyte claim loads the same quad, allocating what the streams decode to.
    let path = quad_path(&dir, "claims", |d, _| {
        d["buffers"][1]["byteLength"] = json!(1u64 << 40);
        d["bufferViews"][0]["byteOffset"] = json!(1u64 << 39);
    });
    let claims = load_gltf(&path).unwrap();
    let intact = load_gltf(&write_glb(&dir, "quad", &doc, &bin)).unwrap();
    assert_eq!(claims.vertices, intact.vertices);
    // Indices past the vertex count: a well-formed stream of a bad index buffer.
    let (doc, bin, _) = meshopt_quad(&[0, 1, 2, 0, 2, 9]);
    let path = write_glb(&dir, "index", &doc, &bin);
    let expected =
        "index 9 is out of range (4 vertices) (decoded from EXT_meshopt_compression bufferView 3)";
    assert!(!loads_or_names(&path, expected, "index"));
}

/// The quad textured with `image` (a file in `dir`) through `extension`, required.
fn textured(dir: &Path, name: &str, image: &str, extension: &str) -> std::path::PathBuf {
    let (mut doc, bin) = quad_document(Some(&format!("{name}.bin")));
    doc["images"] = json!([{ "uri": image }]);
    doc["textures"] = json!([{ "extensions": { extension: { "source": 0 } } }]);
    doc["materials"][0]["pbrMetallicRoughness"] = json!({ "baseColorTexture": { "index": 0 } });
    doc["extensionsUsed"] = json!([extension]);
    doc["extensionsRequired"] = json!([extension]);
    write_gltf(dir, name, &doc, &bin)
}

#[test]
fn corrupt_ktx2_and_webp_images_are_one_line_naming_the_extension() {
    let dir = TempDir::new("corrupt-images");
    for (file, extension) in [
        ("checker-64-etc1s.ktx2", "KHR_texture_basisu"),
        ("checker-64-uastc.ktx2", "KHR_texture_basisu"),
        ("checker-64-lossy.webp", "EXT_texture_webp"),
        ("checker-64-lossless.webp", "EXT_texture_webp"),
    ] {
        let bytes = std::fs::read(asset(&format!("compressed/{file}"))).unwrap();
        let try_bytes = |variant: &[u8], case: String| {
            std::fs::write(dir.join(file), variant).unwrap();
            loads_or_names(&textured(&dir, "image", file, extension), extension, &case)
        };
        assert!(try_bytes(&bytes, format!("{file} intact")));
        // Cut short anywhere.
        for length in (0..bytes.len()).step_by(7).chain([bytes.len() - 1]) {
            let case = format!("{file} cut to {length} of {} bytes", bytes.len());
            assert!(!try_bytes(&bytes[..length], case.clone()), "{case} loads");
        }
        // Every byte of the headers (KTX2: header, level index, DFD, key/values, Basis
        // global data), then every 5th.
        let mut failed = 0;
        for i in (0..bytes.len()).filter(|&i| i < 320 || i % 5 == 0) {
            let mut b = bytes.clone();
            b[i] ^= 0xFF;
            failed += !try_bytes(&b, format!("{file} byte {i}")) as usize;
        }
        println!("{file}: {failed} flips refused");
        assert!(failed > 0);
    }
}
