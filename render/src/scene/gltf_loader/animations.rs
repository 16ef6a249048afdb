//! glTF animations → `SceneAnimation`: the node tree, node TRS channels (through the gltf
//! crate's reader) and KHR_animation_pointer channels (taken from the raw JSON, see
//! `pointer_channels`), bound to what the walker recorded for moving nodes.

use glam::{Quat, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::animation::Property;

use super::data::check_accessor;
use super::pointer_channels::{PointerChannel, PointerTarget};
use crate::scene::Scene;
use crate::scene::animation::{
    CameraBinding, Channel, Clip, Hierarchy, Interpolation, Keyframes, Local, MaterialBinding,
    MeshBinding, Node, PunctualBinding, SceneAnimation, Target, Track, Trs,
};
use crate::scene::validate::SceneError;

/// What the walker saw on moving nodes (and every punctual light instance).
#[derive(Default)]
pub(super) struct Records {
    pub meshes: Vec<MeshBinding>,
    /// (index in `Scene::punctual_lights`, KHR light definition, node)
    pub lights: Vec<(usize, usize, usize)>,
    pub camera: Option<CameraBinding>,
}

/// Per node: whether a TRS channel targets it or one of its ancestors.
pub(super) fn moving_nodes(doc: &gltf::Document) -> Vec<bool> {
    let n = doc.nodes().len();
    let mut animated = vec![false; n];
    for channel in doc
        .animations()
        .flat_map(|a| a.channels().collect::<Vec<_>>())
    {
        let target = channel.target();
        if target.property() != Property::MorphTargetWeights {
            animated[target.node().index()] = true;
        }
    }
    let mut parent = vec![None; n];
    for node in doc.nodes() {
        for child in node.children() {
            parent[child.index()] = Some(node.index());
        }
    }
    (0..n)
        .map(|i| {
            let (mut at, mut steps) = (Some(i), 0);
            while let Some(j) = at.filter(|_| steps <= n) {
                if animated[j] {
                    return true;
                }
                at = parent[j];
                steps += 1;
            }
            false
        })
        .collect()
}

fn interpolation(i: gltf::animation::Interpolation) -> Interpolation {
    match i {
        gltf::animation::Interpolation::Linear => Interpolation::Linear,
        gltf::animation::Interpolation::Step => Interpolation::Step,
        gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
    }
}

struct Reader<'a> {
    file: &'a str,
    buffers: &'a [Vec<u8>],
}

