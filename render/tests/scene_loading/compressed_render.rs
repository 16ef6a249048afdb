//! The compressed twins through the real GPU path (lavapipe in CI), 32×24, against their
//! plain files rendered with the same settings, camera and seed: the Cornell box's Draco and
//! meshopt twins (direct light, NEE), and a quad whose emissive texture is the checker as
//! PNG, KTX2 (ETC1S, UASTC) and WebP, shown as it is (the sRGB decode on the GPU included).
//! Planted twins (positions left on the quantisation grid, texels converted sRGB → linear)
//! must fail the same comparison.

use glam::{Quat, Vec3};
use restir_render::scene::gltf_loader::load_gltf;
use restir_render::{Camera, Gpu, LinearImage, Mode, Renderer, Scene, Settings};
use serde_json::json;

use super::asset;
use super::compressed_files::{DRACO, MESHOPT, PLAIN};
use super::files::{TempDir, quad_document, write_gltf};
use super::twins::{skip_dequantisation, srgb_to_linear};

const SIZE: (u32, u32) = (32, 24);

fn render(gpu: &Gpu, scene: &Scene, camera: Camera, seed: u32) -> LinearImage {
    let mut settings = Settings::default();
    settings.apply_assignments(["jitter=false"]).unwrap();
    let mut r = Renderer::new(gpu.clone(), scene, SIZE.0, SIZE.1, settings)
        .unwrap_or_else(|e| panic!("{e:#}"));
    r.set_mode(Mode::Nee);
    r.set_seed(seed);
    r.set_camera(camera);
    r.reset_accumulation();
    for _ in 0..8 {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
    }
    r.read_accumulated()
}

