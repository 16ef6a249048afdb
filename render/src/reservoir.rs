//! The plain-Rust mirror of the reservoir math in `shaders/common/reservoir.wgsl` (docs/src/ris.md,
//! docs/src/temporal-reuse.md, docs/src/mis-and-bias.md). The shader is written to match this file
//! operation for operation (f32 all the way), so the statistical tests here vouch for the GPU side
//! too.
//!
//! # Conventions
//! - **M counts reservoirs' worth of samples, not candidates** (RTXDI / Bevy Solari). A fresh
//!   initial reservoir has `M = 1` after finalisation however many candidates it streamed, so the M
//!   cap (docs/src/temporal-reuse.md, "The M cap") counts frames of history rather than light
//!   candidates.
//! - **Initial RIS weights carry their own normalisation**: with `N_s` candidates drawn from
//!   each proposal strategy `s` (light sampling, BSDF sampling), candidate `y_i` gets
//!   `w_i = p̂(y_i) / Σ_s N_s·p_s(y_i)` (balance-heuristic MIS over the strategies) and the
//!   reservoir is finalised with normalisation 1 ([`Reservoir::finalize_initial`]). That is
//!   the textbook `W = w_sum / (M·p̂)` with the `1/M` folded into the weights.
//! - **1/M reuse** (biased mode, docs/src/mis-and-bias.md, "1/M weights"): [`Reservoir::merge`]
//!   each neighbour with `M_rep` candidates, then [`Reservoir::finalize`] with the summed `m`.
//! - **Pairwise MIS reuse** (unbiased mode, docs/src/mis-and-bias.md, "Pairwise MIS"): start from
//!   [`Reservoir::empty`], [`Reservoir::merge_mis`] the canonical reservoir with
//!   [`pairwise_mis_canonical`] and each neighbour with [`pairwise_mis_noncanonical`], set
//!   `m = c_total` (the confidences summed) and finalise with normalisation 1.
//! - **The null sample** (`sample == None`, `W = 0`) stays null: finalisation never redraws.
//!
//! Robustness: every operation keeps the fields finite and non-negative whatever it is fed
//! (NaN, infinities, negatives, subnormals), because a single poisoned reservoir would spread
//! through temporal and spatial reuse to its whole neighbourhood.

/// A streaming weighted-selection reservoir over samples of type `S`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reservoir<S: Copy> {
    /// The selected sample; `None` is the null sample.
    pub sample: Option<S>,
    /// p̂ of `sample` at the pixel that selected it (what `finalize` divides by).
    pub p_hat: f32,
    /// Sum of the resampling weights of every candidate seen.
    pub w_sum: f32,
    /// The unbiased contribution weight W, valid after `finalize`.
    pub weight: f32,
    /// Confidence: how many reservoirs' worth of candidates this one represents.
    pub m: f32,
}

impl<S: Copy> Default for Reservoir<S> {
    fn default() -> Self {
        Self::empty()
    }
}

impl<S: Copy> Reservoir<S> {
    pub const fn empty() -> Self {
        Self {
            sample: None,
            p_hat: 0.0,
            w_sum: 0.0,
            weight: 0.0,
            m: 0.0,
        }
    }

    pub fn is_null(&self) -> bool {
        self.sample.is_none()
    }

    /// Streams one candidate of resampling weight `w` and target `p_hat` (docs/src/ris.md, "The
    /// streaming reservoir"); `u` is uniform in [0, 1). Returns whether the candidate replaced the
    /// current sample.
    ///
    /// A candidate whose weight or target is not finite and positive cannot contribute
    /// (p̂ = 0 means w = 0), so it is ignored and `w_sum` is left alone. `w_sum` saturates at
    /// `f32::MAX` instead of overflowing to infinity.
    pub fn update(&mut self, sample: S, w: f32, p_hat: f32, u: f32) -> bool {
        if !(is_positive_finite(w) && is_positive_finite(p_hat)) {
            return false;
        }
        self.w_sum = (self.w_sum + w).min(f32::MAX);
        // `u · w_sum < w` keeps the candidate with probability w / w_sum. The null check only
        // matters when `w_sum` saturated: the first accepted candidate must always be kept.
        let replace = self.sample.is_none() || u * self.w_sum < w;
        if replace {
            self.sample = Some(sample);
            self.p_hat = p_hat;
        }
        replace
    }

    /// Sets `W = w_sum / (normalization · p_hat)`. Any degenerate input (nothing selected,
    /// zero target, zero normalisation, overflow) makes the reservoir null, with `w_sum` and
    /// `W` zero, so that it contributes nothing and is never reused.
    pub fn finalize(&mut self, normalization: f32) {
        let weight = self.w_sum / (normalization * self.p_hat);
        let valid = self.sample.is_some()
            && is_positive_finite(self.w_sum)
            && is_positive_finite(normalization)
            && is_positive_finite(self.p_hat)
            && is_positive_finite(weight);
        if valid {
            self.weight = weight;
        } else {
            self.sample = None;
            self.p_hat = 0.0;
            self.w_sum = 0.0;
            self.weight = 0.0;
        }
    }

