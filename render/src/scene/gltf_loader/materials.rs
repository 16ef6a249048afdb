//! glTF materials and textures → `Material` / `Texture`. Scene material `i` and texture `i`
//! are glTF material `i` and texture `i`, so indices in the file and in the scene agree.

use std::path::Path;

use glam::{Vec3, Vec4};
use gltf::texture::WrappingMode;

use super::super::load::{SceneError, one_line};
use super::super::{AlphaMode, Material, Texture, TextureRef, UvTransform, Wrap};
use super::data;

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

/// Every texture of the document decoded to RGBA8. Each image is decoded once even when
/// several textures (with different samplers) share it.
pub(super) fn load_textures(
    file: &str,
    doc: &gltf::Document,
    base: &Path,
    buffers: &[Vec<u8>],
) -> Result<Vec<Texture>, SceneError> {
    let mut decoded: Vec<Option<::image::RgbaImage>> = vec![None; doc.images().len()];
    let mut textures = Vec::new();
    for texture in doc.textures() {
        let image = texture.source();
        let slot = &mut decoded[image.index()];
        if slot.is_none() {
            *slot = Some(decode_image(file, &image, base, buffers)?);
        }
        let rgba = slot.as_ref().expect("decoded just above");
        let sampler = texture.sampler();
        let name = texture
            .name()
            .or(image.name())
            .map_or_else(|| format!("texture {}", texture.index()), str::to_string);
        textures.push(Texture {
            name,
            width: rgba.width(),
            height: rgba.height(),
            texels: rgba.pixels().map(|p| p.0).collect(),
            wrap_u: wrap(sampler.wrap_s()),
            wrap_v: wrap(sampler.wrap_t()),
        });
    }
    Ok(textures)
}

fn wrap(mode: WrappingMode) -> Wrap {
    match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
    }
}

fn decode_image(
    file: &str,
    image: &gltf::Image,
    base: &Path,
    buffers: &[Vec<u8>],
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
            let bytes = data::read_uri(file, base, uri, &format!("image {label}"))?;
            (label, bytes)
        }
    };
    // The format is guessed from the bytes: exporters get mimeType and file extensions wrong.
    ::image::load_from_memory(&bytes)
        .map(|img| img.to_rgba8())
        .map_err(|e| SceneError::Image {
            file: file.to_string(),
            image: label,
            detail: one_line(e.to_string()),
        })
}
