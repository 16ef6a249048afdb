//! Scene time: what moves and changes in a scene, and posing the scene at a time t.
//!
//! A `Scene` stays a flat world-space triangle soup (what the BVH, the light table and the
//! shaders read). `SceneAnimation` keeps what is needed to re-pose it: the glTF node tree,
//! the vertex ranges that belong to moving nodes (in their node's local space), the lights,
//! materials and camera bound to nodes or animated, and the clips. `pose` evaluates every
//! channel at t and writes the results into the scene. All clips play together by
//! default, looping over the longest; one can be chosen instead (`ClipChoice`).

mod hierarchy;
mod keyframes;
mod pose;

#[cfg(test)]
mod tests;

pub use hierarchy::{Hierarchy, Local, Node, Trs};
pub use keyframes::{Animatable, Interpolation, Keyframes, TrackError, slerp_shortest};
pub use pose::SceneChange;

use glam::Vec3;

use super::Vertex;

/// The whole of a scene's dynamics.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneAnimation {
    pub nodes: Hierarchy,
    pub clips: Vec<Clip>,
    /// Vertex ranges of `Scene::vertices` owned by a node that moves.
    pub meshes: Vec<MeshBinding>,
    /// Punctual lights (index into `Scene::punctual_lights`) and what drives them.
    pub punctual: Vec<PunctualBinding>,
    /// Materials whose emission a channel animates.
    pub materials: Vec<MaterialBinding>,
    /// The node carrying the scene camera, when that node moves.
    pub camera: Option<CameraBinding>,
    /// The time of the last `pose` (references are keyed by it).
    pub posed_at: f32,
}

/// Vertices `first..first + local.len()` of the scene, stored in node `node`'s space.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshBinding {
    pub node: usize,
    pub first: u32,
    pub local: Vec<Vertex>,
    /// The materials of the triangles using these vertices (`bind_materials` fills it).
    pub materials: Vec<u32>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PunctualBinding {
    pub light: usize,
    /// The node the light sits on, when that node moves.
    pub node: Option<usize>,
    /// KHR_lights_punctual `color` and `intensity` at rest (the scene stores their product).
    pub color: Vec3,
    pub intensity: f32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialBinding {
    pub material: usize,
    /// `emissiveFactor` and `KHR_materials_emissive_strength` at rest.
    pub emissive_factor: Vec3,
    pub emissive_strength: f32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraBinding {
    pub node: usize,
    pub yfov: f32,
}

/// One glTF animation (or one built-in scene's motion).
#[derive(Clone, Debug, PartialEq)]
pub struct Clip {
    pub name: String,
    pub channels: Vec<Channel>,
}

impl Clip {
    /// The clip's length: its longest track (a clip of constant tracks has length 0).
    pub fn duration(&self) -> f32 {
        self.channels
            .iter()
            .map(|c| c.track.end_time())
            .fold(0.0, f32::max)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    pub target: Target,
    pub track: Track,
}

/// What a channel drives. Indices are into `SceneAnimation::nodes`, `::materials` and
/// `::punctual`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    Translation(usize),
    Rotation(usize),
    Scale(usize),
    EmissiveFactor(usize),
    EmissiveStrength(usize),
    LightColor(usize),
    LightIntensity(usize),
}

#[derive(Clone, Debug, PartialEq)]
pub enum Track {
    Vec3(Keyframes<Vec3>),
    Quat(Keyframes<glam::Quat>),
    Scalar(Keyframes<f32>),
}

impl Track {
    pub fn end_time(&self) -> f32 {
        match self {
            Track::Vec3(k) => k.end_time(),
            Track::Quat(k) => k.end_time(),
            Track::Scalar(k) => k.end_time(),
        }
    }
}

/// Which clips play.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ClipChoice {
    /// Every clip together, looping over the longest.
    #[default]
    All,
    /// One clip, looping over its own length.
    One(usize),
}

impl SceneAnimation {
    /// The loop length of what `choice` plays (0: nothing changes with time).
    pub fn duration(&self, choice: ClipChoice) -> f32 {
        self.playing(choice).map(Clip::duration).fold(0.0, f32::max)
    }

    fn playing(&self, choice: ClipChoice) -> impl Iterator<Item = &Clip> {
        self.clips.iter().enumerate().filter_map(move |(i, c)| {
            (choice == ClipChoice::All || choice == ClipChoice::One(i)).then_some(c)
        })
    }

    /// Scene time → clip time: wrapped into [0, duration) (a negative time wraps too).
    pub fn wrap(&self, time: f32, choice: ClipChoice) -> f32 {
        let duration = self.duration(choice);
        if duration > 0.0 && time.is_finite() {
            time.rem_euclid(duration)
        } else {
            0.0
        }
    }

    /// Clip times in [0, duration) at which a light switches (a STEP emission or light
    /// intensity/colour track changing value), sorted: the scene's own event list.
    pub fn light_events(&self, choice: ClipChoice) -> Vec<f32> {
        let mut events: Vec<f32> = self
            .playing(choice)
            .flat_map(|clip| &clip.channels)
            .filter(|c| {
                !matches!(
                    c.target,
                    Target::Translation(_) | Target::Rotation(_) | Target::Scale(_)
                )
            })
            .flat_map(|c| match &c.track {
                Track::Vec3(k) => k.step_changes().collect::<Vec<_>>(),
                Track::Scalar(k) => k.step_changes().collect(),
                Track::Quat(_) => Vec::new(),
            })
            .collect();
        events.sort_by(f32::total_cmp);
        events.dedup();
        events
    }

    /// For each triangle, the mesh binding whose vertices it uses (`None`: it never
    /// moves). A mesh's triangles use its own vertices only, so the first one tells; the
    /// bindings sorted by first vertex make this O(T log meshes) even for 65536 separately
    /// moving lights.
    pub fn triangle_bindings(&self, triangles: &[super::Triangle]) -> Vec<Option<usize>> {
        let mut by_first: Vec<usize> = (0..self.meshes.len()).collect();
        by_first.sort_by_key(|&m| self.meshes[m].first);
        triangles
            .iter()
            .map(|t| {
                let v = t.indices[0];
                let after = by_first.partition_point(|&m| self.meshes[m].first <= v);
                let m = *by_first.get(after.checked_sub(1)?)?;
                let mesh = &self.meshes[m];
                (v < mesh.first + mesh.local.len() as u32).then_some(m)
            })
            .collect()
    }

    /// Records which materials each moving mesh uses (once, after the triangles exist), so
    /// `pose` can tell cheaply whether a moving mesh is an emitter.
    pub fn bind_materials(&mut self, triangles: &[super::Triangle]) {
        let mut materials: Vec<Vec<u32>> = vec![Vec::new(); self.meshes.len()];
        for (t, binding) in triangles.iter().zip(self.triangle_bindings(triangles)) {
            if let Some(m) = binding {
                materials[m].push(t.material);
            }
        }
        for (mesh, mut used) in self.meshes.iter_mut().zip(materials) {
            used.sort_unstable();
            used.dedup();
            mesh.materials = used;
        }
    }

    /// True when nothing can change with time (no clip has a key after 0).
    pub fn is_static(&self) -> bool {
        self.clips.iter().all(|c| c.channels.is_empty())
    }
}
