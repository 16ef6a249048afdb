//! ReSTIR GI's reservoir math (Ouyang et al. 2021), the plain-Rust mirror of
//! `shaders/gi/reservoir.wgsl`, built on the DI reservoir of `reservoir.rs` (same
//! streaming, finalisation, null-sample and robustness rules; same M convention).
//!
//! A pixel's visible point `x_v` (its G-buffer surface: implicit, never stored) receives
//! indirect light along one direction; the sample is the secondary hit `x_s` with its normal
//! and the outgoing radiance `L_o(x_s → x_v)` cached when it was found. Its domain is the
//! hemisphere at `x_v`, in solid angle, so reuse at another pixel goes through the
//! reconnection shift (`model/jacobian.rs`): the neighbour's sample counts with weight
//! `p̂_here(y) · W · |J|`, and in pairwise MIS every target seen from another domain is
//! expressed in this pixel's measure (`p̂_j · |J_{here→j}|`).
//!
//! # Target function
//! `p̂ = luminance(f_r(x_v, ω_o, ω) · L_o · cos θ_v)`: the sample's whole contribution at the
//! receiving pixel. The cheaper `luminance(L_o)` would keep samples the receiver sees at a
//! grazing angle or below its horizon as often as head-on ones (zero contribution, full
//! weight), and it ignores the receiver altogether (in the MIS weights only the Jacobian
//! would tell neighbours apart); the full contribution is 0 exactly where the pixel's integrand is and, for
//! the Lambertian receivers of the tests, proportional to it (the ideal RIS target). The
//! notes do not ask for the simpler one, so it is not provided.
//!
//! # Which failures count M
//! A neighbour rejected for its *pixel* (surface checks: normal, depth, material, off-screen)
//! is not merged at all: the set of domains depends on the geometry only. A neighbour whose
//! *sample* cannot be used here (reconnection undefined, Jacobian outside the window,
//! reconnection occluded) is a candidate seen with target 0 here: in 1/M mode its M counts
//! (the darkening bias of 1/M with rejection, measured in model/tests.rs); in pairwise mode its
//! confidence is part of `c_total` and its MIS weight is 0, which stays unbiased because the
//! shift's validity is symmetric, and, behind occluders, only when the canonical sample's
//! MIS weight also knows which neighbours see its point (`GiReuse::mis_visibility`,
//! measured in model/visibility_tests.rs).

use glam::Vec3;

use crate::reservoir::{
    Reservoir, clamp_unit, pairwise_mis_canonical_term, pairwise_mis_noncanonical, sanitize, share,
};
use crate::shader_constants::{GI_REJECT_JACOBIAN, GI_REJECT_OCCLUDED, GI_REJECT_RECONNECTION};
/// The Jacobian `gi_resample` takes where no test plants another.
pub use jacobian::reconnection_jacobian;
use jacobian::{jacobian_in_window, normalized};

/// One GI sample: the secondary hit and the radiance it sends toward the pixel that found it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GiSample {
    /// x_s, the sample point (secondary hit).
    pub position: Vec3,
    /// n_s, its surface normal (either orientation: the Jacobian only compares sides).
    pub normal: Vec3,
    /// L_o(x_s → x_v), rgb, cached when the sample was drawn and assumed unchanged toward
    /// other receivers (exact for Lambertian x_s, the approximation of ReSTIR GI).
    pub radiance: Vec3,
    /// Density of the direction that found x_s, per steradian at the pixel that drew it
    /// (forms the initial weight; after resampling `W` stands for it).
    pub source_pdf: f32,
    /// Frames since the sample was drawn (temporal reuse adds one).
    pub age: u32,
}

/// A GI reservoir: the sample with `w_sum`, `W` (`weight`), `M` and the target at the pixel
/// that selected it (`p_hat`); the age travels with the sample.
pub type GiReservoir = Reservoir<GiSample>;

/// A pixel's visible point as GI reuse needs it: where it is, which way it faces, and its
/// BRDF. Lambertian here (`brdf` = albedo/π, rgb); the GPU evaluates brdf.wgsl at the same
/// place and feeds the result to the same [`gi_target`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GiReceiver {
    pub position: Vec3,
    pub normal: Vec3,
    pub brdf: Vec3,
}

/// `luminance(f_r · L_o · cos θ)`; 0 for a negative cosine and whenever the product is not
/// finite and positive (a NaN radiance must not become a target).
pub fn gi_target(f_r: Vec3, radiance: Vec3, cos_theta: f32) -> f32 {
    let p = luminance(f_r * radiance * cos_theta.max(0.0));
    if p > 0.0 && p.is_finite() { p } else { 0.0 }
}

/// cos θ at `position` (normal `normal`, unit length) toward `sample_position`, clamped at 0;
/// 0 when the two points coincide or anything is not finite.
pub fn receiver_cosine(position: Vec3, normal: Vec3, sample_position: Vec3) -> f32 {
    match normalized(sample_position - position) {
        Some(w) => {
            let c = normal.dot(w);
            if c > 0.0 && c.is_finite() {
                c.min(1.0)
            } else {
                0.0
            }
        }
        None => 0.0,
    }
}

