//! `dynamic:*`: scenes that change with time, for ghosting and lag (docs/src/dynamic-scenes.md).
//! Their motion is expressed in the same `SceneAnimation` model glTF animations load into: moving
//! shapes are built in their node's space and posed at t = 0 before the scene is returned.

use std::f32::consts::TAU;

use glam::{Quat, Vec3};

use super::many_lights::{diffuse_floor, many_lights_room};
use super::shapes::{Facing, SceneBuilder};
use crate::scene::animation::{
    Channel, Clip, ClipChoice, Hierarchy, Interpolation, Keyframes, Local, MaterialBinding,
    MeshBinding, Node, SceneAnimation, Target, Track, Trs,
};
use crate::scene::{Camera, Material, Scene};

/// Collects nodes, moving meshes and channels while a scene is built.
#[derive(Default)]
pub(super) struct Motion {
    nodes: Vec<Node>,
    meshes: Vec<MeshBinding>,
    materials: Vec<MaterialBinding>,
    channels: Vec<Channel>,
}

impl Motion {
    pub(super) fn node(&mut self, parent: Option<usize>, trs: Trs) -> usize {
        self.nodes.push(Node {
            name: format!("node {}", self.nodes.len()),
            parent,
            rest: Local::Trs(trs),
        });
        self.nodes.len() - 1
    }

    /// Makes the vertices built since `first` belong to `node` (they were built in its space).
    pub(super) fn attach(&mut self, b: &SceneBuilder, node: usize, first: u32) {
        self.meshes.push(MeshBinding {
            node,
            first,
            local: b.vertices_since(first),
            materials: Vec::new(),
        });
    }

    pub(super) fn channel(&mut self, target: Target, track: Track) {
        self.channels.push(Channel { target, track });
    }

    /// Attaches the animation and poses the scene at t = 0.
    /// Switches material `m` of `scene` on (1) and off (0) at the keys `times` (STEP).
    pub(super) fn blink(&mut self, scene: &Scene, m: usize, times: Vec<f32>, on: Vec<f32>) {
        self.materials.push(MaterialBinding {
            material: m,
            emissive_factor: scene.materials[m].emission,
            emissive_strength: 1.0,
        });
        let binding = self.materials.len() - 1;
        let track = Keyframes::new(times, on, Interpolation::Step).expect("valid keys");
        self.channel(Target::EmissiveStrength(binding), Track::Scalar(track));
    }

    pub(super) fn finish(self, mut scene: Scene, clip: &str) -> Scene {
        let mut anim = SceneAnimation {
            nodes: Hierarchy::new(self.nodes).expect("built-in hierarchies are trees"),
            clips: vec![Clip {
                name: clip.to_string(),
                channels: self.channels,
            }],
            meshes: self.meshes,
            materials: self.materials,
            ..SceneAnimation::default()
        };
        anim.bind_materials(&scene.triangles);
        anim.pose(&mut scene, 0.0, ClipChoice::All);
        scene.animation = Some(anim);
        scene
    }
}

/// A full turn about +Y in `period` seconds starting at `phase` radians: five LINEAR keys a
/// quarter turn apart (slerp between them has constant angular speed).
fn spin_y(period: f32, phase: f32) -> Track {
    let times = (0..5).map(|k| k as f32 * period / 4.0).collect();
    let values = (0..5)
        .map(|k| Quat::from_rotation_y(phase + k as f32 * TAU / 4.0))
        .collect();
    Track::Quat(Keyframes::new(times, values, Interpolation::Linear).expect("valid keys"))
}

pub(super) fn linear_vec3(times: &[f32], values: &[Vec3]) -> Track {
    Track::Vec3(
        Keyframes::new(times.to_vec(), values.to_vec(), Interpolation::Linear).expect("valid keys"),
    )
}