impl Reader<'_> {
    fn floats<T: gltf::accessor::Item>(
        &self,
        accessor: gltf::Accessor,
        what: &str,
        dims: Dimensions,
    ) -> Result<Vec<T>, SceneError> {
        check_accessor(
            self.file,
            &accessor,
            self.buffers,
            what,
            &[DataType::F32],
            dims,
        )?;
        let iter = gltf::accessor::Iter::<T>::new(accessor, |b| {
            self.buffers.get(b.index()).map(Vec::as_slice)
        })
        .ok_or_else(|| SceneError::invalid(self.file, format!("{what} is unreadable")))?;
        Ok(iter.collect())
    }

    fn track(
        &self,
        sampler: &gltf::animation::Sampler,
        what: &str,
        kind: Dimensions,
        is_rotation: bool,
    ) -> Result<Track, SceneError> {
        let times: Vec<f32> = self.floats(
            sampler.input(),
            &format!("{what} input"),
            Dimensions::Scalar,
        )?;
        let i = interpolation(sampler.interpolation());
        let output = sampler.output();
        let out_what = format!("{what} output");
        let bad = |e: crate::scene::animation::TrackError| {
            SceneError::invalid(self.file, format!("{what}: {e}"))
        };
        Ok(match kind {
            Dimensions::Scalar => {
                let v = self.floats::<f32>(output, &out_what, kind)?;
                Track::Scalar(Keyframes::new(times, v, i).map_err(bad)?)
            }
            Dimensions::Vec4 if is_rotation => {
                let v = self.rotations(output, &out_what)?;
                Track::Quat(Keyframes::new(times, v, i).map_err(bad)?)
            }
            _ => {
                let v = self.floats::<[f32; 3]>(output, &out_what, Dimensions::Vec3)?;
                let v = v.into_iter().map(Vec3::from_array).collect();
                Track::Vec3(Keyframes::new(times, v, i).map_err(bad)?)
            }
        })
    }

    /// Rotations may be floats or normalised integers (glTF §3.11.1).
    fn rotations(&self, accessor: gltf::Accessor, what: &str) -> Result<Vec<Quat>, SceneError> {
        use DataType::*;
        check_accessor(
            self.file,
            &accessor,
            self.buffers,
            what,
            &[F32, I8, U8, I16, U16],
            Dimensions::Vec4,
        )?;
        let data = accessor.data_type();
        let get = |b: gltf::Buffer| self.buffers.get(b.index()).map(Vec::as_slice);
        let unreadable = || SceneError::invalid(self.file, format!("{what} is unreadable"));
        let quats: Vec<[f32; 4]> = match data {
            F32 => gltf::accessor::Iter::<[f32; 4]>::new(accessor, get)
                .ok_or_else(unreadable)?
                .collect(),
            I8 => norm(
                gltf::accessor::Iter::<[i8; 4]>::new(accessor, get).ok_or_else(unreadable)?,
                |x| (x as f32 / 127.0).max(-1.0),
            ),
            U8 => norm(
                gltf::accessor::Iter::<[u8; 4]>::new(accessor, get).ok_or_else(unreadable)?,
                |x| x as f32 / 255.0,
            ),
            I16 => norm(
                gltf::accessor::Iter::<[i16; 4]>::new(accessor, get).ok_or_else(unreadable)?,
                |x| (x as f32 / 32767.0).max(-1.0),
            ),
            _ => norm(
                gltf::accessor::Iter::<[u16; 4]>::new(accessor, get).ok_or_else(unreadable)?,
                |x| x as f32 / 65535.0,
            ),
        };
        Ok(quats.into_iter().map(Quat::from_array).collect())
    }
}

fn norm<T: Copy>(iter: impl Iterator<Item = [T; 4]>, f: impl Fn(T) -> f32) -> Vec<[f32; 4]> {
    iter.map(|q| q.map(&f)).collect()
}

