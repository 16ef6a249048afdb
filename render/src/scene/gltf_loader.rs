//! glTF 2.0 → `Scene`: .gltf (external or data-URI buffers) and .glb, flattened to world
//! space. Bad files give a `SceneError` naming the file; the gltf crate's own panics are
//! caught as a second line of defence (a malformed file must never crash the viewer).

mod animations;
mod compressed;
mod data;
mod draco;
pub mod extensions;
mod ktx2;
mod materials;
mod meshopt;
mod parse;
mod pointer_channels;
mod primitives;
mod quantized;
mod sources;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use glam::{Mat4, Vec3};
use gltf::khr_lights_punctual::Kind;

use super::animation::{CameraBinding, MeshBinding};
use super::validate::{SceneError, one_line, validate};
use super::{Camera, Material, PunctualKind, PunctualLight, Scene};
use crate::load_phases::{LoadPhases, Watcher, unwatched};
use parse::{Parsed, open_document};
use primitives::append_primitive;
use sources::{PrimitiveId, Sources};

/// Load a .gltf or .glb file. The returned scene has passed `validate::validate`.
pub fn load_gltf(path: &Path) -> Result<Scene, SceneError> {
    load_gltf_watched(path, &unwatched)
}

/// As `load_gltf`, timing each phase (in the scene's `load_phases`) and telling `watch`.
pub fn load_gltf_watched(path: &Path, watch: Watcher) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let mut phases = LoadPhases::default();
    let loaded = catch_unwind(AssertUnwindSafe(|| {
        load_unvalidated(path, &file, &mut phases, watch)
    }));
    let mut scene = match loaded {
        Ok(result) => result?,
        Err(payload) => {
            let detail = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            return Err(SceneError::Panicked {
                file,
                detail: one_line(detail),
            });
        }
    };
    phases.try_time(watch, "validate", || {
        validate(&mut scene, &file).map(|()| ((), String::new()))
    })?;
    scene.load_phases = phases;
    Ok(scene)
}

fn load_unvalidated(
    path: &Path,
    file: &str,
    phases: &mut LoadPhases,
    watch: Watcher,
) -> Result<Scene, SceneError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if !matches!(extension.as_deref(), Some("gltf" | "glb")) {
        return Err(SceneError::Unsupported {
            file: file.to_string(),
            detail: "expected a .gltf or .glb file".to_string(),
        });
    }
    let parsed = phases.try_time(watch, "read and parse", || {
        let bytes = std::fs::read(path).map_err(|source| SceneError::Io {
            file: file.to_string(),
            what: "the file".to_string(),
            error: source,
        })?;
        let parsed = open_document(file, &bytes)?;
        Ok((parsed, format!("{} bytes", bytes.len())))
    })?;
    let Parsed {
        gltf: gltf::Gltf { document, blob },
        pointers,
        extensions,
        compression,
    } = parsed;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = phases.try_time(watch, "buffers", || {
        let fallback = &compression.fallback;
        let mut buffers = data::load_buffers(file, &document, base, blob, fallback)?;
        // meshopt views decode into their buffers here; from now on they read as plain data.
        let decoded = meshopt::decode_views(file, &compression.meshopt, fallback, &mut buffers)?;
        let bytes: usize = buffers.iter().map(Vec::len).sum();
        let mut detail = format!("{} buffers, {bytes} bytes", buffers.len());
        if !compression.meshopt.is_empty() {
            let views = compression.meshopt.len();
            detail += &format!(" ({decoded} decoded from {views} meshopt views)");
        }
        Ok((buffers, detail))
    })?;
    let materials = materials::load_materials(file, &document);
    let textures = phases.try_time(watch, "images", || {
        let images = &compression.images;
        materials::load_textures(file, &document, base, &buffers, &materials, images, watch)
    })?;

    let mut scene = Scene {
        name: path
            .file_name()
            .map_or_else(|| file.to_string(), |n| n.to_string_lossy().into_owned()),
        materials,
        textures,
        extensions,
        ..Scene::default()
    };
    phases.try_time(watch, "geometry", || {
        let mut walker = Walker {
            file,
            sources: Sources {
                doc: &document,
                buffers: &buffers,
                compression: &compression,
                draco: Default::default(),
            },
            scene: &mut scene,
            default_material: None,
            moving: animations::moving_nodes(&document),
            records: animations::Records::default(),
        };
        walker.walk(&document)?;
        let records = std::mem::take(&mut walker.records);
        warn_rest_pose_only(file, &document);
        scene.animation = animations::build(file, &document, &buffers, &pointers, records, &scene)?;
        let detail = format!(
            "{} triangles, {} vertices",
            scene.triangles.len(),
            scene.vertices.len()
        );
        Ok(((), detail))
    })?;
    Ok(scene)
}