/// A 10 × 10 m grey floor with a back wall, and a camera looking down at it.
fn stage(name: &str) -> (SceneBuilder, u32) {
    let mut b = SceneBuilder::new(name);
    let grey = b.material(Material::diffuse("floor", Vec3::splat(0.6)));
    b.rect(Vec3::ZERO, Vec3::Z * 5.0, Vec3::X * 5.0, grey);
    b.rect(
        Vec3::new(0.0, 2.5, -5.0),
        Vec3::X * 5.0,
        Vec3::Y * 2.5,
        grey,
    );
    (b, grey)
}

fn stage_camera() -> Camera {
    Camera::look_at(
        Vec3::new(0.0, 4.0, 6.5),
        Vec3::new(0.0, 0.0, -0.5),
        55f32.to_radians(),
    )
}

/// Seconds for one sweep of the moving light there and back.
pub const MOVING_LIGHT_PERIOD: f32 = 4.0;

/// One bright 0.5 m emitter sweeping x = −4 → 4 → −4 m at 1.5 m over the floor, past a
/// pillar, plus four dim fixed lights in the corners.
pub(super) fn moving_light(name: &str) -> Scene {
    let (mut b, grey) = stage(name);
    b.solid_box(
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.3, 1.0, 0.3),
        Quat::IDENTITY,
        grey,
    );
    let dim = b.material(Material::emitter("dim", Vec3::splat(2.0), false));
    for (x, z) in [(-4.0, -4.0), (4.0, -4.0), (-4.0, 4.0), (4.0, 4.0)] {
        b.rect(Vec3::new(x, 3.0, z), Vec3::X * 0.25, Vec3::Z * 0.25, dim);
    }
    let bright = b.material(Material::emitter("sweeping", Vec3::splat(60.0), false));
    let mut motion = Motion::default();
    let node = motion.node(None, Trs::default());
    let first = b.vertex_count();
    b.rect(Vec3::ZERO, Vec3::X * 0.25, Vec3::Z * 0.25, bright);
    motion.attach(&b, node, first);
    let half = MOVING_LIGHT_PERIOD / 2.0;
    let (left, right) = (Vec3::new(-4.0, 1.5, 1.5), Vec3::new(4.0, 1.5, 1.5));
    motion.channel(
        Target::Translation(node),
        linear_vec3(&[0.0, half, MOVING_LIGHT_PERIOD], &[left, right, left]),
    );
    motion.finish(b.finish(Some(stage_camera())), "sweep")
}

/// Lights in `blinking-lights`.
pub const BLINKING_LIGHT_COUNT: usize = 256;
/// The blinking set is off during [OFF_AT, ON_AT) of every BLINK_PERIOD seconds.
pub const BLINK_OFF_AT: f32 = 1.0;
pub const BLINK_ON_AT: f32 = 2.0;
pub const BLINK_PERIOD: f32 = 3.0;

/// The many-lights room (Lambertian) with 256 lights; the lights of every other palette
/// colour (about half) switch off at t = 1 s and back on at t = 2 s, every 3 s.
pub(super) fn blinking_lights(name: &str) -> Scene {
    let scene = many_lights_room(name, BLINKING_LIGHT_COUNT, diffuse_floor());
    let mut motion = Motion::default();
    let palette: Vec<usize> = (0..scene.materials.len())
        .filter(|&m| scene.materials[m].is_emissive())
        .collect();
    for &m in palette.iter().step_by(2) {
        motion.blink(
            &scene,
            m,
            vec![0.0, BLINK_OFF_AT, BLINK_ON_AT, BLINK_PERIOD],
            vec![1.0, 0.0, 1.0, 1.0],
        );
    }
    motion.finish(scene, "blink")
}

/// Seconds per turn of the blade in `moving-occluder`.
pub const BLADE_PERIOD: f32 = 4.0;

