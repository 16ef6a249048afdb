//! Animation sampling against values computed by hand from the glTF 2.0 formulas.

use std::f32::consts::{FRAC_PI_2, PI};

use glam::{Quat, Vec3};

use super::*;
use crate::scene::{Material, Scene, Triangle, Vertex};

const EPS: f32 = 1e-5;

fn scalar(times: &[f32], values: &[f32], i: Interpolation) -> Keyframes<f32> {
    Keyframes::new(times.to_vec(), values.to_vec(), i).unwrap()
}

#[test]
fn step_holds_the_previous_key_and_clamps_outside() {
    let k = scalar(&[0.0, 1.0, 2.0], &[0.0, 10.0, 20.0], Interpolation::Step);
    for (t, want) in [
        (-1.0, 0.0),
        (0.5, 0.0),
        (1.0, 10.0),
        (1.99, 10.0),
        (2.0, 20.0),
        (7.0, 20.0),
    ] {
        assert_eq!(k.sample(t), want, "t = {t}");
    }
    assert_eq!(k.step_changes().collect::<Vec<_>>(), vec![1.0, 2.0]);
}

#[test]
fn linear_interpolates_componentwise() {
    let k = Keyframes::new(
        vec![1.0, 3.0],
        vec![Vec3::ZERO, Vec3::new(2.0, 4.0, 6.0)],
        Interpolation::Linear,
    )
    .unwrap();
    // s = (1.5 − 1) / 2 = 0.25
    assert!((k.sample(1.5) - Vec3::new(0.5, 1.0, 1.5)).length() < EPS);
    assert_eq!(k.sample(0.0), Vec3::ZERO);
}

#[test]
fn cubic_spline_scales_tangents_by_the_key_interval() {
    // Keys at 0 s and 2 s (td = 2): (in 0, v 0, out 1) and (in 3, v 1, out 0).
    // At t = 1, s = ½: h = [½, ⅛·td, ½, −⅛·td] = [0.5, 0.25, 0.5, −0.25], so
    // p = 0.5·0 + 0.25·1 + 0.5·1 − 0.25·3 = 0. Unscaled tangents would give 0.25.
    let k = scalar(
        &[0.0, 2.0],
        &[0.0, 0.0, 1.0, 3.0, 1.0, 0.0],
        Interpolation::CubicSpline,
    );
    assert!(k.sample(1.0).abs() < EPS, "{}", k.sample(1.0));
    // At s = ¼ (t = 0.5): h0 = 27/32, h1 = 9/64·2, h2 = 5/32, h3 = −3/64·2.
    let want = 0.28125 * 1.0 + 0.15625 * 1.0 - 0.09375 * 3.0;
    assert!((k.sample(0.5) - want).abs() < EPS, "{}", k.sample(0.5));
    // The out-tangent is a slope in value per second: p(t) ≈ b0·t near the first key.
    assert!((k.sample(1e-3) - 1e-3).abs() < 1e-5);
    // Keys themselves are exact, tangents of the first in and last out are unused.
    assert_eq!(k.sample(0.0), 0.0);
    assert_eq!(k.sample(2.0), 1.0);
}

#[test]
fn rotation_slerp_takes_the_shortest_path() {
    let a = Quat::IDENTITY;
    // −q is the same 90° rotation; the long way round would pass through 135°.
    let b = -Quat::from_rotation_z(FRAC_PI_2);
    let k = Keyframes::new(vec![0.0, 1.0], vec![a, b], Interpolation::Linear).unwrap();
    let half = k.sample(0.5);
    assert!((half.length() - 1.0).abs() < EPS);
    assert!(half.angle_between(Quat::from_rotation_z(FRAC_PI_2 / 2.0)) < 1e-4);
    // Constant angular speed: a third of the way is 30°.
    let b = Quat::from_rotation_z(FRAC_PI_2);
    let third = slerp_shortest(a, b, 1.0 / 3.0);
    assert!(third.angle_between(Quat::from_rotation_z(PI / 6.0)) < 1e-4);
    // Nearly equal quaternions take the normalised-lerp branch and stay unit length.
    let near = slerp_shortest(a, Quat::from_rotation_x(1e-4), 0.5);
    assert!((near.length() - 1.0).abs() < EPS);
}