/// Rec. 709 luminance, the weights of math.wgsl and image.rs.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

impl GiReceiver {
    /// f_r · L_o · cos θ: what the sample adds to this pixel, before `W`.
    pub fn contribution(&self, s: &GiSample) -> Vec3 {
        let c = receiver_cosine(self.position, self.normal, s.position);
        self.brdf * s.radiance * c
    }

    /// p̂ of `s` at this pixel (see the module docs).
    pub fn target(&self, s: &GiSample) -> f32 {
        let c = receiver_cosine(self.position, self.normal, s.position);
        gi_target(self.brdf, s.radiance, c)
    }
}

/// The initial RIS weight of a candidate drawn with density `source_pdf` (per steradian) as
/// one of `candidates` from the same strategy: `p̂ / (N · p_src)`, 0 when degenerate.
pub fn gi_initial_weight(p_hat: f32, source_pdf: f32, candidates: f32) -> f32 {
    let w = p_hat / (candidates * source_pdf);
    if w > 0.0 && w.is_finite() { w } else { 0.0 }
}

/// 1/M merge of a reservoir from another pixel or frame whose sample was shifted here with
/// Jacobian `jacobian` (0: the shift failed, see the module docs): `w = p̂_here · W · M_rep ·
/// |J|`, and M grows by `m_rep` whether or not the candidate can be used.
pub fn gi_merge(
    r: &mut GiReservoir,
    other: &GiReservoir,
    target_here: f32,
    jacobian: f32,
    m_rep: f32,
    u: f32,
) -> bool {
    r.m = (r.m + sanitize(m_rep)).min(f32::MAX);
    gi_merge_mis(r, other, target_here, jacobian, m_rep, u)
}

/// The candidate step with an explicit MIS weight (pairwise): `w = p̂_here · W · m_i · |J|`.
/// The stored target stays `p̂_here` (what finalisation divides by), never `p̂_here · |J|`.
pub fn gi_merge_mis(
    r: &mut GiReservoir,
    other: &GiReservoir,
    target_here: f32,
    jacobian: f32,
    mis_weight: f32,
    u: f32,
) -> bool {
    r.merge_mis(
        other,
        target_here,
        sanitize(mis_weight) * sanitize(jacobian),
        u,
    )
}

/// Neighbour i's sample y, shifted here with `jacobian_i_to_here` = |J_{i→here}|: its
/// pairwise MIS weight, with p̂_i(y) brought into this pixel's measure
/// (p̂_i · |J_{here→i}| = p̂_i / |J_{i→here}|); 0 when the shift failed (jacobian 0).
pub fn shifted_pairwise_noncanonical(
    c_total: f32,
    c_canonical: f32,
    c_i: f32,
    p_hat_i_at_y: f32,
    p_hat_here_at_y: f32,
    jacobian_i_to_here: f32,
) -> f32 {
    let j = sanitize(jacobian_i_to_here);
    let p_i = if j > 0.0 { p_hat_i_at_y / j } else { 0.0 };
    pairwise_mis_noncanonical(c_total, c_canonical, c_i, p_i, p_hat_here_at_y)
}

/// Neighbour j's term of the canonical sample's pairwise weight (`c_c/c_total + Σ_j
/// terms`), with p̂_j(y_c) · |J_{here→j}| (`jacobian_here_to_j` = 0 when that shift fails).
pub fn shifted_pairwise_canonical_term(
    c_total: f32,
    c_canonical: f32,
    c_j: f32,
    p_hat_here_at_yc: f32,
    p_hat_j_at_yc: f32,
    jacobian_here_to_j: f32,
) -> f32 {
    let p_j = p_hat_j_at_yc * sanitize(jacobian_here_to_j);
    pairwise_mis_canonical_term(c_total, c_canonical, c_j, p_hat_here_at_yc, p_j)
}

/// A reservoir from another pixel (spatial) or the previous frame (temporal), with the
/// receiver it was resampled for and the confidence it enters with (spatial: its M;
/// temporal: min(M, gi_m_cap)). Only neighbours that passed the pixel checks are listed.
#[derive(Clone, Copy, Debug)]
pub struct GiNeighbour<'a> {
    pub receiver: GiReceiver,
    pub reservoir: &'a GiReservoir,
    pub confidence: f32,
}

/// How reuse treats shifted samples (the Indirect stage's settings).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GiReuse {
    /// Pairwise MIS (unbiased) or 1/M with rejection.
    pub pairwise: bool,
    /// `gi_jacobian_max`: the window [1/j_max, j_max].
    pub jacobian_max: f32,
    /// Trace the reconnection x_here → x_s of each neighbour's sample (spatial reuse with
    /// `gi_spatial_visibility`; the temporal sample at the same surface is not traced).
    pub visibility: bool,
    /// Pairwise only: also trace from each neighbour's visible point to the canonical
    /// sample's point, and count the neighbour's target there as 0 when occluded (the
    /// neighbour could not have found that sample). Without it the canonical sample's MIS
    /// weight assumes every neighbour sees it, and reuse behind occluders darkens (measured
    /// in model/tests.rs: −5 % where a blocker hides 40 % of the light). One more ray per
    /// neighbour.
    pub mis_visibility: bool,
}