/// A 4 m blade turning about the vertical at 1 m over a floor lit by a 2 × 2 m ceiling
/// light: the floor behind and under it is uncovered every frame.
pub(super) fn moving_occluder(name: &str) -> Scene {
    let (mut b, _) = stage(name);
    let light = b.material(Material::emitter("ceiling", Vec3::splat(8.0), false));
    b.rect(Vec3::new(0.0, 4.0, 0.0), Vec3::X, Vec3::Z, light);
    let blade_material = b.material(Material::diffuse("blade", Vec3::new(0.7, 0.3, 0.2)));
    let mut motion = Motion::default();
    let hub = motion.node(
        None,
        Trs {
            translation: Vec3::new(0.0, 1.0, 0.0),
            ..Trs::default()
        },
    );
    let first = b.vertex_count();
    b.cuboid(
        Vec3::ZERO,
        Vec3::new(2.0, 0.05, 0.3),
        Quat::IDENTITY,
        Facing::Outward,
        [Some(blade_material); 6],
    );
    motion.attach(&b, hub, first);
    motion.channel(Target::Rotation(hub), spin_y(BLADE_PERIOD, 0.0));
    motion.finish(b.finish(Some(stage_camera())), "turn")
}

/// Radius and period of every light's orbit in `dynamic:many-lights`. 0.2 m is half the
/// room's 0.4 m light clearance, so no light ever comes near a surface.
pub const ORBIT_RADIUS: f32 = 0.2;
pub const ORBIT_PERIOD: f32 = 4.0;

/// The many-lights room (glossy floor) with every light orbiting its own centre.
pub(super) fn orbiting_lights(name: &str, n: usize) -> Scene {
    let scene = many_lights_room(name, n, super::many_lights::glossy_floor());
    let emissive: Vec<bool> = scene.materials.iter().map(|m| m.is_emissive()).collect();
    let mut motion = Motion::default();
    // Lights are quads (4 vertices, 2 triangles) appended after the room: find each by its
    // first triangle. The quad is re-expressed around an arm of the orbit.
    let mut k = 0usize;
    let mut t = 0;
    while t < scene.triangles.len() {
        let tri = scene.triangles[t];
        if !emissive[tri.material as usize] {
            t += 1;
            continue;
        }
        let first = tri.indices[0];
        let quad = &scene.vertices[first as usize..first as usize + 4];
        let center = quad.iter().map(|v| v.position).sum::<Vec3>() / 4.0;
        // The pivot is the light's built centre: the light circles it at ORBIT_RADIUS.
        let pivot = motion.node(
            None,
            Trs {
                translation: center,
                ..Trs::default()
            },
        );
        let arm = motion.node(
            Some(pivot),
            Trs {
                translation: Vec3::X * ORBIT_RADIUS,
                ..Trs::default()
            },
        );
        let local: Vec<_> = quad
            .iter()
            .map(|v| crate::scene::Vertex {
                position: v.position - center,
                ..*v
            })
            .collect();
        motion.meshes.push(MeshBinding {
            node: arm,
            first,
            local,
            materials: Vec::new(),
        });
        // Phases spread by the golden angle so neighbours do not move in lockstep.
        let phase = k as f32 * 2.399_963;
        motion.channel(Target::Rotation(pivot), spin_y(ORBIT_PERIOD, phase));
        k += 1;
        t += 2;
    }
    motion.finish(scene, "orbit")
}

#[cfg(test)]
mod tests {
    use super::super::{builtin_names, builtin_scene};
    use super::*;

    fn emitted(scene: &Scene) -> usize {
        scene.emissive_triangle_count()
    }

    #[test]
    fn dynamic_scenes_are_listed_under_their_exact_names() {
        let names = builtin_names();
        for name in [
            "builtin:dynamic:moving-light",
            "builtin:dynamic:blinking-lights",
            "builtin:dynamic:moving-occluder",
            "builtin:dynamic:many-lights",
        ] {
            assert!(names.iter().any(|n| n == name), "{name} missing");
        }
        let scene = builtin_scene("dynamic:many-lights:300").unwrap();
        assert_eq!(scene.name, "builtin:dynamic:many-lights:300");
        assert_eq!(scene.animation.unwrap().meshes.len(), 300);
        assert!(builtin_scene("dynamic:many-lights:0").is_err());
    }