    /// Finalises a reservoir built by initial sampling: normalisation 1 (the weights already
    /// hold `1/Σ N_s p_s`) and `M = 1` (see the module conventions).
    pub fn finalize_initial(&mut self) {
        self.finalize(1.0);
        self.m = 1.0;
    }

    /// Reuses `other` as one candidate representing `m_represented` candidates, for the 1/M mode
    /// (docs/src/temporal-reuse.md, "The merge"): `w = target_here · W_other · m_represented`.
    /// `target_here` is p̂ of `other`'s sample re-evaluated at this pixel, never `other.p_hat`. M
    /// grows by `m_represented` even when the candidate is rejected or null: those candidates were
    /// seen, and the normalisation must count them.
    pub fn merge(&mut self, other: &Self, target_here: f32, m_represented: f32, u: f32) -> bool {
        self.m = (self.m + sanitize(m_represented)).min(f32::MAX);
        self.merge_mis(other, target_here, m_represented, u)
    }

    /// The candidate step of a merge with an explicit MIS weight (pairwise MIS):
    /// `w = target_here · W_other · mis_weight`. M is left alone: the pairwise caller sets it
    /// to `c_total` itself and finalises with normalisation 1 (see the module docs).
    pub fn merge_mis(&mut self, other: &Self, target_here: f32, mis_weight: f32, u: f32) -> bool {
        match other.sample {
            Some(sample) => self.update(
                sample,
                target_here * other.weight * mis_weight,
                target_here,
                u,
            ),
            None => false,
        }
    }

    /// The full 1/M temporal (or single-neighbour spatial) step: merge, then finalise with
    /// the summed M. `self` must already be finalised (its `w_sum = M·p̂·W` then).
    pub fn merge_and_finalize(
        &mut self,
        other: &Reservoir<S>,
        target_here: f32,
        m_represented: f32,
        u: f32,
    ) -> bool {
        let replaced = self.merge(other, target_here, m_represented, u);
        self.finalize(self.m);
        replaced
    }
}

/// Pairwise MIS weight of neighbour `i`'s sample `y` (defensive pairwise MIS with confidence
/// weights, docs/src/mis-and-bias.md, "Pairwise MIS"): `(c_i/c_total) · (c_total−c_c)·p̂_i(y) /
/// ((c_total−c_c)·p̂_i(y) + c_c·p̂_c(y))`, where `c_total` sums the canonical confidence `c_c` and
/// every neighbour's. Always finite, in [0, 1]; 0/0 gives 0.
pub fn pairwise_mis_noncanonical(
    c_total: f32,
    c_canonical: f32,
    c_i: f32,
    p_hat_i_at_y: f32,
    p_hat_c_at_y: f32,
) -> f32 {
    pairwise_split(c_total, c_canonical, c_i, p_hat_i_at_y, p_hat_c_at_y).0
}

/// One neighbour's term of the canonical sample's pairwise MIS weight:
/// `(c_j/c_total) · c_c·p̂_c(y_c) / (c_c·p̂_c(y_c) + (c_total−c_c)·p̂_j(y_c))`. The shader
/// accumulates these in its neighbour loop; [`pairwise_mis_canonical`] adds them up.
pub fn pairwise_mis_canonical_term(
    c_total: f32,
    c_canonical: f32,
    c_j: f32,
    p_hat_c_at_yc: f32,
    p_hat_j_at_yc: f32,
) -> f32 {
    pairwise_split(c_total, c_canonical, c_j, p_hat_j_at_yc, p_hat_c_at_yc).1
}

/// The pair (canonical, neighbour j) at one point y splits the neighbour's share
/// `c_j/c_total` in proportion `(c_total−c_c)·p̂_j(y) : c_c·p̂_c(y)`; returns
/// `(neighbour part, canonical part)`. Both weights above are one side of this split, which
/// is why they sum to the share (and all weights to 1).
fn pairwise_split(
    c_total: f32,
    c_canonical: f32,
    c_j: f32,
    p_hat_j: f32,
    p_hat_c: f32,
) -> (f32, f32) {
    let neighbour = (c_total - c_canonical).max(0.0) * p_hat_j;
    let canonical = c_canonical * p_hat_c;
    let s = share(c_j, c_total);
    (
        s * balance(neighbour, canonical),
        s * balance(canonical, neighbour),
    )
}

