//! MCMC mutation of a resampled light sample (docs/src/mcmc-mutation.md; Sawhney et al.
//! 2024, "Decorrelating ReSTIR Samplers via MCMC Mutations"), the plain-Rust mirror of
//! `shaders/di/mutation.wgsl`, step for step.
//!
//! After resampling, a reservoir holds a sample `Y` and a contribution weight `W` with
//! `E[f(Y) W] = ∫ f`. A Markov kernel `K` that leaves the target `T` invariant
//! (`∫ T(y) K(y → y') dy = T(y')`) keeps that true when the weight follows the move:
//! `W' = W · T(Y) / T(Y')`. (Let `g(y) = T(y) ∫ K(y → y') f(y') / T(y') dy'`; W is unbiased
//! for g, so `E[f(Y') W'] = ∫ g = ∫ f(y') / T(y') ∫ T(y) K(y → y') dy dy' = ∫ f`.) Any
//! Metropolis–Hastings kernel toward `T` is invariant; the shader uses two, chosen by a coin:
//! a symmetric slide of the point on its own triangle light, and an independent draw from the
//! power table, whose acceptance carries the proposal densities `q(y) / q(y')`.

/// What a mutation needs to know about a pixel's light samples.
pub trait MutationDomain {
    type Sample: Copy + PartialEq;
    /// The target T(y) at this pixel (visibility included where reuse includes it).
    fn target(&self, y: &Self::Sample) -> f32;
    /// The local move: `y` slid by `(2u − 1) · step` on its own light, or `None` when the
    /// light has no area or the slide left it (a rejected step).
    fn slide(&self, y: &Self::Sample, u: [f32; 2], step: f32) -> Option<Self::Sample>;
    /// The independent proposal's draw from uniform numbers.
    fn propose(&self, u: [f32; 3]) -> Self::Sample;
    /// The independent proposal's density at `y`, in y's own measure.
    fn proposal_density(&self, y: &Self::Sample) -> f32;
}

/// Errors the statistical tests plant to show that they can see them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Planted {
    None,
    /// The acceptance ratio without T(y') / T(y).
    NoTargetRatio,
    /// W kept as it was when the sample moves.
    WeightKept,
}

/// `steps` Metropolis–Hastings steps on `r` (`sample`, `p_hat` = T(sample), `weight`);
/// `rand` gives uniform numbers in [0, 1). Returns the steps accepted. A null reservoir or
/// one whose stored target is not positive stays as it is.
pub fn mutate<D: MutationDomain>(
    domain: &D,
    r: &mut crate::reservoir::Reservoir<D::Sample>,
    steps: u32,
    step: f32,
    rand: &mut impl FnMut() -> f32,
    planted: Planted,
) -> u32 {
    let Some(mut y) = r.sample else {
        return 0;
    };
    if !(r.p_hat > 0.0 && r.p_hat.is_finite() && r.weight > 0.0) {
        return 0;
    }
    let mut accepted = 0;
    for _ in 0..steps {
        let local = rand() < 0.5;
        let u_move = [rand(), rand()];
        let u_accept = rand();
        let (candidate, proposal_ratio) = if local {
            match domain.slide(&y, u_move, step) {
                Some(c) => (c, 1.0),
                None => continue,
            }
        } else {
            let c = domain.propose([rand(), rand(), rand()]);
            let q_new = domain.proposal_density(&c);
            if !(q_new > 0.0) {
                continue;
            }
            (c, domain.proposal_density(&y) / q_new)
        };
        let t_new = domain.target(&candidate);
        let ratio = match planted {
            Planted::NoTargetRatio => proposal_ratio,
            _ => t_new / r.p_hat * proposal_ratio,
        };
        if !(t_new > 0.0) || !(u_accept < ratio) {
            continue;
        }
        accepted += 1;
        if planted != Planted::WeightKept {
            r.weight *= r.p_hat / t_new;
        }
        y = candidate;
        r.sample = Some(y);
        r.p_hat = t_new;
    }
    accepted
}

#[cfg(test)]
#[path = "mcmc_tests.rs"]
mod tests;
