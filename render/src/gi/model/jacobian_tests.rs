//! The reconnection Jacobian against closed forms, against a finite-difference measurement
//! (the solid angle of a small patch around x_s seen from both receivers), and at its
//! singularities.

use glam::{DVec3, Vec3};
use proptest::prelude::*;

use super::*;
use crate::reservoir::test_support::{Rng, wild_f32, wild_vec3};

#[test]
fn analytic_values() {
    let (xs, n) = (Vec3::ZERO, Vec3::Z);
    let q = Vec3::new(0.0, 0.0, 1.0);
    let j = |r: Vec3| reconnection_jacobian(xs, n, q, r).unwrap();
    // Twice as far, head-on: a quarter of the solid angle.
    assert!((j(Vec3::new(0.0, 0.0, 2.0)) - 0.25).abs() < 1e-6);
    // d² = 2 and cos φ_r = 1/√2: J = (1/√2) / 2.
    assert!((j(Vec3::new(1.0, 0.0, 1.0)) - 0.5f32.sqrt() / 2.0).abs() < 1e-6);
    // The inverse shift gives the inverse Jacobian (the window's symmetry rests on this).
    let r = Vec3::new(0.3, -1.2, 0.7);
    let forward = reconnection_jacobian(xs, n, q, r).unwrap();
    let back = reconnection_jacobian(xs, n, r, q).unwrap();
    assert!((forward * back - 1.0).abs() < 1e-5);
    // The same point: identity. The normal's length and orientation do not matter.
    assert_eq!(reconnection_jacobian(xs, n, r, r), Some(1.0));
    let flipped = reconnection_jacobian(xs, -3.0 * n, q, r).unwrap();
    assert!((flipped - forward).abs() < 1e-6 * forward);
}

/// Solid angle of the triangle (a, b, c) seen from `eye` (Van Oosterom and Strackee 1983).
/// The triple product is taken as a·((b−a)×(c−a)), equal to a·(b×c) but without the
/// cancellation of three nearly parallel long vectors (the triangle here is tiny).
fn triangle_solid_angle(eye: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let numerator = (a - eye).dot((b - a).cross(c - a)).abs();
    let (a, b, c) = (a - eye, b - eye, c - eye);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * numerator.atan2(denominator)
}

/// Solid angle of a square of side `side` centred on `centre` in the plane of normal `n`.
fn patch_solid_angle(eye: DVec3, centre: DVec3, n: DVec3, side: f64) -> f64 {
    let (t, b) = n.any_orthonormal_pair();
    let h = side / 2.0;
    let corner = |s: f64, u: f64| centre + t * (s * h) + b * (u * h);
    let (p00, p10, p11, p01) = (
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
        corner(1.0, 1.0),
        corner(-1.0, 1.0),
    );
    triangle_solid_angle(eye, p00, p10, p11) + triangle_solid_angle(eye, p00, p11, p01)
}

#[test]
fn jacobian_is_the_ratio_of_solid_angles_of_a_small_patch() {
    // Random valid configurations: both receivers in front of the sample's surface, at
    // distances 0.2..5 and cosines above 0.05 (the patch must not be seen edge-on, where the
    // finite patch's solid angle is no longer linear in its area).
    let mut rng = Rng::new(11);
    let mut checked = 0;
    while checked < 2000 {
        let xs = Vec3::new(
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        let n = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let Some(n) = n.try_normalize() else { continue };
        let receiver = |rng: &mut Rng| loop {
            let dir = Vec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            );
            let Some(dir) = dir.try_normalize() else {
                continue;
            };
            if dir.dot(n) > 0.05 {
                return xs + dir * rng.range(0.2, 5.0);
            }
        };
        let (q, r) = (receiver(&mut rng), receiver(&mut rng));
        let j = reconnection_jacobian(xs, n, q, r).expect("a valid configuration");
        // The patch is 1e-4 of the nearest distance: the solid angle's deviation from
        // |cos φ| A / d² is second order in side/d (~1e-8), far below f32's 1e-6 rounding of
        // J, so 1e-4 relative leaves room for rounding and nothing for a wrong formula.
        let side = 1e-4 * 0.2;
        let (xs64, n64) = (xs.as_dvec3(), n.as_dvec3());
        let measured = patch_solid_angle(r.as_dvec3(), xs64, n64, side)
            / patch_solid_angle(q.as_dvec3(), xs64, n64, side);
        let relative = (j as f64 / measured - 1.0).abs();
        assert!(
            relative < 1e-4,
            "J = {j}, solid-angle ratio {measured} (xs {xs}, n {n}, q {q}, r {r})"
        );
        checked += 1;
    }
}

