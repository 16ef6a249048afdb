//! The pairwise reuse rules (docs/src/mis-and-bias.md, "The two rules of unbiased reuse")
//! against exact integrals. The toy problem: a pixel
//! estimates ∫₀¹ f(y) dy for a target f on the sample space [0, 1) (a light's points), from
//! its own RIS reservoir and one or two reused ones whose targets differ from its own. Each
//! case has a closed form, and each has a planted twin (the rule it replaces) that must be
//! told apart from it. "Unbiased" is |mean − exact| < 4 standard errors (a 6·10⁻⁵ false
//! alarm rate per check); "biased" is more than 10 of them.

use super::*;
use crate::reservoir::test_support::{Rng, mean_and_se};

/// ∫ y² over [a, b).
fn integral_of_square(a: f64, b: f64) -> f64 {
    (b.powi(3) - a.powi(3)) / 3.0
}

fn square(y: f32) -> f32 {
    y * y
}

/// Initial RIS with `n` uniform candidates toward `target` (project convention w = p̂/(N·p)),
/// then, like initial visibility, the survivor dropped where `visible` says it is hidden.
fn ris(
    rng: &mut Rng,
    n: u32,
    target: &dyn Fn(f32) -> f32,
    visible: &dyn Fn(f32) -> bool,
) -> Reservoir<f32> {
    let mut r = Reservoir::empty();
    for _ in 0..n {
        let y = rng.f32();
        r.update(y, target(y) / n as f32, target(y), rng.f32());
    }
    r.finalize_initial();
    if r.sample.is_some_and(|y| !visible(y)) {
        r = Reservoir::empty();
        r.m = 1.0;
    }
    r
}

fn always(_: f32) -> bool {
    true
}

/// Mean and standard error of `trials` estimates f(y)·W.
fn estimate(
    seed: u64,
    trials: usize,
    f: &dyn Fn(f32) -> f32,
    mut one: impl FnMut(&mut Rng) -> Reservoir<f32>,
) -> (f64, f64) {
    let mut rng = Rng::new(seed);
    let values: Vec<f64> = (0..trials)
        .map(|_| {
            let r = one(&mut rng);
            r.sample.map_or(0.0, |y| f(y) as f64 * r.weight as f64)
        })
        .collect();
    mean_and_se(&values)
}

fn assert_unbiased((mean, se): (f64, f64), exact: f64, what: &str) {
    eprintln!("{what}: {:.4} of exact ± {:.4}", mean / exact, se / exact);
    assert!(
        (mean - exact).abs() < 4.0 * se,
        "{what}: {mean:.5} ± {se:.5}, exact {exact:.5}"
    );
}

fn assert_biased((mean, se): (f64, f64), exact: f64, what: &str) {
    eprintln!("{what}: {:.4} of exact ± {:.4}", mean / exact, se / exact);
    assert!(
        (mean - exact).abs() > 10.0 * se,
        "{what} should be biased: {mean:.5} ± {se:.5}, exact {exact:.5}"
    );
}

const TRIALS: usize = 80_000;

/// This pixel sees the light only on [0, 0.8) (its target is 0 beyond: below its horizon);
/// one neighbour has the whole light (uniform target), so its sample lands where the target
/// here is 0 a fifth of the time; another sees only [0, 0.5) with two candidates, so its
/// reservoir is null a quarter of the time.
fn null_and_zero_target(rng: &mut Rng, rule: SampleRule) -> Reservoir<f32> {
    let here = |y: f32| if y < 0.8 { y * y } else { 0.0 };
    let uniform = |_: f32| 1.0;
    let half = |y: f32| if y < 0.5 { y * y } else { 0.0 };
    let canonical = ris(rng, 4, &here, &always);
    let wide = Domain {
        reservoir: ris(rng, 4, &uniform, &always),
        confidence: 3.0,
        target: &uniform,
    };
    let narrow = Domain {
        reservoir: ris(rng, 2, &half, &always),
        confidence: 2.0,
        target: &half,
    };
    pairwise_reuse(
        &canonical,
        1.0,
        &here,
        &[wide, narrow],
        rule,
        0.0,
        &mut || rng.f32(),
    )
}

#[test]
fn null_and_zero_target_candidates_stay_domains() {
    let exact = integral_of_square(0.0, 0.8);
    let here = |y: f32| if y < 0.8 { y * y } else { 0.0 };
    let kept = estimate(1, TRIALS, &here, |rng| {
        null_and_zero_target(rng, SampleRule::KeepDomain)
    });
    assert_unbiased(
        kept,
        exact,
        "null and zero-target candidates kept as domains",
    );
    // The planted error: dropping them gives the canonical sample the weight of a merge
    // without those domains while their samples' share is gone: too bright.
    let rejected = estimate(1, TRIALS, &here, |rng| {
        null_and_zero_target(rng, SampleRule::Reject)
    });
    assert_biased(rejected, exact, "rejected for their sample");
    assert!(rejected.0 > exact);
}

