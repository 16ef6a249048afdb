//! The mutation keeps the estimate unbiased, and each planted error moves it by far more
//! than the test's noise. A toy light set with known integral: three triangle lights of
//! different areas (so a missing 1/area shows) and one point light, target and integrand
//! polynomials in the barycentrics (exact means over a triangle: u, v → 1/3; u², v² → 1/6;
//! uv → 1/12).

use super::*;
use crate::reservoir::Reservoir;
use crate::reservoir::test_support::{Rng, mean_and_se};

#[derive(Clone, Copy, Debug, PartialEq)]
struct Sample {
    light: usize,
    uv: [f32; 2],
}

/// Triangle lights (area, emission, gradient a, b of the target 1 + a u + b v), then one
/// point light (intensity), each with its power-table probability.
struct Toy {
    areas: [f32; 3],
    emission: [f32; 3],
    gradient: [[f32; 2]; 3],
    point: f32,
    select: [f32; 4],
    /// Planted: the proposal density without the triangle's 1/area.
    proposal_without_area: bool,
}

const TOY: Toy = Toy {
    areas: [0.2, 1.0, 3.0],
    emission: [4.0, 1.0, 0.3],
    gradient: [[3.0, 0.0], [0.0, -0.8], [1.0, 1.0]],
    point: 0.5,
    select: [0.4, 0.2, 0.3, 0.1],
    proposal_without_area: false,
};

impl Toy {
    /// The integrand: the target times a factor it does not know (a BRDF's variation).
    fn f(&self, y: &Sample) -> f64 {
        let t = self.target(y) as f64;
        if y.light == 3 {
            0.7 * t
        } else {
            t * (0.5 + y.uv[0] as f64)
        }
    }

    fn integral(&self) -> f64 {
        let mut sum = 0.7 * self.point as f64;
        for i in 0..3 {
            let (e, [a, b]) = (self.emission[i] as f64, self.gradient[i].map(f64::from));
            // mean of (1 + a u + b v)(0.5 + u) over the triangle
            let mean = 0.5 * (1.0 + a / 3.0 + b / 3.0) + (1.0 / 3.0 + a / 6.0 + b / 12.0);
            sum += self.areas[i] as f64 * e * mean;
        }
        sum
    }
}

impl MutationDomain for Toy {
    type Sample = Sample;

    fn target(&self, y: &Sample) -> f32 {
        if y.light == 3 {
            return self.point;
        }
        let [a, b] = self.gradient[y.light];
        self.emission[y.light] * (1.0 + a * y.uv[0] + b * y.uv[1])
    }

    fn slide(&self, y: &Sample, u: [f32; 2], step: f32) -> Option<Sample> {
        if y.light == 3 {
            return None;
        }
        let uv = [
            y.uv[0] + (u[0] * 2.0 - 1.0) * step,
            y.uv[1] + (u[1] * 2.0 - 1.0) * step,
        ];
        let inside = uv[0] >= 0.0 && uv[1] >= 0.0 && uv[0] + uv[1] <= 1.0;
        inside.then_some(Sample { light: y.light, uv })
    }

    fn propose(&self, u: [f32; 3]) -> Sample {
        let mut light = 3;
        let mut acc = 0.0;
        for (i, p) in self.select.iter().enumerate() {
            acc += p;
            if u[0] < acc {
                light = i;
                break;
            }
        }
        let su = u[1].sqrt();
        Sample {
            light,
            uv: [su * (1.0 - u[2]), su * u[2]],
        }
    }

    fn proposal_density(&self, y: &Sample) -> f32 {
        if y.light == 3 || self.proposal_without_area {
            self.select[y.light]
        } else {
            self.select[y.light] / self.areas[y.light]
        }
    }
}