/// Skins and morph targets are shown in their rest pose (one warning says so).
fn warn_rest_pose_only(file: &str, doc: &gltf::Document) {
    let skins = doc.skins().len();
    let morphs = doc
        .meshes()
        .flat_map(|m| m.primitives().collect::<Vec<_>>())
        .filter(|p| p.morph_targets().len() > 0)
        .count();
    if skins > 0 || morphs > 0 {
        log::warn!(
            "{file}: {skins} skin(s) and {morphs} primitive(s) with morph targets are shown in \
             their rest pose (skinning and morphing are not implemented)"
        );
    }
}

/// Depth-first traversal of the scene's node trees, carrying world transforms.
struct Walker<'a> {
    file: &'a str,
    sources: Sources<'a>,
    scene: &'a mut Scene,
    /// Index of `Material::default()` in the scene, added the first time a primitive has none.
    default_material: Option<u32>,
    /// Per node: whether it (or an ancestor) is animated, so its geometry must be re-posed.
    moving: Vec<bool>,
    records: animations::Records,
}

impl Walker<'_> {
    fn walk(&mut self, doc: &gltf::Document) -> Result<(), SceneError> {
        let roots: Vec<gltf::Node> = match doc.default_scene().or_else(|| doc.scenes().next()) {
            Some(s) => s.nodes().collect(),
            None => {
                // No scene at all: show every root node rather than nothing.
                let mut is_child = vec![false; doc.nodes().len()];
                doc.nodes()
                    .flat_map(|n| n.children())
                    .for_each(|c| is_child[c.index()] = true);
                doc.nodes().filter(|n| !is_child[n.index()]).collect()
            }
        };
        // An explicit stack (children pushed in reverse) keeps the file's depth-first order
        // and cannot overflow the call stack on deep or cyclic hierarchies.
        let mut visited = vec![false; doc.nodes().len()];
        let mut stack: Vec<(gltf::Node, Mat4)> = roots
            .into_iter()
            .rev()
            .map(|n| (n, Mat4::IDENTITY))
            .collect();
        while let Some((node, parent)) = stack.pop() {
            if std::mem::replace(&mut visited[node.index()], true) {
                return Err(SceneError::invalid(
                    self.file,
                    format!(
                        "node {} is reached twice (a cycle or a shared child)",
                        node.index()
                    ),
                ));
            }
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            self.visit(&node, world)?;
            let children: Vec<gltf::Node> = node.children().collect();
            stack.extend(children.into_iter().rev().map(|c| (c, world)));
        }
        Ok(())
    }

    fn visit(&mut self, node: &gltf::Node, world: Mat4) -> Result<(), SceneError> {
        if let Some(mesh) = node.mesh() {
            for (index, primitive) in mesh.primitives().enumerate() {
                let material = match primitive.material().index() {
                    Some(i) => i as u32,
                    None => self.default_material(),
                };
                let id = PrimitiveId { mesh: &mesh, index };
                let first = self.scene.vertices.len() as u32;
                let local = append_primitive(
                    self.file,
                    &id,
                    &primitive,
                    &mut self.sources,
                    world,
                    material,
                    self.scene,
                )?;
                if self.moving[node.index()] {
                    self.records.meshes.push(MeshBinding {
                        node: node.index(),
                        first,
                        local,
                        materials: Vec::new(),
                    });
                    self.scene.mesh_transforms.push(world);
                }
            }
        }
        let yfov = node.camera().and_then(|c| match c.projection() {
            gltf::camera::Projection::Perspective(p) => Some(p.yfov()),
            gltf::camera::Projection::Orthographic(_) => None,
        });
        if let (None, Some(yfov)) = (self.scene.camera, yfov) {
            // Scale is dropped: a camera's rotation must stay orthonormal.
            let (_, rotation, position) = world.to_scale_rotation_translation();
            self.scene.camera = Some(Camera {
                position,
                rotation: rotation.normalize(),
                yfov,
            });
            if self.moving[node.index()] {
                self.records.camera = Some(CameraBinding {
                    node: node.index(),
                    yfov,
                });
            }
        }
        if let Some(light) = node.light() {
            self.records.lights.push((
                self.scene.punctual_lights.len(),
                light.index(),
                node.index(),
            ));
            self.scene
                .punctual_lights
                .push(punctual_light(&light, world));
        }
        Ok(())
    }

    fn default_material(&mut self) -> u32 {
        *self.default_material.get_or_insert_with(|| {
            self.scene.materials.push(Material::default());
            (self.scene.materials.len() - 1) as u32
        })
    }
}

/// KHR_lights_punctual: lights sit at the node's origin and point down its local -Z.
fn punctual_light(light: &gltf::khr_lights_punctual::Light, world: Mat4) -> PunctualLight {
    let kind = match light.kind() {
        Kind::Point => PunctualKind::Point,
        Kind::Directional => PunctualKind::Directional,
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => PunctualKind::Spot {
            inner_cone: inner_cone_angle,
            outer_cone: outer_cone_angle,
        },
    };
    PunctualLight {
        kind,
        position: world.transform_point3(Vec3::ZERO),
        direction: world
            .transform_vector3(Vec3::NEG_Z)
            .normalize_or(Vec3::NEG_Z),
        intensity: Vec3::from_array(light.color()) * light.intensity(),
        range: light.range(),
    }
}
