//! Statistical and property tests of the reservoir math. The toy problem throughout: estimate
//! ∫₀¹ f(x) dx with f(x) = x² (= 1/3) from uniform candidates, resampled toward various
//! targets p̂. "Unbiased" is checked as |mean − 1/3| < 4 standard errors over many trials.

use proptest::prelude::*;

use super::test_support::{Rng, assert_chi_square, mean_and_se};
use super::*;

pub(super) const INTEGRAL: f64 = 1.0 / 3.0;

pub(super) fn f(x: f32) -> f32 {
    x * x
}

/// A target on a reduced support: resampling toward it alone cannot see x ≥ 0.5.
fn half_support(x: f32) -> f32 {
    if x < 0.5 { x * x } else { 0.0 }
}

/// Initial RIS with `n` uniform candidates, in the project convention w = p̂ / (N · p_src).
pub(super) fn ris(rng: &mut Rng, n: u32, target: fn(f32) -> f32) -> Reservoir<f32> {
    let mut r = Reservoir::empty();
    for _ in 0..n {
        let x = rng.f32();
        r.update(x, target(x) / n as f32, target(x), rng.f32());
    }
    r.finalize_initial();
    r
}

fn estimate(r: &Reservoir<f32>) -> f64 {
    r.sample.map_or(0.0, |y| f(y) as f64 * r.weight as f64)
}

/// Runs `trials` independent estimates and returns their mean and standard error.
fn run(seed: u64, trials: usize, mut one: impl FnMut(&mut Rng) -> f64) -> (f64, f64) {
    let mut rng = Rng::new(seed);
    let values: Vec<f64> = (0..trials).map(|_| one(&mut rng)).collect();
    mean_and_se(&values)
}

fn assert_unbiased((mean, se): (f64, f64), what: &str) {
    assert!(
        (mean - INTEGRAL).abs() < 4.0 * se,
        "{what}: mean {mean} ± {se}, expected {INTEGRAL}"
    );
}

#[test]
fn selection_frequency_is_proportional_to_weight() {
    let weights = [1.0, 2.0, 0.5, 10.0, 0.01, 3.0, 0.0, 7.0];
    let total: f64 = weights.iter().sum();
    let probs: Vec<f64> = weights.iter().map(|w| w / total).collect();
    let mut rng = Rng::new(1);
    let mut counts = [0u64; 8];
    for _ in 0..200_000 {
        let mut r = Reservoir::empty();
        for (i, &w) in weights.iter().enumerate() {
            r.update(i, w as f32, 1.0, rng.f32());
        }
        counts[r.sample.unwrap()] += 1;
    }
    assert_eq!(counts[6], 0, "a zero-weight candidate was selected");
    assert_chi_square(&counts, &probs);
}

#[test]
fn plain_ris_is_unbiased_for_matching_and_mismatched_targets() {
    assert_unbiased(run(2, 40_000, |rng| estimate(&ris(rng, 8, f))), "p̂ = f");
    assert_unbiased(run(3, 40_000, |rng| estimate(&ris(rng, 8, |x| x))), "p̂ = x");
    assert_unbiased(
        run(4, 40_000, |rng| estimate(&ris(rng, 3, |x| 1.0 + x))),
        "p̂ = 1 + x",
    );
}

#[test]
fn one_over_m_merging_of_independent_reservoirs_is_unbiased() {
    // Joint merge of four reservoirs of the same pixel, then one finalisation with Σ M.
    let joint = run(5, 40_000, |rng| {
        let mut s = Reservoir::empty();
        for n in [1, 4, 8, 2] {
            let r = ris(rng, n, |x| x);
            s.merge(&r, r.sample.map_or(0.0, |y| y), r.m, rng.f32());
        }
        s.finalize(s.m);
        estimate(&s)
    });
    assert_unbiased(joint, "joint 1/M merge");
    // Temporal-style chain: each frame merges the previous history (M capped at 20).
    let chained = run(6, 40_000, |rng| {
        let mut history = ris(rng, 4, f);
        for _ in 0..5 {
            let mut current = ris(rng, 4, f);
            let target_here = history.sample.map_or(0.0, f);
            current.merge_and_finalize(&history, target_here, history.m.min(20.0), rng.f32());
            history = current;
        }
        assert_eq!(history.m, 6.0);
        estimate(&history)
    });
    assert_unbiased(chained, "temporal chain");
}