/// The canonical sample's pairwise MIS weight `c_c/c_total + Σ_j term_j`, with `neighbours`
/// holding `(c_j, p̂_j(y_c))`. Together with the neighbours' weights at the same point it sums
/// to 1 wherever the canonical target is positive (the pixel's whole integrand), which is what
/// makes the merge unbiased.
pub fn pairwise_mis_canonical(
    c_total: f32,
    c_canonical: f32,
    p_hat_c_at_yc: f32,
    neighbours: &[(f32, f32)],
) -> f32 {
    let terms: f32 = neighbours
        .iter()
        .map(|&(c_j, p_j)| {
            pairwise_mis_canonical_term(c_total, c_canonical, c_j, p_hat_c_at_yc, p_j)
        })
        .sum();
    (share(c_canonical, c_total) + terms).clamp(0.0, 1.0)
}

fn is_positive_finite(x: f32) -> bool {
    x > 0.0 && x.is_finite()
}

/// Negative, NaN and infinite confidences count as nothing seen.
pub(crate) fn sanitize(x: f32) -> f32 {
    if x.is_finite() { x.max(0.0) } else { 0.0 }
}

/// `c / c_total` clamped to [0, 1]; 0 when either is degenerate.
pub(crate) fn share(c: f32, c_total: f32) -> f32 {
    clamp_unit(sanitize(c) / sanitize(c_total))
}

/// `a / (a + b)` for non-negative `a`, `b`, in [0, 1]; 0/0 (and any overflow) gives 0.
fn balance(a: f32, b: f32) -> f32 {
    let a = sanitize(a);
    clamp_unit(a / (a + sanitize(b)))
}

pub(crate) fn clamp_unit(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

#[cfg(test)]
mod history_reset_tests;
#[cfg(test)]
mod tests;

/// Deterministic randomness and goodness-of-fit checks shared by the crate's statistical
/// tests (no rand crate: the seeds and streams must never change under us).
#[cfg(test)]
pub(crate) mod test_support {
    /// SplitMix64: tiny, fast, and good enough for Monte Carlo tests.
    pub struct Rng(u64);

    impl Rng {
        pub fn new(seed: u64) -> Self {
            Self(seed)
        }

        pub fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        }

        /// Uniform in [0, 1) with 24 random bits (exactly representable, never 1.0).
        pub fn f32(&mut self) -> f32 {
            (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
        }

        /// Uniform in [0, 1) with 53 random bits.
        pub fn f64(&mut self) -> f64 {
            (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
        }

        pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
            lo + (hi - lo) * self.f32()
        }

        pub fn below(&mut self, n: usize) -> usize {
            (self.f64() * n as f64) as usize
        }
    }

    /// Panics when `observed` counts are implausible under the probabilities `probs`, at a
    /// 1e-4 false-alarm level. Cells expected to hold fewer than 5 counts are pooled with
    /// their neighbours so the χ² approximation holds (huge dynamic ranges make many).
    pub fn assert_chi_square(observed: &[u64], probs: &[f64]) {
        assert_eq!(observed.len(), probs.len());
        let total: u64 = observed.iter().sum();
        let mut cells: Vec<(f64, f64)> = Vec::new(); // (observed, expected)
        let mut pending = (0.0, 0.0);
        for (&o, &p) in observed.iter().zip(probs) {
            pending.0 += o as f64;
            pending.1 += p * total as f64;
            if pending.1 >= 5.0 {
                cells.push(pending);
                pending = (0.0, 0.0);
            }
        }
        match cells.last_mut() {
            Some(last) => {
                last.0 += pending.0;
                last.1 += pending.1;
            }
            None => cells.push(pending),
        }
        if cells.len() < 2 {
            // One cell: everything must have landed in it.
            assert_eq!(cells[0].0, total as f64, "samples outside the support");
            return;
        }
        let stat: f64 = cells.iter().map(|(o, e)| (o - e) * (o - e) / e).sum();
        let dof = (cells.len() - 1) as f64;
        // Wilson–Hilferty approximation of the χ² quantile; z = Φ⁻¹(1 − 1e-4).
        let z = 3.719;
        let h = 2.0 / (9.0 * dof);
        let critical = dof * (1.0 - h + z * h.sqrt()).powi(3);
        assert!(
            stat <= critical,
            "χ² = {stat:.2} > {critical:.2} with {dof} dof"
        );
    }

    /// f32s from the whole range for robustness properties: zeros, subnormals, huge,
    /// infinite, NaN, negative, and ordinary values (so that valid configurations occur).
    pub fn wild_f32() -> impl proptest::strategy::Strategy<Value = f32> {
        use proptest::prelude::*;
        prop_oneof![
            proptest::num::f32::ANY,
            Just(0.0f32),
            Just(f32::MAX),
            (1u32..0x0080_0000).prop_map(f32::from_bits),
            -10.0f32..10.0,
        ]
    }

    pub fn wild_vec3() -> impl proptest::strategy::Strategy<Value = glam::Vec3> {
        use proptest::prelude::*;
        (wild_f32(), wild_f32(), wild_f32()).prop_map(|(x, y, z)| glam::Vec3::new(x, y, z))
    }

    /// Mean and standard error of a sample.
    pub fn mean_and_se(values: &[f64]) -> (f64, f64) {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
        (mean, (var / n).sqrt())
    }
}
