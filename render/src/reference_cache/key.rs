//! The cache key of a reference image: a canonical text naming everything the reference
//! depends on (scene content, camera, size, spp, jitter, effect set, seed, bounces, and
//! the shaders that render it), and a stable 64-bit hash of that text for the file name.
//!
//! The text is stored beside the image and compared on load, so a hash collision can never
//! hand back the wrong image.

use std::path::Path;

use anyhow::Context;

use super::ReferenceRequest;
use crate::fnv::Fnv64;
use crate::shader_source::compose;

/// Bump when something a reference depends on changes in a way the key cannot see (the
/// reference estimator's Rust side; a built-in scene's generator is seen: its content is
/// hashed).
pub const CACHE_VERSION: u32 = 1;

/// A reference's identity: the canonical description and its hash.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReferenceKey {
    pub hash: u64,
    /// One `name=value` per line (stored in the cache's JSON and compared on load).
    pub description: String,
}

impl ReferenceKey {
    /// The file stem in the cache directory.
    pub fn stem(&self) -> String {
        format!("ref-{:016x}", self.hash)
    }
}

/// The key of `request`. Reads the scene file (and, for .gltf, the buffers and images it
/// names) to hash its bytes; builds a built-in scene to hash its content.
pub fn key_of(request: &ReferenceRequest) -> anyhow::Result<ReferenceKey> {
    let scene = scene_fingerprint(&request.scene)?;
    let c = &request.camera;
    // Bit patterns, so the key never depends on how a float prints.
    let bits = |v: &[f32]| {
        v.iter()
            .map(|x| format!("{:08x}", x.to_bits()))
            .collect::<Vec<_>>()
            .join(",")
    };
    let defines = request.effects.defines();
    let mut shaders = Fnv64::default();
    for entry in [
        "gbuffer_raster.wgsl",
        "gbuffer_resolve.wgsl",
        "reference.wgsl",
    ] {
        match compose(entry, &defines) {
            Ok(text) => shaders.write(text.as_bytes()),
            Err(e) => shaders.write(e.to_string().as_bytes()),
        }
    }
    let description = format!(
        "version={CACHE_VERSION}\nscene={}\nscene_content={scene:016x}\ncamera_position={}\n\
         camera_rotation={}\ncamera_yfov={}\nsize={}x{}\nspp={}\njitter={}\neffects={}\n\
         seed={}\nshaders={:016x}\n",
        request.scene,
        bits(&c.position.to_array()),
        bits(&c.rotation.to_array()),
        bits(&[c.yfov]),
        request.width,
        request.height,
        request.spp,
        request.jitter,
        request.effects,
        request.seed,
        shaders.finish(),
    );
    // Only with an environment, so keys (and caches) of scenes without one are unchanged.
    let mut description = match &request.environment {
        Some(env) => format!("{description}environment={env}\n"),
        None => description,
    };
    // Likewise only for an animated scene.
    if let Some(t) = request.scene_time {
        description.push_str(&format!("scene_time={:08x}\n", t.to_bits()));
    }
    // And only beyond direct light (1 bounce, what every reference was before).
    if request.max_bounces != 1 {
        description.push_str(&format!("max_bounces={}\n", request.max_bounces));
    }
    // And only with more than one light sample per vertex.
    if request.light_samples != 1 {
        description.push_str(&format!("light_samples={}\n", request.light_samples));
    }
    // And only for a jitter phase's reference (the pixel centres' keys stay as they were).
    if let Some(phase) = request.jitter_phase {
        description.push_str(&format!("jitter_phase={phase}\n"));
    }
    Ok(ReferenceKey {
        hash: Fnv64::of(description.as_bytes()),
        description,
    })
}

/// Hash of the scene's source: a built-in scene's content (so a changed generator gets
/// new references; keyed by name alone, a cache once served a city's old references to
/// its new lights), or the bytes of the file and of the external files a .gltf refers to.
fn scene_fingerprint(spec: &str) -> anyhow::Result<u64> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        let scene = crate::scene::builtin::builtin_scene(name)
            .with_context(|| format!("{spec}: cannot build the scene to key its reference"))?;
        return Ok(scene_content_hash(&scene));
    }
    let path = Path::new(spec);
    let bytes = std::fs::read(path)
        .with_context(|| format!("{spec}: cannot read the scene to key its reference"))?;
    let mut h = Fnv64::default();
    h.write(&bytes);
    let is_gltf = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf"));
    if is_gltf {
        let dir = path.parent().unwrap_or(Path::new("."));
        for uri in external_uris(&bytes) {
            h.write(uri.as_bytes());
            // A missing file makes the scene fail to load anyway; key it by name only.
            if let Ok(data) = std::fs::read(dir.join(percent_decode(&uri))) {
                h.write(&data);
            }
        }
    }
    Ok(h.finish())
}