#[test]
fn merge_order_does_not_change_the_expected_value() {
    // Different candidate counts, targets (all covering f's support) and confidences, so the
    // order is structurally visible to the selection; only the expectation must not care.
    let targets: [fn(f32) -> f32; 4] = [f, |x| x, |x| 1.0 + x, |x| x.sqrt()];
    let confidences = [1.0, 3.0, 2.0, 5.0];
    let merged = |rng: &mut Rng, reverse: bool| {
        let reservoirs: Vec<_> = targets.iter().map(|&t| ris(rng, 6, t)).collect();
        let mut order: Vec<usize> = (0..4).collect();
        if reverse {
            order.reverse();
        }
        let mut s = Reservoir::empty();
        for i in order {
            let r = &reservoirs[i];
            s.merge(r, r.sample.map_or(0.0, f), confidences[i], rng.f32());
        }
        s.finalize(s.m);
        estimate(&s)
    };
    let forward = run(7, 40_000, |rng| merged(rng, false));
    let backward = run(7, 40_000, |rng| merged(rng, true));
    assert_unbiased(forward, "forward order");
    assert_unbiased(backward, "reverse order");
    let se = (forward.1.powi(2) + backward.1.powi(2)).sqrt();
    assert!((forward.0 - backward.0).abs() < 4.0 * se);
}

/// Canonical domain with target f plus neighbours with other targets, one of them blind to
/// half the domain; merged with pairwise MIS (or, for contrast, 1/M).
fn multi_domain_estimate(rng: &mut Rng, pairwise: bool) -> f64 {
    let targets: [fn(f32) -> f32; 3] = [|x| x, half_support, |_| 1.0];
    let (c_c, c) = (1.0, [2.0, 3.0, 1.0]);
    let c_total = c_c + c.iter().sum::<f32>();
    let canonical = ris(rng, 4, f);
    let neighbours: Vec<_> = targets.iter().map(|&t| ris(rng, 4, t)).collect();
    let mut s = Reservoir::empty();
    if pairwise {
        let m_c = canonical.sample.map_or(0.0, |y| {
            let at_y: Vec<(f32, f32)> = c
                .iter()
                .zip(&targets)
                .map(|(&c_j, t)| (c_j, t(y)))
                .collect();
            pairwise_mis_canonical(c_total, c_c, f(y), &at_y)
        });
        s.merge_mis(&canonical, canonical.sample.map_or(0.0, f), m_c, rng.f32());
        for ((r, t), &c_i) in neighbours.iter().zip(&targets).zip(&c) {
            let (target_here, m_i) = r.sample.map_or((0.0, 0.0), |y| {
                (
                    f(y),
                    pairwise_mis_noncanonical(c_total, c_c, c_i, t(y), f(y)),
                )
            });
            s.merge_mis(r, target_here, m_i, rng.f32());
        }
        s.m = c_total;
        s.finalize(1.0);
    } else {
        s.merge(&canonical, canonical.sample.map_or(0.0, f), c_c, rng.f32());
        for (r, &c_i) in neighbours.iter().zip(&c) {
            s.merge(r, r.sample.map_or(0.0, f), c_i, rng.f32());
        }
        s.finalize(s.m);
    }
    assert_eq!(s.m, c_total);
    estimate(&s)
}

#[test]
fn pairwise_mis_merge_is_unbiased_across_domains_with_different_targets() {
    assert_unbiased(
        run(8, 60_000, |rng| multi_domain_estimate(rng, true)),
        "pairwise MIS",
    );
    // The same inputs under 1/M lose the mass the blind neighbour cannot see (expected value
    // 1/3 − 3/7·(1/3 − 1/24) ≈ 0.208): the test above can tell bias when there is some.
    let (mean, se) = run(8, 60_000, |rng| multi_domain_estimate(rng, false));
    assert!(
        (mean - INTEGRAL).abs() > 10.0 * se,
        "1/M mean {mean} ± {se} looks unbiased"
    );
}

#[test]
fn pairwise_mis_weights_sum_to_one_wherever_the_canonical_target_is_positive() {
    let mut rng = Rng::new(9);
    for _ in 0..10_000 {
        let k = 1 + rng.below(6);
        let c_c = rng.range(0.1, 20.0);
        let neighbours: Vec<(f32, f32)> = (0..k)
            .map(|_| {
                let p = if rng.f32() < 0.2 {
                    0.0
                } else {
                    rng.range(0.0, 5.0)
                };
                (rng.range(0.1, 20.0), p)
            })
            .collect();
        let c_total = c_c + neighbours.iter().map(|n| n.0).sum::<f32>();
        let p_c = rng.range(1e-3, 5.0);
        let canonical = pairwise_mis_canonical(c_total, c_c, p_c, &neighbours);
        let others: f32 = neighbours
            .iter()
            .map(|&(c_i, p_i)| pairwise_mis_noncanonical(c_total, c_c, c_i, p_i, p_c))
            .sum();
        assert!(
            (canonical + others - 1.0).abs() < 1e-5,
            "{canonical} + {others}"
        );
    }
}