#[test]
fn singular_configurations_have_no_jacobian() {
    let (xs, n) = (Vec3::ZERO, Vec3::Z);
    let q = Vec3::new(0.2, 0.1, 1.0);
    let none = |xs: Vec3, n: Vec3, q: Vec3, r: Vec3| reconnection_jacobian(xs, n, q, r).is_none();
    // Distance → 0 at either end (J → ∞ and J → 0), up to just below the threshold.
    assert!(none(xs, n, q, xs));
    assert!(none(xs, n, xs, q));
    assert!(none(xs, n, q, Vec3::new(0.0, 0.0, 0.9e-5)));
    assert!(reconnection_jacobian(xs, n, q, Vec3::new(0.0, 0.0, 2e-5)).is_some());
    // Grazing at the source (cos φ_q = 0) and at the receiver.
    assert!(none(xs, n, Vec3::new(1.0, 0.0, 0.0), q));
    assert!(none(xs, n, q, Vec3::new(0.0, 3.0, 0.0)));
    // A receiver behind the sample's surface: back face, invalid at r.
    assert!(none(xs, n, q, Vec3::new(0.0, 0.0, -1.0)));
    assert!(none(xs, -n, q, Vec3::new(0.5, 0.0, -1.0)));
    // Degenerate normals and non-finite input.
    assert!(none(xs, Vec3::ZERO, q, q));
    assert!(none(xs, Vec3::splat(f32::NAN), q, q));
    assert!(none(Vec3::splat(f32::INFINITY), n, q, q));
    assert!(none(xs, n, Vec3::new(f32::NAN, 0.0, 1.0), q));
    assert!(none(xs, n, q, Vec3::new(0.0, 0.0, f32::INFINITY)));
    // Beyond the longest reconnection (1e10 units).
    assert!(none(xs, n, q, Vec3::new(0.0, 0.0, 2e10)));
}

#[test]
fn the_window_rejects_large_and_small_jacobians_symmetrically() {
    assert!(jacobian_in_window(1.0, 10.0));
    assert!(jacobian_in_window(10.0, 10.0) && jacobian_in_window(0.1, 10.0));
    assert!(!jacobian_in_window(10.5, 10.0) && !jacobian_in_window(1.0 / 10.5, 10.0));
    // Degenerate windows and Jacobians.
    assert!(jacobian_in_window(1.0, 0.5) && !jacobian_in_window(1.01, 0.5));
    assert!(jacobian_in_window(1.0, f32::NAN) && !jacobian_in_window(2.0, f32::NAN));
    assert!(jacobian_in_window(1e30, f32::INFINITY));
    for j in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert!(!jacobian_in_window(j, f32::INFINITY), "{j}");
    }
    // The shift reports why it failed.
    let (xs, n, q) = (Vec3::ZERO, Vec3::Z, Vec3::new(0.0, 0.0, 1.0));
    assert_eq!(reconnection_shift(xs, n, q, q, 10.0), Ok(1.0));
    assert_eq!(
        reconnection_shift(xs, n, q, Vec3::new(0.0, 0.0, 4.0), 10.0),
        Err(GI_REJECT_JACOBIAN)
    );
    assert_eq!(
        reconnection_shift(xs, n, q, Vec3::new(0.0, 0.0, -1.0), 10.0),
        Err(GI_REJECT_RECONNECTION)
    );
    // Symmetry: the shift q→r passes exactly when r→q does.
    let mut rng = Rng::new(12);
    for _ in 0..10_000 {
        let r = Vec3::new(
            rng.range(-4.0, 4.0),
            rng.range(-4.0, 4.0),
            rng.range(-1.0, 4.0),
        );
        let j_max = rng.range(1.0, 20.0);
        let forward = reconnection_shift(xs, n, q, r, j_max).is_ok();
        let back = reconnection_shift(xs, n, r, q, j_max).is_ok();
        let j = reconnection_jacobian(xs, n, q, r).unwrap_or(1.0);
        // Exactly at the window's edge rounding may split them; nowhere else.
        let at_edge = ((j / j_max) - 1.0).abs() < 1e-5 || ((j * j_max) - 1.0).abs() < 1e-5;
        assert!(forward == back || at_edge, "r {r}, j_max {j_max}");
    }
}

proptest! {
    #[test]
    fn jacobian_is_none_or_finite_positive(
        xs in wild_vec3(), n in wild_vec3(), q in wild_vec3(), r in wild_vec3(), j_max in wild_f32(),
    ) {
        if let Some(j) = reconnection_jacobian(xs, n, q, r) {
            prop_assert!(j.is_finite() && j > 0.0, "{}", j);
        }
        if let Ok(j) = reconnection_shift(xs, n, q, r, j_max) {
            prop_assert!(j.is_finite() && j > 0.0, "{}", j);
        }
    }
}
