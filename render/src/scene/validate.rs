//! The checks every loaded scene passes before anyone uploads it (a NaN position or an index
//! out of range would otherwise turn into a GPU fault or a silently black image far from its
//! cause), and the one-line error every scene source reports.

use glam::{Vec2, Vec3};

use super::Scene;
use crate::gpu_types::{MAX_TEXTURE_SIDE, TEXEL_OFFSET_BITS};

/// Why a scene could not be loaded. `Display` is one line that starts with the file (as given)
/// or the built-in name, then says what is wrong, e.g.
/// `scene.gltf: buffer 0 ('scene.bin') is 120 bytes but accessor 3 needs 480`.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// A file (the glTF itself, a buffer or an image) could not be read.
    // The io error is part of the one-line message, not a `source()`: anyhow's `{:#}`
    // would print it a second time.
    #[error("{file}: cannot read {what}: {error}")]
    Io {
        file: String,
        what: String,
        error: std::io::Error,
    },
    /// Not parseable as glTF: bad JSON, bad GLB framing, or the glTF schema check failed.
    #[error("{file}: not valid glTF: {detail}")]
    Parse { file: String, detail: String },
    /// Valid glTF that uses something this renderer does not handle (a required extension,
    /// point or line primitives, a file type other than .gltf/.glb).
    #[error("{file}: unsupported: {detail}")]
    Unsupported { file: String, detail: String },
    /// The content is wrong: data out of range, non-finite positions, no triangles, ...
    #[error("{file}: {detail}")]
    Invalid { file: String, detail: String },
    /// A texture image could not be read or decoded.
    #[error("{file}: image {image}: {detail}")]
    Image {
        file: String,
        image: String,
        detail: String,
    },
    /// An unknown built-in name or a bad built-in parameter.
    #[error("builtin:{name}: {detail}")]
    Builtin { name: String, detail: String },
    /// The glTF crate panicked on this input. Caught so a bad file never takes the viewer down.
    #[error("{file}: the glTF reader crashed on this file (it is probably malformed): {detail}")]
    Panicked { file: String, detail: String },
}

impl SceneError {
    pub(crate) fn invalid(file: &str, detail: impl Into<String>) -> Self {
        SceneError::Invalid {
            file: file.to_string(),
            detail: one_line(detail.into()),
        }
    }
}

/// Error text from other crates may span lines; the promise is one line per error.
pub(crate) fn one_line(text: impl Into<String>) -> String {
    text.into().replace(['\n', '\r'], " ")
}

/// Check what the renderer relies on and repair what is harmless to repair. Errors and
/// warnings start with `source` (the path as given, or the built-in name). Non-finite normals
/// become zero ("use the geometric normal") and non-finite UVs become 0, each with one warning.
pub(crate) fn validate(scene: &mut Scene, source: &str) -> Result<(), SceneError> {
    let file = source;
    if scene.triangles.is_empty() {
        return Err(SceneError::invalid(file, "0 triangles: nothing to render"));
    }
    if let Some(i) = scene.vertices.iter().position(|v| !v.position.is_finite()) {
        let p = scene.vertices[i].position;
        return Err(SceneError::invalid(
            file,
            format!("vertex {i} has a non-finite position {p}"),
        ));
    }
    repair_attributes(scene, file);
    check_references(scene, file)?;
    repair_emission(scene, file)
}

fn repair_attributes(scene: &mut Scene, file: &str) {
    let (mut normals, mut uvs) = (0usize, 0usize);
    for v in &mut scene.vertices {
        if !v.normal.is_finite() {
            v.normal = Vec3::ZERO;
            normals += 1;
        }
        if !v.uv.is_finite() {
            v.uv = Vec2::ZERO;
            uvs += 1;
        }
    }
    if normals > 0 {
        log::warn!("{file}: {normals} non-finite vertex normals replaced by the geometric normal");
    }
    if uvs > 0 {
        log::warn!("{file}: {uvs} non-finite texture coordinates set to 0");
    }
}

fn check_references(scene: &Scene, file: &str) -> Result<(), SceneError> {
    let vertex_count = scene.vertices.len();
    let material_count = scene.materials.len();
    for (t, tri) in scene.triangles.iter().enumerate() {
        if let Some(&i) = tri.indices.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(SceneError::invalid(
                file,
                format!("triangle {t} uses vertex {i} but there are {vertex_count} vertices"),
            ));
        }
        if tri.material as usize >= material_count {
            return Err(SceneError::invalid(
                file,
                format!(
                    "triangle {t} uses material {} but there are {material_count} materials",
                    tri.material
                ),
            ));
        }
    }
    let texture_count = scene.textures.len();
    for m in &scene.materials {
        if let Some(r) = m
            .texture_slots()
            .iter()
            .filter_map(|(_, r)| *r)
            .find(|r| r.texture as usize >= texture_count)
        {
            return Err(SceneError::invalid(
                file,
                format!(
                    "material '{}' uses texture {} but there are {texture_count} textures",
                    m.name, r.texture
                ),
            ));
        }
    }
    let mut texels = 0usize;
    for (i, t) in scene.textures.iter().enumerate() {
        if t.width == 0 || t.height == 0 || t.texels.len() != t.width as usize * t.height as usize {
            return Err(SceneError::invalid(
                file,
                format!("texture {i} ('{}') has inconsistent size", t.name),
            ));
        }
        // The GPU's texture record packs each side in 16 bits and the first texel in
        // TEXEL_OFFSET_BITS (gpu_types.rs).
        if t.width.max(t.height) > MAX_TEXTURE_SIDE {
            return Err(SceneError::invalid(
                file,
                format!(
                    "texture {i} ('{}') is {}×{}: sides up to {MAX_TEXTURE_SIDE} texels are supported",
                    t.name, t.width, t.height
                ),
            ));
        }
        texels += t.texels.len();
    }
    if texels > 1 << TEXEL_OFFSET_BITS {
        return Err(SceneError::invalid(
            file,
            format!(
                "the textures hold {texels} texels: up to {} (1 GiB) are supported",
                1u64 << TEXEL_OFFSET_BITS
            ),
        ));
    }
    for (i, l) in scene.punctual_lights.iter().enumerate() {
        if !(l.position.is_finite() && l.direction.is_finite() && l.intensity.is_finite()) {
            return Err(SceneError::invalid(
                file,
                format!("punctual light {i} has a non-finite position, direction or intensity"),
            ));
        }
    }
    Ok(())
}

