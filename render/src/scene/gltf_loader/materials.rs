//! glTF materials and textures → `Material` / `Texture`. Scene material `i` and texture `i`
//! are glTF material `i` and texture `i`, so indices in the file and in the scene agree.

use std::collections::BTreeMap;
use std::path::Path;

use glam::{Vec3, Vec4};
use gltf::texture::WrappingMode;

use super::super::validate::{SceneError, one_line};
use super::super::{AlphaMode, Material, Texture, TextureRef, UvTransform, Wrap};
use super::compressed::{BASISU, WEBP};
use super::{data, ktx2};
use crate::load_phases::{LoadEvent, Watcher};

/// Every material of the document, in order. Normal and occlusion textures are ignored: this
/// renderer shades with vertex normals and computes its own visibility.
pub(super) fn load_materials(file: &str, doc: &gltf::Document) -> Vec<Material> {
    doc.materials().map(|m| material(file, &m)).collect()
}

fn material(file: &str, m: &gltf::Material) -> Material {
    let name = m
        .name()
        .map(str::to_string)
        .unwrap_or_else(|| format!("material {}", m.index().unwrap_or(0)));
    let pbr = m.pbr_metallic_roughness();
    let slot = |info: Option<gltf::texture::Info>, slot: &str| {
        info.map(|info| texture_ref(file, &name, slot, &info))
    };
    let strength = m.emissive_strength().unwrap_or(1.0);
    let transmission = m.transmission();
    let material = Material {
        base_color: Vec4::from_array(pbr.base_color_factor()),
        base_color_texture: slot(pbr.base_color_texture(), "baseColorTexture"),
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        metallic_roughness_texture: slot(
            pbr.metallic_roughness_texture(),
            "metallicRoughnessTexture",
        ),
        emission: Vec3::from_array(m.emissive_factor()) * strength,
        emissive_texture: slot(m.emissive_texture(), "emissiveTexture"),
        specular: m.specular().map_or(1.0, |s| s.specular_factor()),
        double_sided: m.double_sided(),
        alpha_mode: match m.alpha_mode() {
            gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
            gltf::material::AlphaMode::Mask => AlphaMode::Mask(m.alpha_cutoff().unwrap_or(0.5)),
            gltf::material::AlphaMode::Blend => AlphaMode::Blend,
        },
        transmission: transmission
            .as_ref()
            .map_or(0.0, |t| t.transmission_factor())
            .clamp(0.0, 1.0),
        transmission_texture: slot(
            transmission.and_then(|t| t.transmission_texture()),
            "transmissionTexture",
        ),
        unlit: m.unlit(),
        name,
    };
    warn_on_disagreeing_uv_sets(file, &material);
    material
}

/// A slot's texture, uv set and `KHR_texture_transform`. A transform with a non-finite value
/// is dropped with a warning (the texture is still read, untransformed).
fn texture_ref(file: &str, material: &str, slot: &str, info: &gltf::texture::Info) -> TextureRef {
    let mut r = TextureRef::new(info.texture().index() as u32);
    r.tex_coord = info.tex_coord();
    if let Some(t) = info.texture_transform() {
        r.tex_coord = t.tex_coord().unwrap_or(r.tex_coord);
        match UvTransform::from_khr(t.offset(), t.rotation(), t.scale()) {
            Some(m) => r.transform = m,
            None => log::warn!(
                "{file}: material '{material}' {slot}: KHR_texture_transform has a non-finite \
                 value (offset {:?}, rotation {}, scale {:?}); the texture is read untransformed",
                t.offset(),
                t.rotation(),
                t.scale()
            ),
        }
    }
    r
}

/// Vertices carry one uv set per primitive: when the slots of a material name different
/// sets, one warning names them and the base colour slot's set is read (`Material::uv_set`).
fn warn_on_disagreeing_uv_sets(file: &str, material: &Material) {
    let used: Vec<String> = material
        .texture_slots()
        .iter()
        .filter_map(|(slot, r)| r.map(|r| format!("{slot} TEXCOORD_{}", r.tex_coord)))
        .collect();
    let sets: std::collections::BTreeSet<u32> = material
        .texture_slots()
        .iter()
        .filter_map(|(_, r)| r.map(|r| r.tex_coord))
        .collect();
    if sets.len() > 1 {
        log::warn!(
            "{file}: material '{}' reads different uv sets ({}); only one is stored per \
             vertex, TEXCOORD_{} is used for every slot",
            material.name,
            used.join(", "),
            material.uv_set()
        );
    }
}

