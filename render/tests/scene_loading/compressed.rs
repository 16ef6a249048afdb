//! Compressed glTF read against its uncompressed twin, on the CPU: the Cornell box's Draco
//! and meshopt twins (gltf-transform's output, assets/compressed) and a meshopt quad made
//! here, geometry equal up to the codec's quantisation; KTX2 (ETC1S, UASTC) and WebP
//! (lossless, lossy) textures equal to their PNG up to the codec's loss. Each comparison has
//! a planted twin (dequantisation skipped, texels converted sRGB → linear) it must catch.

use restir_render::scene::Scene;
use restir_render::scene::gltf_loader::load_gltf;
use serde_json::{Value, json};

use super::asset;
use super::compressed_files::{
    DRACO, MESHOPT, PLAIN, absolute_image_uris, meshopt_quad, read_json, write_glb,
};
use super::files::{TempDir, quad_document, write_gltf};
use super::twins::{
    largest_extent, png_texels, skip_dequantisation, srgb_to_linear, texel_errors, twin_errors,
};

fn load(relative: &str) -> Scene {
    load_gltf(&asset(relative)).unwrap_or_else(|e| panic!("{e}"))
}

fn report(scene: &Scene) -> Vec<String> {
    scene.extensions.iter().map(|e| e.to_string()).collect()
}