/// Emission feeds the light-selection table: a NaN there poisons every pixel, so it is an
/// error; a negative value is meaningless and is clamped to 0.
fn repair_emission(scene: &mut Scene, file: &str) -> Result<(), SceneError> {
    for m in &mut scene.materials {
        if !m.emission.is_finite() {
            return Err(SceneError::invalid(
                file,
                format!(
                    "material '{}' has non-finite emission {}",
                    m.name, m.emission
                ),
            ));
        }
        if m.emission.min_element() < 0.0 {
            log::warn!(
                "{file}: material '{}' has negative emission {}; clamped to 0",
                m.name,
                m.emission
            );
            m.emission = m.emission.max(Vec3::ZERO);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Material, Triangle, Vertex};

    fn one_triangle() -> Scene {
        let v = |x: f32, y: f32| Vertex {
            position: Vec3::new(x, y, 0.0),
            normal: Vec3::Z,
            uv: Vec2::ZERO,
        };
        Scene {
            name: "test".into(),
            vertices: vec![v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)],
            triangles: vec![Triangle {
                indices: [0, 1, 2],
                material: 0,
            }],
            materials: vec![Material::default()],
            ..Scene::default()
        }
    }

    #[test]
    fn a_good_scene_passes_unchanged() {
        let mut s = one_triangle();
        validate(&mut s, "test.gltf").unwrap();
        assert_eq!(s.vertices[0].normal, Vec3::Z);
    }

    #[test]
    fn empty_scene_is_an_error_naming_the_file() {
        let mut s = one_triangle();
        s.triangles.clear();
        let e = validate(&mut s, "test.gltf").unwrap_err().to_string();
        assert!(e.starts_with("test.gltf: 0 triangles"), "{e}");
    }

    #[test]
    fn nan_position_is_an_error() {
        let mut s = one_triangle();
        s.vertices[1].position.y = f32::NAN;
        let e = validate(&mut s, "test.gltf").unwrap_err().to_string();
        assert!(e.contains("vertex 1") && e.contains("non-finite"), "{e}");
    }

    #[test]
    fn bad_normals_and_uvs_are_repaired() {
        let mut s = one_triangle();
        s.vertices[0].normal = Vec3::new(f32::INFINITY, 0.0, 0.0);
        s.vertices[2].uv = Vec2::new(0.5, f32::NAN);
        validate(&mut s, "test.gltf").unwrap();
        assert_eq!(s.vertices[0].normal, Vec3::ZERO);
        assert_eq!(s.vertices[2].uv, Vec2::ZERO);
    }

    /// The GPU texture record packs a side in 16 bits: a wider texture is refused in one
    /// line, not wrapped into another texture's texels.
    #[test]
    fn a_texture_wider_than_the_record_holds_is_an_error() {
        let texture = |width: u32| crate::scene::Texture {
            name: "wide".into(),
            width,
            height: 1,
            texels: vec![[0; 4]; width as usize],
            wrap_u: crate::scene::Wrap::Repeat,
            wrap_v: crate::scene::Wrap::Repeat,
        };
        let mut s = one_triangle();
        s.textures.push(texture(MAX_TEXTURE_SIDE));
        validate(&mut s, "test.gltf").unwrap();
        s.textures[0] = texture(MAX_TEXTURE_SIDE + 1);
        let e = validate(&mut s, "test.gltf").unwrap_err().to_string();
        assert!(e.contains("texture 0 ('wide') is 65536×1"), "{e}");
    }

    #[test]
    fn references_out_of_range_are_errors() {
        type Edit = fn(&mut Scene);
        let cases: [(Edit, &str); 3] = [
            (|s| s.triangles[0].indices[2] = 3, "vertex 3"),
            (|s| s.triangles[0].material = 1, "material 1"),
            (
                |s| s.materials[0].emissive_texture = Some(crate::scene::TextureRef::new(0)),
                "texture 0",
            ),
        ];
        for (edit, expected) in cases {
            let mut s = one_triangle();
            edit(&mut s);
            let e = validate(&mut s, "test.gltf").unwrap_err().to_string();
            assert!(e.contains(expected), "{e}");
        }
    }

    #[test]
    fn emission_is_checked() {
        let mut s = one_triangle();
        s.materials[0].emission = Vec3::new(1.0, -2.0, 0.0);
        validate(&mut s, "test.gltf").unwrap();
        assert_eq!(s.materials[0].emission, Vec3::new(1.0, 0.0, 0.0));
        s.materials[0].emission.x = f32::NAN;
        assert!(validate(&mut s, "test.gltf").is_err());
    }

    #[test]
    fn errors_are_one_line() {
        let e = SceneError::invalid("a.gltf", "two\nlines");
        assert_eq!(e.to_string(), "a.gltf: two lines");
    }
}
