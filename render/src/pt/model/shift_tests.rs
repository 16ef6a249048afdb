//! Where each shift reconnects, and that a failure says why.

use super::fixtures::{find_path, pixel};
use super::shift::{Failure, Shift, reconnection_bounce, shift_path};
use super::toy_scene::{BACK_WALL, BLOCKER, EMITTER, FLOOR, MIRROR, ToyScene};
use glam::Vec3;

const HYBRID: Shift = Shift::Hybrid {
    rough_threshold: 0.2,
    min_distance: 0.1,
};

/// Hybrid reconnects at the first bounce with two rough ends: at once off the back wall,
/// never along floor → near-mirror → emitter (pure replay), and after the mirror on
/// floor → mirror → wall → emitter.
#[test]
fn hybrid_reconnects_at_the_first_rough_pair() {
    let scene = ToyScene::new(0.35, 0.03);
    let q = pixel([0.2, -0.6]);
    let wall = find_path(&scene, &q, &[FLOOR, BACK_WALL, EMITTER], |_| true);
    let glossy = find_path(&scene, &q, &[FLOOR, MIRROR, EMITTER], |_| true);
    let both = find_path(&scene, &q, &[FLOOR, MIRROR, BACK_WALL, EMITTER], |_| true);
    assert_eq!(reconnection_bounce(&scene, &wall, HYBRID), Some(0));
    assert_eq!(reconnection_bounce(&scene, &glossy, HYBRID), None);
    assert_eq!(reconnection_bounce(&scene, &both, HYBRID), Some(2));
    assert_eq!(
        reconnection_bounce(&scene, &glossy, Shift::Reconnection),
        Some(0)
    );
    assert_eq!(
        reconnection_bounce(&scene, &wall, Shift::RandomReplay),
        None
    );
}

/// A shift and its inverse return the path (the bijection pairwise MIS relies on), with
/// Jacobians that multiply to 1.
#[test]
fn shifting_there_and_back_returns_the_path() {
    let scene = ToyScene::new(0.35, 0.1);
    let (q, r) = (pixel([0.2, -0.6]), pixel([0.4, -0.5]));
    for shift in [Shift::Reconnection, Shift::RandomReplay, HYBRID] {
        for route in [
            &[FLOOR, BACK_WALL, EMITTER][..],
            &[FLOOR, MIRROR, EMITTER],
            &[FLOOR, MIRROR, BACK_WALL, EMITTER],
        ] {
            let path = find_path(&scene, &q, route, |p| {
                shift_path(&scene, p, &q, &r, shift).is_ok()
            });
            let there = shift_path(&scene, &path, &q, &r, shift).unwrap();
            let back = shift_path(&scene, &there.path, &r, &q, shift).unwrap();
            for (a, b) in path
                .vertices
                .iter()
                .zip(&back.path.vertices)
                .take(path.bounces + 1)
            {
                assert!(
                    a.position.distance(b.position) < 1e-3,
                    "{shift:?} {route:?}"
                );
            }
            let product = there.jacobian * back.jacobian;
            assert!(
                (product - 1.0).abs() < 1e-2,
                "{shift:?} {route:?}: {product}"
            );
        }
    }
}

/// Failures carry their reason: a replayed glossy chain far away misses the emitter; a
/// reconnection from a pixel under a small lid is occluded.
#[test]
fn failures_say_why() {
    let mut scene = ToyScene::new(0.35, 0.03);
    let q = pixel([0.2, -0.6]);
    let far = pixel([-1.5, -2.0]);
    let glossy = find_path(&scene, &q, &[FLOOR, MIRROR, EMITTER], |_| true);
    assert_eq!(
        shift_path(&scene, &glossy, &q, &far, Shift::RandomReplay).err(),
        Some(Failure::ReplayLeft)
    );
    let under = pixel([-1.0, -1.0]);
    let mut lid = scene.quads[BLOCKER];
    lid.center = under.primary.position + Vec3::Z * 0.05;
    lid.half = [0.2, 0.2];
    scene.quads.push(lid);
    let wall = find_path(&scene, &q, &[FLOOR, BACK_WALL, EMITTER], |_| true);
    assert_eq!(
        shift_path(&scene, &wall, &q, &under, Shift::Reconnection).err(),
        Some(Failure::Occluded)
    );
}