#[test]
fn cubic_spline_rotations_are_renormalised() {
    let q0 = Quat::IDENTITY;
    let q1 = Quat::from_rotation_y(FRAC_PI_2);
    let zero = Quat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    let k = Keyframes::new(
        vec![0.0, 1.0],
        vec![zero, q0, zero, zero, q1, zero],
        Interpolation::CubicSpline,
    )
    .unwrap();
    let mid = k.sample(0.5);
    assert!((mid.length() - 1.0).abs() < EPS);
    // Zero tangents and s = ½: the components are the plain average, then normalised.
    let avg = (glam::Vec4::from(q0) + glam::Vec4::from(q1)) * 0.5;
    assert!(
        mid.abs_diff_eq(Quat::from_vec4(avg.normalize()), 1e-5),
        "{mid}"
    );
}

#[test]
fn bad_tracks_are_errors_not_panics() {
    use Interpolation::*;
    assert_eq!(
        Keyframes::<f32>::new(vec![], vec![], Linear),
        Err(TrackError::Empty)
    );
    assert_eq!(
        Keyframes::new(vec![0.0, f32::NAN], vec![0.0, 1.0], Linear),
        Err(TrackError::NonFiniteTime(1))
    );
    assert_eq!(
        Keyframes::new(vec![0.0, 0.0], vec![0.0, 1.0], Step),
        Err(TrackError::NotIncreasing(1))
    );
    assert!(matches!(
        Keyframes::new(vec![0.0, 1.0], vec![0.0, 1.0], CubicSpline),
        Err(TrackError::CountMismatch { expected: 6, .. })
    ));
    assert_eq!(
        Keyframes::new(vec![0.0], vec![f32::INFINITY], Step),
        Err(TrackError::NonFiniteValue(0))
    );
    // One key: constant, whatever the interpolation; a NaN time samples the first key.
    let one = scalar(&[0.5], &[1.0, 2.0, 3.0], CubicSpline);
    assert_eq!(one.sample(10.0), 2.0);
    assert_eq!(one.sample(f32::NAN), 2.0);
}

fn trs_node(name: &str, parent: Option<usize>, translation: Vec3) -> Node {
    Node {
        name: name.into(),
        parent,
        rest: Local::Trs(Trs {
            translation,
            ..Trs::default()
        }),
    }
}

/// Node 0 is the child (listed first on purpose), node 1 its parent, rotating about Z
/// from 0 to 180° over 2 s.
fn rotating_parent() -> SceneAnimation {
    let nodes = Hierarchy::new(vec![
        trs_node("child", Some(1), Vec3::X),
        trs_node("parent", None, Vec3::X),
    ])
    .unwrap();
    let rotation = Keyframes::new(
        vec![0.0, 1.0, 2.0],
        vec![
            Quat::IDENTITY,
            Quat::from_rotation_z(FRAC_PI_2),
            Quat::from_rotation_z(PI),
        ],
        Interpolation::Linear,
    )
    .unwrap();
    SceneAnimation {
        nodes,
        clips: vec![Clip {
            name: "spin".into(),
            channels: vec![Channel {
                target: Target::Rotation(1),
                track: Track::Quat(rotation),
            }],
        }],
        ..SceneAnimation::default()
    }
}

#[test]
fn parent_chains_compose() {
    let anim = rotating_parent();
    // At 1 s the parent is at (1,0,0) turned 90°: the child's (1,0,0) becomes (0,1,0).
    let world = anim.world_matrices(1.0, ClipChoice::All);
    let child = world[0].transform_point3(Vec3::ZERO);
    assert!((child - Vec3::new(1.0, 1.0, 0.0)).length() < EPS, "{child}");
    // At 0.5 s: 45°.
    let world = anim.world_matrices(0.5, ClipChoice::All);
    let child = world[0].transform_point3(Vec3::ZERO);
    let h = std::f32::consts::FRAC_1_SQRT_2;
    assert!(
        (child - Vec3::new(1.0 + h, h, 0.0)).length() < EPS,
        "{child}"
    );
}

#[test]
fn cycles_and_bad_parents_are_refused() {
    let cycle = vec![
        trs_node("a", Some(1), Vec3::ZERO),
        trs_node("b", Some(0), Vec3::ZERO),
    ];
    assert!(Hierarchy::new(cycle).unwrap_err().contains("own ancestor"));
    let dangling = vec![trs_node("a", Some(5), Vec3::ZERO)];
    assert!(Hierarchy::new(dangling).is_err());
}