/// Hash of everything a scene renders from: its name, vertices, triangles, materials,
/// textures, punctual lights, camera and animation (floats by their bits).
pub fn scene_content_hash(scene: &crate::Scene) -> u64 {
    let mut h = Fnv64::default();
    h.write(scene.name.as_bytes());
    for v in &scene.vertices {
        for x in [v.position.to_array(), v.normal.to_array()].concat() {
            h.write(&x.to_bits().to_le_bytes());
        }
        for x in v.uv.to_array() {
            h.write(&x.to_bits().to_le_bytes());
        }
    }
    for t in &scene.triangles {
        for i in t.indices {
            h.write(&i.to_le_bytes());
        }
        h.write(&t.material.to_le_bytes());
    }
    for texture in &scene.textures {
        h.write(format!("{}:{}x{}", texture.name, texture.width, texture.height).as_bytes());
        h.write(texture.texels.as_flattened());
    }
    // Debug prints every float exactly (shortest round-trip form).
    h.write(format!("{:?}", scene.materials).as_bytes());
    h.write(format!("{:?}", scene.punctual_lights).as_bytes());
    h.write(format!("{:?}", scene.camera).as_bytes());
    h.write(format!("{:?}", scene.animation).as_bytes());
    h.finish()
}

/// The non-`data:` URIs of a .gltf's buffers and images, in file order.
fn external_uris(gltf_json: &[u8]) -> Vec<String> {
    let Ok(doc) = serde_json::from_slice::<serde_json::Value>(gltf_json) else {
        return Vec::new();
    };
    ["buffers", "images"]
        .iter()
        .filter_map(|list| doc.get(list)?.as_array())
        .flatten()
        .filter_map(|item| item.get("uri")?.as_str())
        .filter(|uri| !uri.starts_with("data:"))
        .map(str::to_string)
        .collect()
}

/// `%XX` escapes as glTF URIs use them (UTF-8 bytes); anything malformed is kept as is.
fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = (bytes[i] == b'%')
            .then(|| std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok())
            .flatten()
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match hex {
            Some(b) => {
                out.push(b);
                i += 3;
            }
            None => {
                out.push(bytes[i]);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_matches_the_published_test_vectors() {
        assert_eq!(Fnv64::of(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(Fnv64::of(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(Fnv64::of(b"foobar"), 0x8594_4171_f739_67e8);
    }

    /// A built-in scene is keyed by what it holds: the same scene twice hashes alike, a
    /// light moved by a millimetre or a changed emission does not.
    #[test]
    fn a_builtin_scene_is_keyed_by_its_content() {
        let scene = crate::scene::builtin::builtin_scene("city:64").unwrap();
        let base = scene_content_hash(&scene);
        assert_eq!(
            base,
            scene_content_hash(&crate::scene::builtin::builtin_scene("city:64").unwrap())
        );
        assert_eq!(base, scene_fingerprint("builtin:city:64").unwrap());
        let mut moved = scene.clone();
        let last = moved.vertices.len() - 1;
        moved.vertices[last].position.x += 1e-3;
        assert_ne!(base, scene_content_hash(&moved));
        let mut brighter = scene.clone();
        let m = brighter
            .materials
            .iter()
            .position(|m| m.is_emissive())
            .unwrap();
        brighter.materials[m].emission *= 1.01;
        assert_ne!(base, scene_content_hash(&brighter));
        assert_ne!(base, scene_fingerprint("builtin:city:65").unwrap());
    }

    #[test]
    fn gltf_uris_are_found_and_decoded() {
        let json = br#"{"buffers":[{"uri":"a%20b.bin"},{"uri":"data:application/octet-stream;base64,AA=="}],
                        "images":[{"uri":"tex.png"},{"bufferView":0}]}"#;
        assert_eq!(external_uris(json), vec!["a%20b.bin", "tex.png"]);
        assert_eq!(percent_decode("a%20b.bin"), "a b.bin");
        assert_eq!(percent_decode("100%"), "100%");
        assert_eq!(percent_decode("%zz"), "%zz");
    }
}
