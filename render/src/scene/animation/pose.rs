//! Posing: every playing channel evaluated at one time and written into the scene's flat
//! world-space data (vertices, material emission, punctual lights, camera).

use std::ops::Range;

use glam::{Mat3, Mat4, Vec3};

use super::{ClipChoice, Local, SceneAnimation, Target, Track, Trs};
use crate::scene::{Camera, Scene};

/// What `pose` changed, so the renderer rebuilds only what depends on it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SceneChange {
    /// Some vertex moved: triangles and the BVH need updating.
    pub geometry: bool,
    /// An emitter moved or a light's emission changed: light data needs updating.
    pub lights: bool,
    /// A light's emission changed (not only its place): its power, and with it the light
    /// table's probabilities, may differ. Rigid emitter motion leaves this false.
    pub emission: bool,
    /// The scene camera moved (it is used only where the user has not moved the camera).
    pub camera: bool,
    /// The vertex ranges `pose` moved (scene vertex indices), so an update can rewrite
    /// only their triangles and the tree above them. `None`: not known (a full upload, a
    /// change made by hand), every vertex may have moved.
    pub moved_vertices: Option<Vec<Range<u32>>>,
}

impl SceneChange {
    pub fn any(&self) -> bool {
        self.geometry || self.lights || self.camera
    }
}

/// Channel values at one time, before they are written into the scene.
struct Values {
    locals: Vec<Local>,
    emissive_factor: Vec<Vec3>,
    emissive_strength: Vec<f32>,
    light_color: Vec<Vec3>,
    light_intensity: Vec<f32>,
}

impl SceneAnimation {
    fn values_at(&self, time: f32, choice: ClipChoice) -> Values {
        let mut v = Values {
            locals: self.nodes.rest_locals(),
            emissive_factor: self.materials.iter().map(|m| m.emissive_factor).collect(),
            emissive_strength: self.materials.iter().map(|m| m.emissive_strength).collect(),
            light_color: self.punctual.iter().map(|p| p.color).collect(),
            light_intensity: self.punctual.iter().map(|p| p.intensity).collect(),
        };
        let t = self.wrap(time, choice);
        for clip in self.playing(choice) {
            for channel in &clip.channels {
                match (channel.target, &channel.track) {
                    (Target::Translation(n), Track::Vec3(k)) => {
                        if let Some(trs) = trs_mut(&mut v.locals, n) {
                            trs.translation = k.sample(t);
                        }
                    }
                    (Target::Scale(n), Track::Vec3(k)) => {
                        if let Some(trs) = trs_mut(&mut v.locals, n) {
                            trs.scale = k.sample(t);
                        }
                    }
                    (Target::Rotation(n), Track::Quat(k)) => {
                        if let Some(trs) = trs_mut(&mut v.locals, n) {
                            trs.rotation = k.sample(t);
                        }
                    }
                    (Target::EmissiveFactor(m), Track::Vec3(k)) => {
                        v.emissive_factor[m] = k.sample(t);
                    }
                    (Target::EmissiveStrength(m), Track::Scalar(k)) => {
                        v.emissive_strength[m] = k.sample(t);
                    }
                    (Target::LightColor(l), Track::Vec3(k)) => v.light_color[l] = k.sample(t),
                    (Target::LightIntensity(l), Track::Scalar(k)) => {
                        v.light_intensity[l] = k.sample(t);
                    }
                    // Import pairs every target with its track type; anything else is ignored.
                    _ => {}
                }
            }
        }
        v
    }

    /// World matrices of every node at `time` (for tests and the inspector).
    pub fn world_matrices(&self, time: f32, choice: ClipChoice) -> Vec<Mat4> {
        self.nodes
            .world_matrices(&self.values_at(time, choice).locals)
    }

