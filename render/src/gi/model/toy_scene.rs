//! The toy scene of the GI statistical tests, integrated exactly on the CPU: Lambertian
//! receivers on (and tilted about) the plane z = 0 under an emitting square at z = 1 whose
//! radiance varies over it. The indirect light a receiver reflects is
//! `a/π · ∫ L(p) cos θ cos φ / d² dA` (midpoint quadrature in f64, converged to ~1e-6
//! relative); each pixel draws initial samples with cosine-weighted BSDF rays. Optionally a
//! black square (the blocker) hangs between the receivers and the emitter: BSDF rays that
//! hit it find no light, and reconnections through it are occluded. Below the scene, the
//! harness the GI tests share: one spatial reuse step, planted Jacobians, trial statistics.

use glam::{DVec3, Vec3};

use super::*;
use crate::reservoir::test_support::{Rng, mean_and_se};

pub(super) const EMITTER_HEIGHT: f32 = 1.0;
pub(super) const EMITTER_HALF_SIZE: f32 = 1.5;
pub(super) const TINT: Vec3 = Vec3::new(1.0, 0.8, 0.6);

/// The emitter's radiance profile, in [0.2, 1.8].
pub(super) fn profile(x: f64, y: f64) -> f64 {
    1.0 + 0.8 * (1.7 * x + 0.4).sin() * (1.3 * y).cos()
}

pub(super) fn receiver(position: [f32; 3], normal: [f32; 3], albedo: f32) -> GiReceiver {
    GiReceiver {
        position: Vec3::from(position),
        normal: Vec3::from(normal).normalize(),
        brdf: Vec3::splat(albedo / std::f32::consts::PI),
    }
}

