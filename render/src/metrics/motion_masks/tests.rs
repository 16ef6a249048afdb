use glam::Vec3;

use super::*;
use crate::scene::Camera;

/// A wall at z = −5 and a unit square occluder at z = −2 centred at x = `occluder_x`.
fn scene(occluder_x: f32) -> Vec<[Vec3; 3]> {
    let quad = |c: Vec3, half: f32| {
        let (a, b) = (
            c + Vec3::new(-half, -half, 0.0),
            c + Vec3::new(half, -half, 0.0),
        );
        let (d, e) = (
            c + Vec3::new(half, half, 0.0),
            c + Vec3::new(-half, half, 0.0),
        );
        [[a, b, d], [a, d, e]]
    };
    let mut t = quad(Vec3::new(0.0, 0.0, -5.0), 20.0).to_vec();
    t.extend(quad(Vec3::new(occluder_x, 0.0, -2.0), 0.5));
    t
}

fn camera(yaw_degrees: f32) -> Camera {
    let c = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, 60f32.to_radians());
    Camera {
        rotation: (glam::Quat::from_rotation_y(yaw_degrees.to_radians()) * c.rotation).normalize(),
        ..c
    }
}

const W: u32 = 32;
const H: u32 = 32;

fn at(mask: &[bool], x: u32, y: u32) -> bool {
    mask[(y * W + x) as usize]
}

fn count(mask: &[bool]) -> usize {
    mask.iter().filter(|&&m| m).count()
}

#[test]
fn a_still_shot_marks_nothing() {
    let s = scene(0.0);
    let mut tracer = MaskTracer::new(&s);
    let posed = Posed {
        camera: camera(0.0),
        positions: &s,
    };
    let m = tracer.masks(posed, posed, W, H);
    assert_eq!(count(&m.disoccluded), 0);
    assert_eq!(count(&m.near_moving), 0);
}

#[test]
fn a_pan_reveals_the_edge_it_turns_towards() {
    let s = scene(0.0);
    let mut tracer = MaskTracer::new(&s);
    let (before, after) = (camera(0.0), camera(10.0));
    let m = tracer.masks(
        Posed {
            camera: before,
            positions: &s,
        },
        Posed {
            camera: after,
            positions: &s,
        },
        W,
        H,
    );
    // Turning left (+y) brings surfaces in at the left edge; the right half was in view.
    assert!((0..H).all(|y| at(&m.disoccluded, 0, y)));
    assert!((0..H).all(|y| !at(&m.disoccluded, W - 1, y)));
    assert!(!at(&m.disoccluded, W / 2, H / 2));
    // 10° of a 60°·(1:1) field: a sixth-ish of the columns, not half.
    let share = count(&m.disoccluded) as f64 / (W * H) as f64;
    assert!((0.05..0.3).contains(&share), "share {share}");
    assert_eq!(count(&m.near_moving), 0, "nothing moved");
}

#[test]
fn a_moving_occluder_reveals_what_it_hid_and_marks_its_surroundings() {
    let (old, new) = (scene(0.0), scene(1.0));
    let mut tracer = MaskTracer::new(&old);
    let cam = camera(0.0);
    let m = tracer.masks(
        Posed {
            camera: cam,
            positions: &old,
        },
        Posed {
            camera: cam,
            positions: &new,
        },
        W,
        H,
    );
    // The centre pixel saw the occluder and now sees the wall behind it.
    assert!(at(&m.disoccluded, W / 2, H / 2));
    // The occluder itself was visible (it moved, the point moved with it): not revealed.
    // Its new centre, x = 1 at z = −2, lies at ndc x = 0.5 / tan 30° ≈ 0.87 → pixel 29.
    assert!(!at(&m.disoccluded, 29, H / 2));
    assert!(at(&m.near_moving, 29, H / 2) && at(&m.near_moving, W / 2, H / 2));
    // The wall far from the occluder: neither.
    assert!(!at(&m.disoccluded, 2, 2) && !at(&m.near_moving, 2, 2));
}

#[test]
fn an_empty_scene_marks_nothing_and_does_not_panic() {
    let mut tracer = MaskTracer::new(&[]);
    let posed = Posed {
        camera: camera(0.0),
        positions: &[],
    };
    let m = tracer.masks(posed, posed, 4, 3);
    assert_eq!(m, MotionMasks::empty(4, 3));
    // Positions of another scene than the tracer's: nothing marked, no panic.
    let s = scene(0.0);
    let mut tracer = MaskTracer::new(&s);
    let short = Posed {
        camera: camera(0.0),
        positions: &s[..2],
    };
    assert_eq!(tracer.masks(short, short, 4, 3), MotionMasks::empty(4, 3));
}

#[test]
fn the_near_moving_radius_scales_with_the_image() {
    assert_eq!(near_moving_radius(48), 1);
    assert_eq!(near_moving_radius(384), 6);
    let mut seed = vec![false; 25];
    seed[12] = true;
    let d = dilate(&seed, 5, 5, 1);
    assert_eq!(count(&d), 9);
}

#[test]
fn masked_error_pools_over_frames_with_known_values() {
    let reference = LinearImage::from_fn(2, 1, |_, _| [1.0, 1.0, 1.0, 1.0]);
    let frame = LinearImage::from_fn(2, 1, |x, _| {
        let v = if x == 0 { 0.5 } else { 3.0 };
        [v, v, v, 1.0]
    });
    let mut e = MaskedError::default();
    e.push(&frame, &reference, &[true, false]);
    e.push(&frame, &reference, &[false, false]);
    assert_eq!(e.share(), 0.25);
    assert!((e.luma_rmse().unwrap() - 0.5).abs() < 1e-6);
    assert!((e.signed_bias().unwrap() + 0.5).abs() < 1e-6);
    assert_eq!(MaskedError::default().luma_rmse(), None);
}