    /// Writes the scene as it is at `time` and says what changed since its previous pose.
    pub fn pose(&self, scene: &mut Scene, time: f32, choice: ClipChoice) -> SceneChange {
        let values = self.values_at(time, choice);
        let world = self.nodes.world_matrices(&values.locals);
        let mut change = SceneChange {
            moved_vertices: Some(Vec::new()),
            ..SceneChange::default()
        };
        let emissive: Vec<bool> = scene.materials.iter().map(|m| m.is_emissive()).collect();

        scene.mesh_transforms.resize(self.meshes.len(), Mat4::NAN);
        for (mesh, transform) in self.meshes.iter().zip(&mut scene.mesh_transforms) {
            let m = world[mesh.node];
            // As for the vertices below: a degenerate pose keeps the last good placement.
            if m.is_finite() {
                *transform = m;
            }
            let normal_matrix = Mat3::from_mat4(m).inverse().transpose();
            let first = mesh.first as usize;
            let Some(range) = scene.vertices.get_mut(first..first + mesh.local.len()) else {
                continue; // validated at import; never trust an index into a Vec blindly
            };
            let mut moved = false;
            for (out, local) in range.iter_mut().zip(&mesh.local) {
                let position = m.transform_point3(local.position);
                // A degenerate pose (scale 0, NaN from bad data) must not reach the GPU:
                // such a vertex keeps its last good position.
                if !position.is_finite() {
                    continue;
                }
                let normal = (normal_matrix * local.normal).normalize_or_zero();
                moved |= out.position != position;
                out.position = position;
                if normal.is_finite() {
                    out.normal = normal;
                }
            }
            if moved {
                change.geometry = true;
                if let Some(ranges) = &mut change.moved_vertices {
                    ranges.push(mesh.first..mesh.first + mesh.local.len() as u32);
                }
            }
        }
        if change.geometry {
            // An emitter that moved changes the light table's geometry.
            change.lights |= self.meshes.iter().any(|mesh| {
                mesh.materials
                    .iter()
                    .any(|&m| emissive.get(m as usize).copied().unwrap_or(false))
            });
        }

        for (binding, (factor, strength)) in self
            .materials
            .iter()
            .zip(values.emissive_factor.iter().zip(&values.emissive_strength))
        {
            let emission = (*factor * *strength).max(Vec3::ZERO);
            let emission = if emission.is_finite() {
                emission
            } else {
                Vec3::ZERO
            };
            if let Some(material) = scene.materials.get_mut(binding.material)
                && material.emission != emission
            {
                material.emission = emission;
                change.lights = true;
                change.emission = true;
            }
        }

        for (i, binding) in self.punctual.iter().enumerate() {
            let Some(light) = scene.punctual_lights.get_mut(binding.light) else {
                continue;
            };
            let intensity = (values.light_color[i] * values.light_intensity[i]).max(Vec3::ZERO);
            let mut updated = *light;
            if intensity.is_finite() {
                updated.intensity = intensity;
            }
            if let Some(node) = binding.node {
                let position = world[node].transform_point3(Vec3::ZERO);
                let direction = world[node]
                    .transform_vector3(Vec3::NEG_Z)
                    .normalize_or_zero();
                if position.is_finite() && direction != Vec3::ZERO {
                    updated.position = position;
                    updated.direction = direction;
                }
            }
            if updated != *light {
                // Punctual power depends on intensity only (directional: also on the scene
                // size, which the renderer checks), so moving one is not an emission change.
                change.emission |= updated.intensity != light.intensity;
                *light = updated;
                change.lights = true;
            }
        }

        if let Some(binding) = self.camera {
            let (_, rotation, position) = world[binding.node].to_scale_rotation_translation();
            let camera = Camera {
                position,
                rotation: rotation.normalize(),
                yfov: binding.yfov,
            };
            if position.is_finite() && camera.rotation.is_finite() && scene.camera != Some(camera) {
                scene.camera = Some(camera);
                change.camera = true;
            }
        }
        change
    }
}

/// The local TRS of node `n`; `None` for a matrix node (not animatable: import refuses
/// channels on them) or an index out of range.
fn trs_mut(locals: &mut [Local], n: usize) -> Option<&mut Trs> {
    match locals.get_mut(n) {
        Some(Local::Trs(trs)) => Some(trs),
        _ => None,
    }
}