fn luma(p: &[f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// (|mean luma ratio − 1|, mean per-pixel |Δ luma| / mean luma) of `twin` against `plain`.
fn difference(plain: &LinearImage, twin: &LinearImage) -> (f64, f64) {
    let mean = plain.pixels.iter().map(luma).sum::<f64>() / plain.pixels.len() as f64;
    let twin_mean = twin.pixels.iter().map(luma).sum::<f64>() / twin.pixels.len() as f64;
    let per_pixel = plain
        .pixels
        .iter()
        .zip(&twin.pixels)
        .map(|(a, b)| (luma(a) - luma(b)).abs())
        .sum::<f64>()
        / plain.pixels.len() as f64;
    ((twin_mean / mean - 1.0).abs(), per_pixel / mean)
}

/// The quad, black, its emissive texture the given image through `extension`.
fn emissive_quad(dir: &TempDir, name: &str, image: &str, extension: Option<&str>) -> Scene {
    let (mut doc, bin) = quad_document(Some(&format!("{name}.bin")));
    let path = asset("compressed").canonicalize().unwrap().join(image);
    doc["images"] = json!([{ "uri": path.to_str().unwrap() }]);
    doc["samplers"] = json!([{ "magFilter": 9728, "minFilter": 9728 }]);
    doc["textures"] = json!([match extension {
        Some(e) => json!({ "sampler": 0, "extensions": { e: { "source": 0 } } }),
        None => json!({ "sampler": 0, "source": 0 }),
    }]);
    if let Some(e) = extension {
        doc["extensionsUsed"] = json!([e]);
        doc["extensionsRequired"] = json!([e]);
    }
    doc["materials"][0] = json!({ "emissiveFactor": [1.0, 1.0, 1.0],
        "emissiveTexture": { "index": 0 },
        "pbrMetallicRoughness": { "baseColorFactor": [0.0, 0.0, 0.0, 1.0] } });
    load_gltf(&write_gltf(dir, name, &doc, &bin)).unwrap_or_else(|e| panic!("{e}"))
}

/// Tolerances. Geometry: the twins differ from the plain box by at most a 14-bit grid step
/// (≈ 1e-4 of its size, far below a pixel at 32×24), but their triangles come in another
/// order, which re-deals NEE's light samples: a twin may differ from the plain render by
/// what another seed does (measured on lavapipe, 8 frames: mean luma 0.03 %, per pixel
/// 4.7 %; the twins: Draco 0.03 % and 3.4 %, meshopt 0.01 % and 2.3 %). Textures: the
/// render shows the texels, so the twins differ by the codec's texel error after the sRGB
/// decode (measured: ETC1S 0.25 % and 1.1 %, UASTC 0.26 % and 0.63 %, WebP lossless 0); the
/// planted sRGB → linear twin is 12.7 % off.
#[test]
fn compressed_twins_render_like_their_plain_files() {
    let gpu = Gpu::new_headless().unwrap_or_else(|e| panic!("GPU tests need a wgpu adapter: {e}"));
    let plain = load_gltf(&asset(PLAIN)).unwrap();
    let camera = plain.default_camera();
    let reference = render(&gpu, &plain, camera, 0);
    // The noise floor: the plain file again with another seed. A twin's triangles come in
    // another order, so its light samples are as if re-seeded: it may differ by that much.
    let (noise_mean, noise_pixel) = difference(&reference, &render(&gpu, &plain, camera, 1));
    println!("plain, other seed: mean luma {noise_mean:.4}, per pixel {noise_pixel:.4}");
    let (mean_bound, pixel_bound) = (0.005f64.max(3.0 * noise_mean), 1.25 * noise_pixel);
    for file in [DRACO, MESHOPT] {
        let twin = load_gltf(&asset(file)).unwrap();
        let (mean, per_pixel) = difference(&reference, &render(&gpu, &twin, camera, 0));
        println!("{file}: mean luma {mean:.4}, per pixel {per_pixel:.4}");
        assert!(
            mean < mean_bound && per_pixel < pixel_bound,
            "{file}: {mean}, {per_pixel}"
        );
    }
    let planted = skip_dequantisation(&load_gltf(&asset(DRACO)).unwrap(), 14);
    let (mean, per_pixel) = difference(&reference, &render(&gpu, &planted, camera, 0));
    println!("planted (no dequantisation): mean {mean:.3}, per pixel {per_pixel:.3}");
    assert!(
        mean > mean_bound || per_pixel > pixel_bound,
        "the detector must fire"
    );

    let dir = TempDir::new("compressed-render");
    // Facing the unit quad from (0.5, 0.5, 2): it fills the image's height.
    let quad_camera = Camera {
        position: Vec3::new(0.5, 0.5, 2.0),
        rotation: Quat::IDENTITY,
        yfov: 2.0 * 0.25f32.atan(),
    };
    let png = emissive_quad(&dir, "png", "checker-64.png", None);
    let reference = render(&gpu, &png, quad_camera, 0);
    for (name, image, extension, tolerance) in [
        ("etc1s", "checker-64-etc1s.ktx2", "KHR_texture_basisu", 0.02),
        (
            "uastc",
            "checker-64-uastc.ktx2",
            "KHR_texture_basisu",
            0.0125,
        ),
        ("webp", "checker-64-lossless.webp", "EXT_texture_webp", 1e-6),
    ] {
        let twin = emissive_quad(&dir, name, image, Some(extension));
        let (mean, per_pixel) = difference(&reference, &render(&gpu, &twin, quad_camera, 0));
        println!(
            "{name}: mean luma {:.3} %, per pixel {:.3} %",
            mean * 100.0,
            per_pixel * 100.0
        );
        assert!(
            mean <= tolerance && per_pixel <= tolerance,
            "{name}: {mean}, {per_pixel}"
        );
    }
    let mut planted = emissive_quad(
        &dir,
        "planted",
        "checker-64-uastc.ktx2",
        Some("KHR_texture_basisu"),
    );
    planted.textures[0].texels = srgb_to_linear(&planted.textures[0].texels);
    let (mean, per_pixel) = difference(&reference, &render(&gpu, &planted, quad_camera, 0));
    println!("planted (sRGB → linear): mean {mean:.3}, per pixel {per_pixel:.3}");
    assert!(mean > 0.04 && per_pixel > 0.04, "the detector must fire");
}