    #[test]
    fn the_sweeping_light_passes_the_pillar() {
        let mut scene = builtin_scene("dynamic:moving-light").unwrap();
        let anim = scene.animation.clone().unwrap();
        assert_eq!(anim.duration(ClipChoice::All), MOVING_LIGHT_PERIOD);
        let centre = |s: &Scene| {
            let first = anim.meshes[0].first as usize;
            s.vertices[first..first + 4]
                .iter()
                .map(|v| v.position)
                .sum::<Vec3>()
                / 4.0
        };
        assert!((centre(&scene).x + 4.0).abs() < 1e-5);
        let change = anim.pose(&mut scene, MOVING_LIGHT_PERIOD / 4.0, ClipChoice::All);
        assert!(change.geometry && change.lights);
        assert!(centre(&scene).x.abs() < 1e-5, "{}", centre(&scene));
    }

    #[test]
    fn blinking_lights_go_off_at_1s_and_on_at_2s() {
        let mut scene = builtin_scene("dynamic:blinking-lights").unwrap();
        let anim = scene.animation.clone().unwrap();
        assert_eq!(
            anim.light_events(ClipChoice::All),
            vec![BLINK_OFF_AT, BLINK_ON_AT]
        );
        let all = emitted(&scene);
        assert_eq!(all, 2 * BLINKING_LIGHT_COUNT);
        anim.pose(&mut scene, 1.5, ClipChoice::All);
        let off = all - emitted(&scene);
        // Every other palette colour: roughly half the lights (colours are drawn at random).
        assert!(off > all / 4 && off < 3 * all / 4, "{off} of {all}");
        anim.pose(&mut scene, 2.0 + BLINK_PERIOD, ClipChoice::All);
        assert_eq!(emitted(&scene), all);
    }

    #[test]
    fn orbits_and_blades_keep_their_shape() {
        let mut scene = builtin_scene("dynamic:many-lights:50").unwrap();
        let anim = scene.animation.clone().unwrap();
        let area = |s: &Scene, t: usize| {
            let [a, b, c] = s.triangle_positions(t);
            (b - a).cross(c - a).length()
        };
        let before: Vec<f32> = (0..scene.triangles.len())
            .map(|t| area(&scene, t))
            .collect();
        let built = builtin_scene("many-lights:50").unwrap();
        anim.pose(&mut scene, 1.3, ClipChoice::All);
        for (t, a) in before.iter().enumerate() {
            assert!((area(&scene, t) - a).abs() < 1e-5 * a.max(1.0));
        }
        // Every light's centre is on its orbit: ORBIT_RADIUS from where the static room has it.
        let centre = |s: &Scene, first: u32| {
            let f = first as usize;
            s.vertices[f..f + 4]
                .iter()
                .map(|v| v.position)
                .sum::<Vec3>()
                / 4.0
        };
        for mesh in &anim.meshes {
            let d = (centre(&scene, mesh.first) - centre(&built, mesh.first)).length();
            assert!((d - ORBIT_RADIUS).abs() < 1e-4, "{d}");
        }
        let mut blade = builtin_scene("dynamic:moving-occluder").unwrap();
        let anim = blade.animation.clone().unwrap();
        let first = anim.meshes[0].first as usize;
        let tip = |s: &Scene| {
            s.vertices[first..]
                .iter()
                .map(|v| v.position.x)
                .fold(0f32, f32::max)
        };
        assert!((tip(&blade) - 2.0).abs() < 1e-5);
        // A quarter turn later the blade lies along z: its x extent is the 0.3 m half-width.
        anim.pose(&mut blade, BLADE_PERIOD / 4.0, ClipChoice::All);
        assert!((tip(&blade) - 0.3).abs() < 1e-4, "{}", tip(&blade));
    }
}