/// Every texture of the document, the ones a material slot reads decoded to RGBA8 (in
/// parallel, one image per thread at a time; each image once even when several textures
/// share it). A texture no slot reads (normal and occlusion maps: see `load_materials`) is
/// not decoded: it stays in the list as one white texel, so texture indices keep matching
/// the file's. Returns the textures and the phase's detail line.
pub(super) fn load_textures(
    file: &str,
    doc: &gltf::Document,
    base: &Path,
    buffers: &[Vec<u8>],
    materials: &[Material],
    extension_images: &BTreeMap<usize, &'static str>,
    watch: Watcher,
) -> Result<(Vec<Texture>, String), SceneError> {
    let mut read = vec![false; doc.textures().len()];
    for m in materials {
        for r in m.texture_slots().into_iter().filter_map(|(_, r)| r) {
            if let Some(flag) = read.get_mut(r.texture as usize) {
                *flag = true;
            }
        }
    }
    let mut wanted: Vec<gltf::Image> = Vec::new();
    for texture in doc.textures().filter(|t| read[t.index()]) {
        let image = texture.source();
        if !wanted.iter().any(|w| w.index() == image.index()) {
            wanted.push(image);
        }
    }
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(wanted.len())
        .max(1);
    let decoded = decode_in_parallel(&wanted, threads, watch, |image| {
        let extension = extension_images.get(&image.index()).copied();
        decode_image(file, image, base, buffers, extension)
    })?;
    let by_index = |i: usize| {
        wanted
            .iter()
            .position(|w| w.index() == i)
            .map(|k| &decoded[k])
    };
    let mut textures = Vec::new();
    for texture in doc.textures() {
        let image = texture.source();
        let sampler = texture.sampler();
        let name = texture
            .name()
            .or(image.name())
            .map_or_else(|| format!("texture {}", texture.index()), str::to_string);
        let (width, height, texels) =
            match by_index(image.index()).filter(|_| read[texture.index()]) {
                Some(rgba) => (
                    rgba.width(),
                    rgba.height(),
                    rgba.pixels().map(|p| p.0).collect(),
                ),
                None => (1, 1, vec![[255; 4]]),
            };
        textures.push(Texture {
            name,
            width,
            height,
            texels,
            wrap_u: wrap(sampler.wrap_s()),
            wrap_v: wrap(sampler.wrap_t()),
        });
    }
    let largest = decoded
        .iter()
        .max_by_key(|i| i.width() as u64 * i.height() as u64)
        .map_or_else(String::new, |i| {
            format!(", {}×{} largest", i.width(), i.height())
        });
    let skipped = doc.images().len() - wanted.len();
    let detail = format!(
        "{} decoded{largest}, {skipped} not read by any material skipped, {threads} threads",
        wanted.len()
    );
    Ok((textures, detail))
}

/// `decode` applied to every item on `threads` threads, results in item order; the first
/// error (by item order) wins. Tells `watch` as each finishes.
fn decode_in_parallel<T: Sync, R: Send>(
    items: &[T],
    threads: usize,
    watch: Watcher,
    decode: impl Fn(&T) -> Result<R, SceneError> + Sync,
) -> Result<Vec<R>, SceneError> {
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<R, SceneError>>>> =
        Mutex::new((0..items.len()).map(|_| None).collect());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(item) = items.get(i) else { break };
                    let result = decode(item);
                    results.lock().expect("no decoder panics holding it")[i] = Some(result);
                    let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                    watch(LoadEvent::Progress {
                        phase: "images",
                        done: finished,
                        total: items.len(),
                    });
                }
            });
        }
    });
    results
        .into_inner()
        .expect("no decoder panics holding it")
        .into_iter()
        .map(|r| r.expect("every item is decoded"))
        .collect()
}

fn wrap(mode: WrappingMode) -> Wrap {
    match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
    }
}

/// Decode one image to RGBA8. `extension` is the one a texture reads it through
/// (KHR_texture_basisu, EXT_texture_webp), named in its errors.
fn decode_image(
    file: &str,
    image: &gltf::Image,
    base: &Path,
    buffers: &[Vec<u8>],
    extension: Option<&str>,
) -> Result<::image::RgbaImage, SceneError> {
    let (label, bytes) = match image.source() {
        gltf::image::Source::View { view, .. } => (
            format!("{} (bufferView {})", image.index(), view.index()),
            data::view_bytes(file, &view, buffers)?.to_vec(),
        ),
        gltf::image::Source::Uri { uri, .. } => {
            let label = if uri.starts_with("data:") {
                format!("{} (data URI)", image.index())
            } else {
                format!("{} ('{uri}')", image.index())
            };
            let bytes = data::read_image_uri(file, base, uri, &format!("image {label}"))?;
            (label, bytes)
        }
    };
    let is_ktx2 = ktx2::is_ktx2(&bytes);
    let is_webp = bytes.len() >= 12 && &bytes[..4] == b"RIFF" && &bytes[8..12] == b"WEBP";
    // Errors name the extension the image is read through, or its format says.
    let named = extension
        .or(is_ktx2.then_some(BASISU))
        .or(is_webp.then_some(WEBP))
        .map_or_else(String::new, |e| format!("{e}: "));
    let error = |detail: String| SceneError::Image {
        file: file.to_string(),
        image: label.clone(),
        detail: one_line(format!("{named}{detail}")),
    };
    // The format is told by the bytes: exporters get mimeType and file extensions wrong.
    // KTX2 (KHR_texture_basisu) is transcoded here; WebP (EXT_texture_webp) is the image
    // crate's, like PNG and JPEG.
    if is_ktx2 {
        return ktx2::decode(&bytes).map_err(error);
    }
    if is_webp {
        // The decoder reads zeros past a cut-short stream: the RIFF size says where it ends.
        let riff = u32::from_le_bytes([bytes[4], bytes[5], bytes[6], bytes[7]]) as u64 + 8;
        if (bytes.len() as u64) < riff {
            return Err(error(format!(
                "the file is cut short: {} of the {riff} bytes its RIFF header gives",
                bytes.len()
            )));
        }
    }
    ::image::load_from_memory(&bytes)
        .map(|img| img.to_rgba8())
        .map_err(|e| error(e.to_string()))
}