/// Same triangles per material, same materials and textures.
fn assert_same_model(plain: &Scene, twin: &Scene, what: &str) {
    assert_eq!(twin.triangles.len(), plain.triangles.len(), "{what}");
    let names = |s: &Scene| {
        s.materials
            .iter()
            .map(|m| m.name.clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(names(twin), names(plain), "{what}");
    let per_material = |s: &Scene| {
        let mut n = vec![0; s.materials.len()];
        s.triangles.iter().for_each(|t| n[t.material as usize] += 1);
        n
    };
    assert_eq!(per_material(twin), per_material(plain), "{what}");
    let sizes = |s: &Scene| {
        s.textures
            .iter()
            .map(|t| (t.width, t.height))
            .collect::<Vec<_>>()
    };
    assert_eq!(sizes(twin), sizes(plain), "{what}");
}

/// gltf-transform's defaults, both codecs: positions on a 14-bit grid over each mesh's
/// bounds, normals 10 bits (Draco octahedral) or 8 bits (meshopt OCTAHEDRAL on i8), uvs 12
/// bits. A grid step of the largest mesh, L / (2^14 − 1), bounds every position error (a
/// rounding error is half a step per axis, √3/2 of a step as a distance). Normals: an 8-bit
/// octahedral step is 2/127 ≈ 0.016 per coordinate before renormalising, so 0.02 holds
/// both. uvs: gltf-transform keeps out-of-[0,1] uvs as floats (meshopt) or quantises their
/// range to 12 bits (Draco, range ≤ 2 here): 2/4095 ≈ 5e-4 bounds a step. Measured: Draco
/// |Δp| 6.7e-5 (bound 2.4e-4), |Δn| 0.0039, |Δuv| 2.4e-4; meshopt 8.2e-5, 0.0174, 1.8e-4.
#[test]
fn draco_and_meshopt_twins_of_the_cornell_box_match_the_plain_file() {
    let plain = load(PLAIN);
    let bound = largest_extent(&plain) / ((1 << 14) - 1) as f32;
    for (file, expected) in [
        (DRACO, vec!["KHR_draco_mesh_compression (required): used"]),
        (
            MESHOPT,
            vec![
                "EXT_meshopt_compression (required): used",
                "KHR_mesh_quantization (required): used",
            ],
        ),
    ] {
        let twin = load(file);
        assert_same_model(&plain, &twin, file);
        assert_eq!(report(&twin), expected);
        let e = twin_errors(&plain, &twin);
        println!("{file}: {e:?} (position bound {bound:.2e})");
        assert_eq!(e.unmatched, 0, "{file}: {e:?}");
        assert!(e.position <= bound, "{file}: {e:?} vs {bound}");
        assert!(e.normal <= 0.02, "{file}: {e:?}");
        assert!(e.uv <= 5e-4, "{file}: {e:?}");
        assert!(twin.vertices.iter().all(|v| v.position.is_finite()));
        // Planted twin: positions left on the integer grid are caught.
        let planted = twin_errors(&plain, &skip_dequantisation(&twin, 14));
        assert!(
            planted.unmatched > 0 || planted.position > bound,
            "the detector must fire: {planted:?}"
        );
    }
}

/// The meshopt twin as a GLB: its compressed buffer is the BIN chunk, its fallback buffer has
/// no URI and no bytes, and the loader reads the same scene as from the .gltf.
#[test]
fn the_meshopt_twin_reads_the_same_from_a_glb() {
    let dir = TempDir::new("meshopt-glb");
    let path = asset(MESHOPT);
    let mut doc = read_json(&path);
    absolute_image_uris(&mut doc, &path);
    doc["buffers"][0].as_object_mut().unwrap().remove("uri");
    let bin = std::fs::read(path.with_extension("bin")).unwrap();
    let from_glb = load_gltf(&write_glb(&dir, "cornell-meshopt", &doc, &bin)).unwrap();
    let from_gltf = load(MESHOPT);
    assert_eq!(from_glb.vertices, from_gltf.vertices);
    assert_eq!(from_glb.triangles, from_gltf.triangles);
}

#[test]
fn a_meshopt_quad_with_every_mode_and_filter_decodes_exactly() {
    let dir = TempDir::new("meshopt-quad");
    let (plain_doc, plain_bin) = quad_document(Some("plain.bin"));
    let plain = load_gltf(&write_gltf(&dir, "plain", &plain_doc, &plain_bin)).unwrap();
    let (doc, bin, _) = meshopt_quad(&[0, 1, 2, 0, 2, 3]);
    let quad = load_gltf(&write_glb(&dir, "quad", &doc, &bin)).unwrap();
    // The list and the strip: 2 + 2 triangles over the same four corners. The filters are
    // exact here: 0 and 1 in EXPONENTIAL, +z in 16-bit OCTAHEDRAL.
    assert_eq!(quad.triangles.len(), 4);
    assert_eq!(quad.vertices[..4], plain.vertices[..]);
    assert_eq!(quad.vertices[4..], plain.vertices[..]);
    let corners = |s: &Scene, t: usize| s.triangle_positions(t);
    assert_eq!(corners(&quad, 0), corners(&plain, 0));
    assert_eq!(corners(&quad, 1), corners(&plain, 1));
    // Strip 0,1,3,2: triangles (0,1,3) and (1,2,3) in the spec's order, same winding.
    let v = |i: usize| plain.vertices[i].position;
    assert_eq!(corners(&quad, 2), [v(0), v(1), v(3)]);
    assert_eq!(corners(&quad, 3), [v(1), v(2), v(3)]);
}

/// A quad whose base colour (and metallic-roughness) textures are the given images, each
/// texture `{source, extensions}` as given.
fn textured_quad(images: &[&str], base: Value, metal_rough: Option<Value>) -> (Value, Vec<u8>) {
    let (mut doc, bin) = quad_document(None);
    let folder = asset("compressed").canonicalize().unwrap();
    doc["images"] = images
        .iter()
        .map(|name| json!({ "uri": folder.join(name).to_str().unwrap() }))
        .collect();
    let mut textures = vec![base];
    let mut pbr = json!({ "baseColorTexture": { "index": 0 } });
    if let Some(mr) = metal_rough {
        textures.push(mr);
        pbr["metallicRoughnessTexture"] = json!({ "index": 1 });
    }
    doc["textures"] = Value::Array(textures);
    doc["materials"][0]["pbrMetallicRoughness"] = pbr;
    (doc, bin)
}

fn load_textured(dir: &TempDir, name: &str, doc: &Value, bin: &[u8]) -> Scene {
    let mut doc = doc.clone();
    doc["buffers"][0]["uri"] = json!(format!("{name}.bin"));
    load_gltf(&write_gltf(dir, name, &doc, bin)).unwrap_or_else(|e| panic!("{e}"))
}

/// KTX2 and WebP textures against the PNG they were made from (assets/compressed/README.md):
/// WebP lossless is exact; the lossy codecs are held to a mean absolute error in 8-bit units
/// a little above what was measured (ETC1S 3.38, UASTC 1.22, WebP q90 2.67; the linear UASTC
/// metallic-roughness map 0.25, never more than 1). Single texels may be far off (ETC1S
/// 212, a thin line lost in its 4×4 block), so the mean is what is held. The planted twin
/// converting sRGB to linear is 13–15 off on the checker (24 on the ramps), over twice each
/// tolerance. The KTX2 is preferred to the PNG fallback the texture also names; a texture
/// without `source` reads its extension's image.
#[test]
fn ktx2_and_webp_textures_match_their_png_within_the_codecs_loss() {
    let dir = TempDir::new("texture-twins");
    let png = png_texels(&asset("compressed/checker-64.png"));
    let mr_png = png_texels(&asset("compressed/mr-64.png"));
    let ext = |name: &str, source: usize| json!({ "extensions": { name: { "source": source } } });
    let with_fallback = |name: &str| {
        let mut t = ext(name, 1);
        t["source"] = json!(0);
        t
    };
    let basisu = "KHR_texture_basisu";
    let webp = "EXT_texture_webp";
    // (name, images, base texture, extension, tolerance on the mean error)
    let cases: [(&str, &[&str], Value, &str, f64); 4] = [
        (
            "etc1s",
            &["checker-64.png", "checker-64-etc1s.ktx2"],
            with_fallback(basisu),
            basisu,
            4.5,
        ),
        (
            "uastc",
            &["checker-64-uastc.ktx2"],
            ext(basisu, 0),
            basisu,
            1.75,
        ),
        (
            "lossless",
            &["checker-64-lossless.webp"],
            ext(webp, 0),
            webp,
            0.0,
        ),
        (
            "lossy",
            &["checker-64.png", "checker-64-lossy.webp"],
            with_fallback(webp),
            webp,
            3.5,
        ),
    ];
    for (name, images, base, extension, tolerance) in cases {
        let (mut doc, bin) = textured_quad(images, base, None);
        doc["extensionsUsed"] = json!([extension]);
        if !images[0].ends_with(".png") {
            doc["extensionsRequired"] = json!([extension]);
        }
        let scene = load_textured(&dir, name, &doc, &bin);
        let t = &scene.textures[0];
        assert_eq!((t.width, t.height), (64, 64), "{name}");
        let (mean, max) = texel_errors(&t.texels, &png);
        println!("{name}: mean |Δ| {mean:.2}, max {max} (8-bit units)");
        assert!(mean <= tolerance, "{name}: mean {mean} > {tolerance}");
        if tolerance > 0.0 {
            assert!(
                mean > 0.0,
                "{name}: identical to the PNG: the fallback was read"
            );
        } else {
            assert_eq!(max, 0, "{name}");
        }
        assert!(
            report(&scene)[0].starts_with(extension),
            "{:?}",
            report(&scene)
        );
        let (planted, _) = texel_errors(&srgb_to_linear(&t.texels), &png);
        println!("{name}: planted sRGB → linear: mean |Δ| {planted:.2}");
        assert!(
            planted > 2.0 * tolerance.max(1.0),
            "{name}: the detector must fire: {planted}"
        );
    }
    // Linear data stays linear: a UASTC metallic-roughness map (linear transfer function).
    let (mut doc, bin) = textured_quad(
        &["checker-64.png", "mr-64-uastc.ktx2"],
        json!({ "source": 0 }),
        Some(ext(basisu, 1)),
    );
    doc["extensionsUsed"] = json!([basisu]);
    let scene = load_textured(&dir, "mr", &doc, &bin);
    let (mean, max) = texel_errors(&scene.textures[1].texels, &mr_png);
    println!("mr uastc: mean |Δ| {mean:.2}, max {max}");
    assert!(
        mean <= 0.5 && max <= 2,
        "metallic-roughness: mean {mean}, max {max}"
    );
    let (planted, _) = texel_errors(&srgb_to_linear(&scene.textures[1].texels), &mr_png);
    println!("mr uastc: planted sRGB → linear: mean |Δ| {planted:.2}");
    assert!(planted > 3.0, "the detector must fire: {planted}");
    assert_eq!(
        scene.textures[0].texels, png,
        "the plain PNG slot is untouched"
    );
}