#[test]
fn null_samples_stay_null() {
    // Positive weight but zero target: nothing is selected, finalisation gives the null.
    let mut r = Reservoir::empty();
    assert!(!r.update(1u32, 1.0, 0.0, 0.5));
    r.finalize_initial();
    assert!(r.is_null() && r.weight == 0.0 && r.w_sum == 0.0 && r.m == 1.0);
    // A degenerate normalisation nulls a selected sample, and it stays null afterwards.
    let mut r = Reservoir::empty();
    r.update(2u32, 1.0, 1.0, 0.5);
    r.finalize(0.0);
    assert!(r.is_null());
    r.finalize(1.0);
    assert!(r.is_null() && r.weight == 0.0);
    // Merging a null counts its confidence but selects nothing, in either direction.
    let mut s = Reservoir::empty();
    assert!(!s.merge(&r, 1.0, 3.0, 0.0));
    s.finalize(s.m);
    assert!(s.is_null() && s.m == 3.0);
    let mut kept = Reservoir::empty();
    kept.update(7u32, 2.0, 1.0, 0.5);
    kept.finalize_initial();
    kept.merge_and_finalize(&r, 1.0, 4.0, 0.0);
    assert_eq!(
        (kept.sample, kept.m, kept.weight),
        (Some(7), 5.0, 2.0 / 5.0)
    );
}

/// f32s from the whole range: zeros, subnormals, huge, infinite, NaN, negative.
fn wild() -> impl Strategy<Value = f32> {
    prop_oneof![
        proptest::num::f32::ANY,
        Just(0.0f32),
        Just(f32::MAX),
        Just(f32::MIN_POSITIVE),
        (1u32..0x0080_0000).prop_map(f32::from_bits),
        (0u32..0x7f80_0000).prop_map(f32::from_bits),
    ]
}

fn assert_sane<S: Copy>(r: &Reservoir<S>) {
    for (name, v) in [
        ("w_sum", r.w_sum),
        ("p_hat", r.p_hat),
        ("weight", r.weight),
        ("m", r.m),
    ] {
        assert!(v.is_finite() && v >= 0.0, "{name} = {v}");
    }
    assert_eq!(
        r.sample.is_some(),
        r.w_sum > 0.0,
        "selection without weight or vice versa"
    );
}

proptest! {
    #[test]
    fn update_and_finalize_stay_finite(
        candidates in prop::collection::vec((wild(), wild(), 0.0f32..1.0), 0..16),
        normalization in wild(),
    ) {
        let mut r = Reservoir::empty();
        for (i, &(w, target, u)) in candidates.iter().enumerate() {
            r.update(i, w, target, u);
            assert_sane(&r);
        }
        r.finalize(normalization);
        assert_sane(&r);
        if r.is_null() {
            prop_assert!(r.w_sum == 0.0 && r.weight == 0.0);
        }
    }

    #[test]
    fn merge_stays_finite(
        reuses in prop::collection::vec((wild(), wild(), wild(), wild(), wild(), 0.0f32..1.0), 1..8),
    ) {
        let mut s = Reservoir::empty();
        for (i, &(w, target, normalization, target_here, m_rep, u)) in reuses.iter().enumerate() {
            let mut other = Reservoir::empty();
            other.update(i, w, target, u);
            other.finalize(normalization);
            s.merge(&other, target_here, m_rep, u);
            assert_sane(&s);
            s.merge_mis(&other, target_here, w, u);
            assert_sane(&s);
        }
        s.finalize(s.m);
        assert_sane(&s);
    }

    #[test]
    fn pairwise_weights_are_finite_probabilities(
        c_total in wild(), c_c in wild(), c_i in wild(), p_i in wild(), p_c in wild(),
    ) {
        let m_i = pairwise_mis_noncanonical(c_total, c_c, c_i, p_i, p_c);
        let m_c = pairwise_mis_canonical(c_total, c_c, p_c, &[(c_i, p_i)]);
        for m in [m_i, m_c] {
            prop_assert!((0.0..=1.0).contains(&m), "{}", m);
        }
    }
}