#[test]
fn clips_play_together_and_loop_over_the_longest() {
    let mut anim = rotating_parent();
    let mut second = anim.clips[0].clone();
    second.name = "long".into();
    second.channels[0].target = Target::Translation(0);
    second.channels[0].track = Track::Vec3(
        Keyframes::new(
            vec![0.0, 3.0],
            vec![Vec3::ZERO, Vec3::new(3.0, 0.0, 0.0)],
            Interpolation::Linear,
        )
        .unwrap(),
    );
    anim.clips.push(second);
    assert_eq!(anim.duration(ClipChoice::All), 3.0);
    assert_eq!(anim.duration(ClipChoice::One(0)), 2.0);
    assert!((anim.wrap(3.5, ClipChoice::All) - 0.5).abs() < EPS);
    assert!((anim.wrap(2.5, ClipChoice::One(0)) - 0.5).abs() < EPS);
    assert!((anim.wrap(-0.5, ClipChoice::All) - 2.5).abs() < EPS);
    // Chosen alone, the translation clip leaves the parent at rest.
    let world = anim.world_matrices(1.0, ClipChoice::One(1));
    let child = world[0].transform_point3(Vec3::ZERO);
    assert!((child - Vec3::new(2.0, 0.0, 0.0)).length() < EPS, "{child}");
}

/// One emissive triangle on node 1 of `rotating_parent`, and a STEP channel switching
/// its material off at 1 s.
fn posable_scene() -> (Scene, SceneAnimation) {
    let mut anim = rotating_parent();
    let local = vec![
        Vertex {
            position: Vec3::ZERO,
            normal: Vec3::Z,
            ..Vertex::default()
        },
        Vertex {
            position: Vec3::X,
            normal: Vec3::Z,
            ..Vertex::default()
        },
        Vertex {
            position: Vec3::Y,
            normal: Vec3::Z,
            ..Vertex::default()
        },
    ];
    let scene = Scene {
        vertices: local.clone(),
        triangles: vec![Triangle {
            indices: [0, 1, 2],
            material: 0,
        }],
        materials: vec![Material::emitter("light", Vec3::ONE, false)],
        ..Scene::default()
    };
    anim.meshes.push(MeshBinding {
        node: 1,
        first: 0,
        local,
        materials: Vec::new(),
    });
    anim.materials.push(MaterialBinding {
        material: 0,
        emissive_factor: Vec3::ONE,
        emissive_strength: 2.0,
    });
    anim.clips[0].channels.push(Channel {
        target: Target::EmissiveStrength(0),
        track: Track::Scalar(scalar(&[0.0, 1.0], &[2.0, 0.0], Interpolation::Step)),
    });
    anim.bind_materials(&scene.triangles);
    (scene, anim)
}

#[test]
fn posing_moves_vertices_switches_lights_and_reports_changes() {
    let (mut scene, anim) = posable_scene();
    assert_eq!(anim.meshes[0].materials, vec![0]);
    let change = anim.pose(&mut scene, 0.0, ClipChoice::All);
    // At rest the node is at (1,0,0): every vertex moved, the emitter too, and the
    // emission became factor × strength = 2.
    assert!(change.geometry && change.lights);
    assert_eq!(scene.vertices[0].position, Vec3::X);
    assert_eq!(scene.materials[0].emission, Vec3::splat(2.0));
    // Posing the same time again changes nothing.
    assert!(!anim.pose(&mut scene, 0.0, ClipChoice::All).any());
    let change = anim.pose(&mut scene, 1.0, ClipChoice::All);
    assert!(change.geometry && change.lights);
    assert_eq!(scene.materials[0].emission, Vec3::ZERO);
    // (1,0,0) local on a node at (1,0,0) turned 90° about Z: (1,1,0); normals turn too.
    assert!((scene.vertices[1].position - Vec3::new(1.0, 1.0, 0.0)).length() < EPS);
    assert!((scene.vertices[1].normal - Vec3::Z).length() < EPS);
    assert_eq!(anim.light_events(ClipChoice::All), vec![1.0]);
}

#[test]
fn a_degenerate_pose_never_puts_nan_in_the_scene() {
    let (mut scene, mut anim) = posable_scene();
    // Scale 0: the normal matrix is singular (its inverse is infinite).
    anim.clips[0].channels.push(Channel {
        target: Target::Scale(1),
        track: Track::Vec3(
            Keyframes::new(vec![0.0], vec![Vec3::ZERO], Interpolation::Step).unwrap(),
        ),
    });
    anim.pose(&mut scene, 0.5, ClipChoice::All);
    for v in &scene.vertices {
        assert!(v.position.is_finite() && v.normal.is_finite(), "{v:?}");
    }
}