/// The outcome of one reuse step: the finalised reservoir and, per neighbour, the GI
/// rejection bits of its sample (0: merged as a usable candidate).
#[derive(Clone, Debug)]
pub struct GiResampled {
    pub reservoir: GiReservoir,
    pub rejections: Vec<u32>,
}

/// The reconnection Jacobian as reuse computes it (`jacobian::reconnection_jacobian`); the
/// tests swap in planted errors.
pub type JacobianFn = fn(Vec3, Vec3, Vec3, Vec3) -> Option<f32>;

/// One temporal or spatial reuse step at `here` (the reference the WGSL passes follow):
/// the canonical reservoir (this pixel's own, confidence `c_canonical`) resampled with the
/// neighbours' shifted samples, in the mode `reuse` says, finalised. `visible(x, x_s)` traces
/// a reconnection; `u()` gives uniform numbers in [0, 1); `jacobian` is
/// `reconnection_jacobian` but where a test plants an error. The caller caps M afterwards.
#[allow(clippy::too_many_arguments)]
pub fn gi_resample(
    here: &GiReceiver,
    canonical: &GiReservoir,
    c_canonical: f32,
    neighbours: &[GiNeighbour],
    reuse: GiReuse,
    visible: &mut dyn FnMut(Vec3, Vec3) -> bool,
    u: &mut dyn FnMut() -> f32,
    jacobian: JacobianFn,
) -> GiResampled {
    let c_c = sanitize(c_canonical);
    let c_total = neighbours
        .iter()
        .fold(c_c, |acc, n| (acc + sanitize(n.confidence)).min(f32::MAX));
    // |J_{a→b}| within the window, or the rejection bit.
    let shift = |s: &GiSample, a: Vec3, b: Vec3| match jacobian(s.position, s.normal, a, b) {
        Some(j) if jacobian_in_window(j, reuse.jacobian_max) => Ok(j),
        Some(_) => Err(GI_REJECT_JACOBIAN),
        None => Err(GI_REJECT_RECONNECTION),
    };
    let mut r = GiReservoir::empty();
    if let Some(y) = canonical.sample {
        let p_c = here.target(&y);
        if reuse.pairwise {
            // Each neighbour's target at y_c in this pixel's measure (0 where it cannot
            // produce y_c: the reverse shift fails).
            let terms: f32 = neighbours
                .iter()
                .map(|n| {
                    let mut j = shift(&y, here.position, n.receiver.position).unwrap_or(0.0);
                    if j > 0.0 && reuse.mis_visibility && !visible(n.receiver.position, y.position)
                    {
                        j = 0.0;
                    }
                    let p_j = n.receiver.target(&y);
                    shifted_pairwise_canonical_term(c_total, c_c, n.confidence, p_c, p_j, j)
                })
                .sum();
            let m_c = clamp_unit(share(c_c, c_total) + terms);
            gi_merge_mis(&mut r, canonical, p_c, 1.0, m_c, u());
        } else {
            gi_merge(&mut r, canonical, p_c, 1.0, c_c, u());
        }
    } else if !reuse.pairwise {
        r.m += c_c;
    }
    let mut rejections = Vec::with_capacity(neighbours.len());
    for n in neighbours {
        let Some(y) = n.reservoir.sample else {
            rejections.push(0);
            if !reuse.pairwise {
                r.m = (r.m + sanitize(n.confidence)).min(f32::MAX);
            }
            continue;
        };
        let mut usable = shift(&y, n.receiver.position, here.position);
        if usable.is_ok() && reuse.visibility && !visible(here.position, y.position) {
            usable = Err(GI_REJECT_OCCLUDED);
        }
        rejections.push(usable.err().unwrap_or(0));
        let j = usable.unwrap_or(0.0);
        let target_here = if j > 0.0 { here.target(&y) } else { 0.0 };
        if reuse.pairwise {
            let p_n = n.receiver.target(&y);
            let m_n =
                shifted_pairwise_noncanonical(c_total, c_c, n.confidence, p_n, target_here, j);
            gi_merge_mis(&mut r, n.reservoir, target_here, j, m_n, u());
        } else {
            gi_merge(&mut r, n.reservoir, target_here, j, n.confidence, u());
        }
    }
    if reuse.pairwise {
        r.m = c_total;
        r.finalize(1.0);
    } else {
        r.finalize(r.m);
    }
    GiResampled {
        reservoir: r,
        rejections,
    }
}

/// Caps a reservoir's confidence after reuse (`gi_m_cap`); W is unchanged.
pub fn gi_cap_confidence(r: &mut GiReservoir, m_cap: f32) {
    r.m = r.m.min(sanitize(m_cap));
}

/// The reconnection shift: the Jacobian, its singularities and its window.
pub mod jacobian;

#[cfg(test)]
mod toy_scene;

#[cfg(test)]
mod tests;

#[cfg(test)]
mod visibility_tests;

#[cfg(test)]
mod unit_tests;