/// The scene's animation, or `None` when the file has none.
pub(super) fn build(
    file: &str,
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    pointers: &[PointerChannel],
    records: Records,
    scene: &Scene,
) -> Result<Option<SceneAnimation>, SceneError> {
    if doc.animations().len() == 0 {
        return Ok(None);
    }
    let reader = Reader { file, buffers };
    let mut parent = vec![None; doc.nodes().len()];
    for node in doc.nodes() {
        for child in node.children() {
            parent[child.index()] = Some(node.index());
        }
    }
    let nodes = doc
        .nodes()
        .map(|node| Node {
            name: node.name().unwrap_or_default().to_string(),
            parent: parent[node.index()],
            rest: match node.transform() {
                gltf::scene::Transform::Matrix { matrix } => {
                    Local::Matrix(glam::Mat4::from_cols_array_2d(&matrix))
                }
                gltf::scene::Transform::Decomposed {
                    translation,
                    rotation,
                    scale,
                } => Local::Trs(Trs {
                    translation: Vec3::from_array(translation),
                    rotation: Quat::from_array(rotation).normalize(),
                    scale: Vec3::from_array(scale),
                }),
            },
        })
        .collect();
    let nodes = Hierarchy::new(nodes).map_err(|e| SceneError::invalid(file, e))?;

    let mut anim = SceneAnimation {
        nodes,
        meshes: records.meshes,
        camera: records.camera,
        ..SceneAnimation::default()
    };
    let moving = moving_nodes(doc);
    let animated_light = |l: usize| {
        pointers.iter().any(|p| {
            matches!(p.target, PointerTarget::LightColor(x) | PointerTarget::LightIntensity(x) if x == l)
        })
    };
    let definitions: Vec<_> = doc
        .lights()
        .map(|lights| lights.collect::<Vec<_>>())
        .unwrap_or_default();
    for &(scene_light, definition, node) in &records.lights {
        if moving[node] || animated_light(definition) {
            let light = &definitions[definition];
            anim.punctual.push(PunctualBinding {
                light: scene_light,
                node: moving[node].then_some(node),
                color: Vec3::from_array(light.color()),
                intensity: light.intensity(),
            });
        }
    }
    let light_definition_of: Vec<usize> = anim
        .punctual
        .iter()
        .map(|b| {
            records
                .lights
                .iter()
                .find(|r| r.0 == b.light)
                .map_or(usize::MAX, |r| r.1)
        })
        .collect();

    let mut warned_weights = false;
    for (a, animation) in doc.animations().enumerate() {
        let mut channels = Vec::new();
        for (c, channel) in animation.channels().enumerate() {
            let what = format!("animations[{a}].channels[{c}]");
            let target = channel.target();
            let node = target.node().index();
            if anim.nodes.rest_trs(node).is_none() {
                return Err(SceneError::invalid(
                    file,
                    format!("{what} animates node {node}, which has a matrix (glTF forbids it)"),
                ));
            }
            let (target, dims, rotation) = match target.property() {
                Property::Translation => (Target::Translation(node), Dimensions::Vec3, false),
                Property::Rotation => (Target::Rotation(node), Dimensions::Vec4, true),
                Property::Scale => (Target::Scale(node), Dimensions::Vec3, false),
                Property::MorphTargetWeights => {
                    if !std::mem::replace(&mut warned_weights, true) {
                        log::warn!("{file}: morph target weights are not animated (rest pose)");
                    }
                    continue;
                }
            };
            let track = reader.track(&channel.sampler(), &what, dims, rotation)?;
            channels.push(Channel { target, track });
        }
        for (p, pointer) in pointers.iter().filter(|p| p.animation == a).enumerate() {
            let what = format!("animations[{a}] pointer channel {p}");
            let sampler = animation.samplers().nth(pointer.sampler).ok_or_else(|| {
                SceneError::invalid(file, format!("{what}: no sampler {}", pointer.sampler))
            })?;
            let mut material_binding = |m: usize| -> Result<usize, SceneError> {
                let material = doc
                    .materials()
                    .nth(m)
                    .ok_or_else(|| SceneError::invalid(file, format!("{what}: no material {m}")))?;
                if let Some(i) = anim.materials.iter().position(|b| b.material == m) {
                    return Ok(i);
                }
                anim.materials.push(MaterialBinding {
                    material: m,
                    emissive_factor: Vec3::from_array(material.emissive_factor()),
                    emissive_strength: material.emissive_strength().unwrap_or(1.0),
                });
                Ok(anim.materials.len() - 1)
            };
            let (targets, dims): (Vec<Target>, Dimensions) = match pointer.target {
                PointerTarget::EmissiveFactor(m) => (
                    vec![Target::EmissiveFactor(material_binding(m)?)],
                    Dimensions::Vec3,
                ),
                PointerTarget::EmissiveStrength(m) => (
                    vec![Target::EmissiveStrength(material_binding(m)?)],
                    Dimensions::Scalar,
                ),
                PointerTarget::LightColor(l) | PointerTarget::LightIntensity(l) => {
                    if l >= definitions.len() {
                        return Err(SceneError::invalid(file, format!("{what}: no light {l}")));
                    }
                    // One definition may be instanced on several nodes: drive every instance.
                    let bindings =
                        (0..anim.punctual.len()).filter(|&b| light_definition_of[b] == l);
                    match pointer.target {
                        PointerTarget::LightColor(_) => {
                            (bindings.map(Target::LightColor).collect(), Dimensions::Vec3)
                        }
                        _ => (
                            bindings.map(Target::LightIntensity).collect(),
                            Dimensions::Scalar,
                        ),
                    }
                }
            };
            let track = reader.track(&sampler, &what, dims, false)?;
            channels.extend(targets.into_iter().map(|target| Channel {
                target,
                track: track.clone(),
            }));
        }
        anim.clips.push(Clip {
            name: animation
                .name()
                .map_or_else(|| format!("animation {a}"), str::to_string),
            channels,
        });
    }
    anim.bind_materials(&scene.triangles);
    Ok(Some(anim))
}