/// The pixel whose estimate is checked, and four neighbours at different places (distances
/// 0.6–0.95 against an emitter 1 above: Jacobians over the emitter from 0.25 to 4) with
/// normals tilted by up to ~35°, so part of the receiver's integrand lies below some
/// neighbours' horizons.
pub(super) fn scene() -> (GiReceiver, Vec<GiReceiver>) {
    let here = receiver([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.8);
    let neighbours = vec![
        receiver([0.6, 0.1, 0.0], [0.3, 0.0, 1.0], 0.5),
        receiver([-0.4, 0.7, 0.05], [-0.2, 0.5, 1.0], 0.9),
        receiver([0.3, -0.8, -0.05], [0.0, -0.7, 1.0], 0.7),
        receiver([-0.9, -0.3, 0.0], [0.1, 0.1, 1.0], 0.6),
    ];
    (here, neighbours)
}

/// The blocker: z = 0.5, x in [−0.4, 0.4], y in [0, 0.8] (it hides 40 % of the emitter's
/// light from the checked pixel, and a different part from each neighbour).
const BLOCKER_Z: f32 = 0.5;
const BLOCKER_MIN: [f32; 2] = [-0.4, 0.0];
const BLOCKER_MAX: [f32; 2] = [0.4, 0.8];

/// Whether the segment a → b passes through the blocker.
pub(super) fn blocked(a: Vec3, b: Vec3) -> bool {
    let (da, db) = (a.z - BLOCKER_Z, b.z - BLOCKER_Z);
    if da * db >= 0.0 {
        return false;
    }
    let p = a + (b - a) * (da / (da - db));
    (BLOCKER_MIN[0]..=BLOCKER_MAX[0]).contains(&p.x)
        && (BLOCKER_MIN[1]..=BLOCKER_MAX[1]).contains(&p.y)
}

/// The exact reflected indirect luminance at `r`: a/π · lum(TINT) · ∫ L cos θ cos φ / d² dA.
pub(super) fn exact(r: &GiReceiver, cells: usize) -> f64 {
    exact_with(r, cells, false)
}

/// [`exact`], with or without the blocker.
pub(super) fn exact_with(r: &GiReceiver, cells: usize, blocker: bool) -> f64 {
    let (x, n) = (r.position.as_dvec3(), r.normal.as_dvec3());
    let step = 2.0 * EMITTER_HALF_SIZE as f64 / cells as f64;
    let mut sum = 0.0;
    for i in 0..cells {
        for k in 0..cells {
            let px = -(EMITTER_HALF_SIZE as f64) + (i as f64 + 0.5) * step;
            let py = -(EMITTER_HALF_SIZE as f64) + (k as f64 + 0.5) * step;
            let d = DVec3::new(px, py, EMITTER_HEIGHT as f64) - x;
            if blocker && blocked(r.position, (x + d).as_vec3()) {
                continue;
            }
            let d2 = d.length_squared();
            let cos_r = (n.dot(d) / d2.sqrt()).max(0.0);
            let cos_s = d.z / d2.sqrt();
            sum += profile(px, py) * cos_r * cos_s / d2;
        }
    }
    let brdf = r.brdf.x as f64;
    brdf * luminance(TINT) as f64 * sum * step * step
}

/// One cosine-weighted BSDF ray from `r`: the emitter point it hits, if any (none when
/// `blocker` and the ray hits the blocker: a black hit is a candidate of weight 0).
pub(super) fn trace_candidate(rng: &mut Rng, r: &GiReceiver, blocker: bool) -> Option<GiSample> {
    let (u1, u2) = (rng.f32(), rng.f32());
    let (t, b) = r.normal.any_orthonormal_pair();
    let radius = u1.sqrt();
    let phi = std::f32::consts::TAU * u2;
    let cos = (1.0 - u1).max(0.0).sqrt();
    let dir = (t * radius * phi.cos() + b * radius * phi.sin() + r.normal * cos).normalize();
    if dir.z <= 0.0 {
        return None;
    }
    let p = r.position + dir * ((EMITTER_HEIGHT - r.position.z) / dir.z);
    if p.x.abs() > EMITTER_HALF_SIZE || p.y.abs() > EMITTER_HALF_SIZE {
        return None;
    }
    if blocker && blocked(r.position, p) {
        return None;
    }
    Some(GiSample {
        position: p,
        normal: Vec3::NEG_Z,
        radiance: TINT * profile(p.x as f64, p.y as f64) as f32,
        source_pdf: cos / std::f32::consts::PI,
        age: 0,
    })
}

/// Initial RIS at `r` with `n` BSDF candidates (a miss is a candidate of weight 0).
pub(super) fn initial(rng: &mut Rng, r: &GiReceiver, n: u32) -> GiReservoir {
    initial_with(rng, r, n, false)
}

/// [`initial`], with or without the blocker.
pub(super) fn initial_with(rng: &mut Rng, r: &GiReceiver, n: u32, blocker: bool) -> GiReservoir {
    let mut res = GiReservoir::empty();
    for _ in 0..n {
        if let Some(s) = trace_candidate(rng, r, blocker) {
            let p_hat = r.target(&s);
            res.update(
                s,
                gi_initial_weight(p_hat, s.source_pdf, n as f32),
                p_hat,
                rng.f32(),
            );
        } else {
            rng.f32();
        }
    }
    res.finalize_initial();
    res
}

pub(super) fn estimate(r: &GiReceiver, res: &GiReservoir) -> f64 {
    res.sample.map_or(0.0, |s| {
        luminance(r.contribution(&s)) as f64 * res.weight as f64
    })
}

pub(super) const REUSE_PAIRWISE: GiReuse = GiReuse {
    pairwise: true,
    jacobian_max: 10.0,
    visibility: true,
    mis_visibility: true,
};

/// No occluders in this scene: every reconnection is visible.
pub(super) fn unoccluded(_: Vec3, _: Vec3) -> bool {
    true
}

pub(super) fn omitted(xs: Vec3, n: Vec3, a: Vec3, b: Vec3) -> Option<f32> {
    reconnection_jacobian(xs, n, a, b).map(|_| 1.0)
}

pub(super) fn inverted(xs: Vec3, n: Vec3, a: Vec3, b: Vec3) -> Option<f32> {
    reconnection_jacobian(xs, n, a, b).map(|j| 1.0 / j)
}

/// One spatial reuse step at `here` with fresh initial reservoirs everywhere.
pub(super) fn spatial_estimate(rng: &mut Rng, reuse: GiReuse, jacobian: JacobianFn) -> f64 {
    spatial_estimate_with(rng, reuse, jacobian, false)
}

/// [`spatial_estimate`], with or without the blocker.
pub(super) fn spatial_estimate_with(
    rng: &mut Rng,
    reuse: GiReuse,
    jacobian: JacobianFn,
    blocker: bool,
) -> f64 {
    let (here, neighbours) = scene();
    let canonical = initial_with(rng, &here, 2, blocker);
    let reservoirs: Vec<GiReservoir> = neighbours
        .iter()
        .map(|n| initial_with(rng, n, 2, blocker))
        .collect();
    let listed: Vec<GiNeighbour> = neighbours
        .iter()
        .zip(&reservoirs)
        .map(|(receiver, reservoir)| GiNeighbour {
            receiver: *receiver,
            reservoir,
            confidence: reservoir.m,
        })
        .collect();
    let mut u = || rng.f32();
    let mut visible = |a: Vec3, b: Vec3| !(blocker && blocked(a, b));
    let out = gi_resample(
        &here,
        &canonical,
        canonical.m,
        &listed,
        reuse,
        &mut visible,
        &mut u,
        jacobian,
    );
    estimate(&here, &out.reservoir)
}

pub(super) fn run(seed: u64, trials: usize, mut one: impl FnMut(&mut Rng) -> f64) -> (f64, f64) {
    let mut rng = Rng::new(seed);
    let values: Vec<f64> = (0..trials).map(|_| one(&mut rng)).collect();
    mean_and_se(&values)
}

/// (mean − exact) / exact and the same in standard errors.
pub(super) fn relative_bias((mean, se): (f64, f64), exact: f64) -> (f64, f64) {
    ((mean - exact) / exact, (mean - exact) / se)
}
