//! One pairwise-MIS reuse step of direct light as `di/temporal.wgsl` and `di/spatial.wgsl` make it
//! (docs/src/mis-and-bias.md, "The two rules of unbiased reuse"): which candidates take part, what
//! each contributes, and the weights, in plain Rust so that the rules can be checked against exact
//! integrals (`pairwise_reuse_tests.rs`).
//!
//! # The rules
//! - **Whether a candidate takes part depends on its pixel only.** The G-buffer checks
//!   (off-screen, surface, material, normal, depth) are made by the caller, which passes only
//!   the candidates that passed them. Every candidate passed here is a *domain* of the MIS:
//!   its confidence counts in `c_total`, and the canonical sample's weight has a term for it.
//! - **A candidate's sample decides only what it contributes.** A null reservoir, a sample whose
//!   target here is 0 (below the horizon, a light that went off) contributes nothing; it is not
//!   dropped. Dropping it ([`SampleRule::Reject`], the estimator's behaviour before these rules,
//!   kept as the tests' planted error) leaves the canonical sample with the weight it would have
//!   had without that domain, which biases the estimate up.
//! - **One target per domain in every term.** Each domain's `target` is what its samples are
//!   distributed by: p̂·V when its reservoirs were visibility-tested (initial visibility),
//!   and then the pixel's own target must be p̂·V too (`mis_visibility`). Mixing an unshadowed
//!   weight with shadowed samples leaves the weights of a point short of one wherever some
//!   domain cannot produce it (dark).
//! - **The target-ratio clamp is a window on both samples alike.** With `ratio_window = k`,
//!   a sample y counts for domain j only where T_here(y) / T_j(y) is in [1/k, k], for the
//!   neighbour's sample and in the canonical sample's term; the pair's weights still sum to
//!   one. Rejecting the neighbour's sample alone is a sample-dependent decision (biased).

use crate::reservoir::{
    Reservoir, clamp_unit, pairwise_mis_canonical_term, pairwise_mis_noncanonical, share,
};

/// What a sample-dependent check does under pairwise MIS.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleRule {
    /// Counted, not acted on: the candidate stays a domain (the shaders' rule).
    KeepDomain,
    /// The candidate is dropped for its sample (null, target 0 here, ratio outside the
    /// clamp): biased, the planted error of the tests.
    Reject,
}

/// One reuse candidate that passed the G-buffer checks.
pub struct Domain<'a, S: Copy> {
    pub reservoir: Reservoir<S>,
    /// Its confidence (min(M, M cap) for the history, M for a spatial neighbour).
    pub confidence: f32,
    /// The target its samples follow, at any sample: p̂_j(y), or p̂_j(y)·V_j(y).
    pub target: &'a dyn Fn(S) -> f32,
}

/// Whether `t_here / t_there` lies in [1/k, k] (always with `k` ≤ 0: no window); a zero on
/// either side is outside. The same test as `target_ratio_in_window` in reuse.wgsl.
pub fn ratio_in_window(t_here: f32, t_there: f32, k: f32) -> bool {
    if k <= 0.0 {
        return true;
    }
    t_here > 0.0 && t_there > 0.0 && t_here <= k * t_there && t_here * k >= t_there
}

/// Resamples the canonical reservoir (confidence `c_canonical`, its target here
/// `target_here`, which is also the estimate's integrand up to the emission colour) with
/// the candidates, by defensive pairwise MIS; returns the finalised reservoir with
/// `m = c_total`. `u()` gives uniform numbers in [0, 1).
pub fn pairwise_reuse<S: Copy>(
    canonical: &Reservoir<S>,
    c_canonical: f32,
    target_here: &dyn Fn(S) -> f32,
    candidates: &[Domain<S>],
    rule: SampleRule,
    ratio_window: f32,
    u: &mut dyn FnMut() -> f32,
) -> Reservoir<S> {
    // A candidate's target here for its own sample, 0 outside the window.
    let here_for = |d: &Domain<S>| {
        d.reservoir.sample.map_or(0.0, |y| {
            let t = target_here(y);
            if ratio_in_window(t, d.reservoir.p_hat, ratio_window) {
                t
            } else {
                0.0
            }
        })
    };
    let takes_part = |d: &Domain<S>| match rule {
        SampleRule::KeepDomain => true,
        SampleRule::Reject => here_for(d) > 0.0,
    };
    let domains: Vec<&Domain<S>> = candidates.iter().filter(|d| takes_part(d)).collect();
    let c_total = domains
        .iter()
        .fold(c_canonical, |acc, d| acc + d.confidence);

    let mut r = Reservoir::empty();
    if let Some(y) = canonical.sample {
        let p_c = target_here(y);
        let terms: f32 = domains
            .iter()
            .map(|d| {
                let p_j = (d.target)(y);
                let p_j = if ratio_in_window(p_c, p_j, ratio_window) {
                    p_j
                } else {
                    0.0
                };
                pairwise_mis_canonical_term(c_total, c_canonical, d.confidence, p_c, p_j)
            })
            .sum();
        let m_c = clamp_unit(share(c_canonical, c_total) + terms);
        r.merge_mis(canonical, p_c, m_c, u());
    }
    for d in &domains {
        let t = here_for(d);
        let m_j =
            pairwise_mis_noncanonical(c_total, c_canonical, d.confidence, d.reservoir.p_hat, t);
        r.merge_mis(&d.reservoir, t, m_j, u());
    }
    r.finalize(1.0);
    r.m = c_total;
    r
}

#[cfg(test)]
#[path = "pairwise_reuse_tests.rs"]
mod tests;