/// RIS from the power table (`candidates` draws, target T), then `steps` mutations; the
/// mean of f(Y) W over `trials` and its standard error, and the acceptance rate.
fn estimate(toy: &Toy, steps: u32, planted: Planted, seed: u64) -> (f64, f64, f64) {
    let trials = 200_000;
    let candidates = 4;
    let mut rng = Rng::new(seed);
    let mut values = Vec::with_capacity(trials);
    let (mut accepted, mut tried) = (0u64, 0u64);
    for _ in 0..trials {
        let mut r = Reservoir::<Sample>::empty();
        for _ in 0..candidates {
            let y = toy.propose([rng.f32(), rng.f32(), rng.f32()]);
            let t = toy.target(&y);
            let w = t / (candidates as f32 * TOY.proposal_density(&y));
            r.update(y, w, t, rng.f32());
        }
        r.finalize_initial();
        accepted += mutate(toy, &mut r, steps, 0.2, &mut || rng.f32(), planted) as u64;
        tried += steps as u64;
        values.push(r.sample.map_or(0.0, |y| toy.f(&y) * r.weight as f64));
    }
    let (mean, se) = mean_and_se(&values);
    (mean, se, accepted as f64 / tried.max(1) as f64)
}

/// 4.5 standard errors: a false alarm once in ~150 000 runs; every planted error below lands
/// at least 10 standard errors away (printed when the test runs with --nocapture).
const Z: f64 = 4.5;

fn relative_error(toy: &Toy, steps: u32, planted: Planted) -> (f64, f64) {
    let (mean, se, acceptance) = estimate(toy, steps, planted, 7);
    let exact = toy.integral();
    eprintln!(
        "steps {steps}, {planted:?}: {mean:.5} vs {exact:.5} ({:+.2} se), acceptance {acceptance:.2}",
        (mean - exact) / se
    );
    ((mean - exact) / exact, se / exact)
}

#[test]
fn mutation_keeps_the_estimate_unbiased() {
    for steps in [0, 1, 4] {
        let (err, se) = relative_error(&TOY, steps, Planted::None);
        assert!(err.abs() < Z * se, "steps {steps}: {err:+.4} ± {se:.4}");
    }
}

#[test]
fn mutation_moves_the_sample() {
    // Decorrelation needs steps that are taken: on the toy a third or more are.
    let (_, _, acceptance) = estimate(&TOY, 4, Planted::None, 3);
    assert!(acceptance > 0.3, "acceptance {acceptance:.3}");
}

#[test]
fn planted_acceptance_without_the_target_is_caught() {
    let (err, se) = relative_error(&TOY, 4, Planted::NoTargetRatio);
    assert!(
        err.abs() > 2.0 * Z * se,
        "detector silent: {err:+.4} ± {se:.4}"
    );
}

#[test]
fn planted_proposal_without_the_area_jacobian_is_caught() {
    // 16 steps: the chain must travel for the wrong stationary density to show (4 steps
    // gave 11.6 se, 16 give more than twice that).
    let toy = Toy {
        proposal_without_area: true,
        ..TOY
    };
    let (err, se) = relative_error(&toy, 16, Planted::None);
    assert!(
        err.abs() > 2.0 * Z * se,
        "detector silent: {err:+.4} ± {se:.4}"
    );
}

#[test]
fn planted_weight_kept_after_a_move_is_caught() {
    let (err, se) = relative_error(&TOY, 4, Planted::WeightKept);
    assert!(
        err.abs() > 2.0 * Z * se,
        "detector silent: {err:+.4} ± {se:.4}"
    );
}

#[test]
fn a_null_or_degenerate_reservoir_is_left_alone() {
    let mut r = Reservoir::<Sample>::empty();
    assert_eq!(mutate(&TOY, &mut r, 8, 0.2, &mut || 0.25, Planted::None), 0);
    assert!(r.is_null());
    let mut r = Reservoir {
        sample: Some(Sample {
            light: 0,
            uv: [0.2, 0.2],
        }),
        p_hat: f32::NAN,
        w_sum: 1.0,
        weight: 1.0,
        m: 1.0,
    };
    assert_eq!(mutate(&TOY, &mut r, 8, 0.2, &mut || 0.25, Planted::None), 0);
    assert_eq!(r.weight, 1.0);
}