/// Last frame the light covered [0, 1); since then its half [0.5, 1) is off. The history
/// (confidence 20, an M cap's worth) was drawn with last frame's target; this pixel's fresh
/// reservoir with today's.
fn light_gone(rng: &mut Rng, rule: SampleRule) -> Reservoir<f32> {
    let now = |y: f32| if y < 0.5 { y * y } else { 0.0 };
    let canonical = ris(rng, 4, &now, &always);
    let history = Domain {
        reservoir: ris(rng, 4, &square, &always),
        confidence: 20.0,
        target: &square,
    };
    pairwise_reuse(&canonical, 1.0, &now, &[history], rule, 0.0, &mut || {
        rng.f32()
    })
}

#[test]
fn a_history_sample_on_a_light_gone_off_stays_a_domain() {
    let exact = integral_of_square(0.0, 0.5);
    let now = |y: f32| if y < 0.5 { y * y } else { 0.0 };
    let kept = estimate(2, TRIALS, &now, |rng| {
        light_gone(rng, SampleRule::KeepDomain)
    });
    assert_unbiased(kept, exact, "gone sample kept as a domain of target 0");
    // Rejecting it (`light_gone` before the rules above) is the switch-off ghost: the history's
    // 20/21 share of the remaining light is never compensated where it was dropped.
    let rejected = estimate(2, TRIALS, &now, |rng| light_gone(rng, SampleRule::Reject));
    assert_biased(rejected, exact, "gone sample rejected");
    assert!(rejected.0 > 1.2 * exact, "ghosting is large: {rejected:?}");
}

/// Both pixels have the target y²; this one sees the light on [0, 0.7), the neighbour on
/// [0.3, 1), and both reservoirs were visibility-tested where they were drawn. `shadowed`:
/// the domain's target in the MIS terms is p̂·V (as the reservoir's samples are), else the
/// unshadowed p̂.
fn visibility(rng: &mut Rng, shadowed: bool) -> Reservoir<f32> {
    let v_here = |y: f32| y < 0.7;
    let v_there = |y: f32| y > 0.3;
    let here = move |y: f32| if v_here(y) { y * y } else { 0.0 };
    let there = move |y: f32| if v_there(y) { y * y } else { 0.0 };
    let canonical = ris(rng, 4, &square, &v_here);
    let neighbour = ris(rng, 4, &square, &v_there);
    let target: &dyn Fn(f32) -> f32 = if shadowed { &there } else { &square };
    let d = Domain {
        reservoir: neighbour,
        confidence: 4.0,
        target,
    };
    pairwise_reuse(
        &canonical,
        1.0,
        &here,
        &[d],
        SampleRule::KeepDomain,
        0.0,
        &mut || rng.f32(),
    )
}

#[test]
fn visibility_tested_samples_need_visibility_in_every_mis_term() {
    let exact = integral_of_square(0.0, 0.7);
    let f = |y: f32| if y < 0.7 { y * y } else { 0.0 };
    assert_unbiased(
        estimate(3, TRIALS, &f, |rng| visibility(rng, true)),
        exact,
        "p̂·V in every term",
    );
    // The planted error (`mis_visibility` off): the neighbour's weight claims points in
    // [0, 0.3) that its visibility-tested reservoir never holds: too dark.
    let unshadowed = estimate(3, TRIALS, &f, |rng| visibility(rng, false));
    assert_biased(
        unshadowed,
        exact,
        "unshadowed MIS terms over visibility-tested samples",
    );
    assert!(unshadowed.0 < exact);
}

/// The target-ratio clamp k = 2 between a target y² here and y there: they agree within a
/// factor 2 only for y ≥ 0.5.
fn ratio_window(rng: &mut Rng, rule: SampleRule) -> Reservoir<f32> {
    let linear = |y: f32| y;
    let canonical = ris(rng, 4, &square, &always);
    let d = Domain {
        reservoir: ris(rng, 4, &linear, &always),
        confidence: 5.0,
        target: &linear,
    };
    pairwise_reuse(&canonical, 1.0, &square, &[d], rule, 2.0, &mut || rng.f32())
}

#[test]
fn the_target_ratio_window_on_both_samples_is_unbiased() {
    let exact = 1.0 / 3.0;
    let window = estimate(4, TRIALS, &square, |rng| {
        ratio_window(rng, SampleRule::KeepDomain)
    });
    assert_unbiased(window, exact, "ratio window on both samples");
    // Rejecting only the neighbour when its sample is outside: biased.
    let one_sided = estimate(4, TRIALS, &square, |rng| {
        ratio_window(rng, SampleRule::Reject)
    });
    assert_biased(
        one_sided,
        exact,
        "ratio clamp as a rejection of the neighbour",
    );
}

#[test]
fn the_window_matches_the_shader_test() {
    assert!(ratio_in_window(1.0, 1.0, 10.0));
    assert!(ratio_in_window(10.0, 1.0, 10.0) && ratio_in_window(1.0, 10.0, 10.0));
    assert!(!ratio_in_window(10.5, 1.0, 10.0) && !ratio_in_window(1.0, 10.5, 10.0));
    assert!(!ratio_in_window(0.0, 1.0, 10.0) && !ratio_in_window(1.0, 0.0, 10.0));
    assert!(ratio_in_window(0.0, 0.0, 0.0), "no clamp: no window");
    assert!(!ratio_in_window(f32::NAN, 1.0, 10.0));
}
