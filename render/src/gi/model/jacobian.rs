//! The reconnection shift of ReSTIR GI (Ouyang et al. 2021, eq. 11; the shift-map view of
//! Lin et al. 2022, GRIS): a GI sample found from pixel q's visible point `x_q` keeps its
//! sample point `x_s` and is reconnected to pixel r's visible point `x_r`. Its density is in
//! solid angle at the receiver, so moving it changes measure by
//!
//! ```text
//! |J_{q→r}| = dω_r/dω_q = (|cos φ_r| / |cos φ_q|) · (‖x_q − x_s‖² / ‖x_r − x_s‖²),
//! ```
//!
//! φ being the angle at `x_s` between `n_s` and the direction to the receiving point: the same
//! patch dA around `x_s` subtends dω = |cos φ| dA / d² from either point, and the ratio of the
//! two is the Jacobian (checked against exactly that in the tests). A sample moved from q to r
//! has resampling weight `p̂_r(y) · W_q · |J_{q→r}|` (its `W` is per steradian at q).
//!
//! The shift is *undefined* (no Jacobian, the sample cannot be used at r) where the formula
//! breaks: a distance near 0 (x_s on the receiver: the patch fills the hemisphere), a grazing
//! cosine (the patch has no solid angle), or a receiver on the other side of the sample's
//! surface (the cached radiance left the side q saw; the back face's is unknown). The
//! conditions are symmetric in q and r, and so is the window `[1/j_max, j_max]`
//! (`jacobian_in_window`) since `J_{r→q} = 1/J_{q→r}`: pairwise MIS relies on that (a shift
//! q→r is usable exactly when the shift r→q is). `shaders/gi/reservoir.wgsl` mirrors
//! this file with the same thresholds.

use glam::Vec3;

pub use crate::gi::constants::{
    RECONNECTION_MAX_DISTANCE_SQ, RECONNECTION_MIN_COS, RECONNECTION_MIN_DISTANCE_SQ,
};
use crate::shader_constants::{GI_REJECT_JACOBIAN, GI_REJECT_RECONNECTION};

/// `|J_{from→to}|` of the reconnection of a sample at `sample_position` (surface normal
/// `sample_normal`, either orientation, need not be unit length) from the receiving point
/// `seen_from` (where it was found) to the receiving point `reused_at`; `None` where the
/// shift is undefined (module docs): degenerate or non-finite input, a distance outside [`RECONNECTION_MIN_DISTANCE_SQ`,
/// `RECONNECTION_MAX_DISTANCE_SQ`], |cos φ| below [`RECONNECTION_MIN_COS`] at either end, or `reused_at` on the
/// other side of the sample's surface than `seen_from`. Never NaN or infinite.
pub fn reconnection_jacobian(
    sample_position: Vec3,
    sample_normal: Vec3,
    seen_from: Vec3,
    reused_at: Vec3,
) -> Option<f32> {
    let n = normalized(sample_normal)?;
    let to_from = seen_from - sample_position;
    let to_to = reused_at - sample_position;
    let d2_from = to_from.length_squared();
    let d2_to = to_to.length_squared();
    if !(distance_in_range(d2_from) && distance_in_range(d2_to)) {
        return None;
    }
    let cos_from = n.dot(to_from) / d2_from.sqrt();
    let cos_to = n.dot(to_to) / d2_to.sqrt();
    // Same side (the sign test also fails for NaN), neither grazing.
    let usable = cos_from.abs() >= RECONNECTION_MIN_COS
        && cos_to.abs() >= RECONNECTION_MIN_COS
        && (cos_from > 0.0) == (cos_to > 0.0);
    if !usable {
        return None;
    }
    let j = (cos_to.abs() * d2_from) / (cos_from.abs() * d2_to);
    (j.is_finite() && j > 0.0).then_some(j)
}

/// `v / |v|`, or `None` for |v|² not in (1e-30, f32::MAX] (the WGSL twin's test).
pub(super) fn normalized(v: Vec3) -> Option<Vec3> {
    let len2 = v.length_squared();
    (len2 > 1e-30 && len2 <= f32::MAX).then(|| v / len2.sqrt())
}

fn distance_in_range(d2: f32) -> bool {
    (RECONNECTION_MIN_DISTANCE_SQ..=RECONNECTION_MAX_DISTANCE_SQ).contains(&d2)
}

/// Whether a Jacobian may be used: `j` in `[1/j_max, j_max]` (Ouyang et al. reject large
/// Jacobians: a sample reused from a pixel that saw it much smaller or larger carries a
/// weight out of proportion with its neighbours, the source of GI's fireflies and dark
/// blotches). `j_max` below 1 or NaN acts as 1 (only J = 1 passes); a non-finite or
/// non-positive `j` never passes.
pub fn jacobian_in_window(j: f32, j_max: f32) -> bool {
    let j_max = if j_max.is_nan() { 1.0 } else { j_max.max(1.0) };
    j.is_finite() && j > 0.0 && j >= 1.0 / j_max && j <= j_max
}

/// The reconnection from `seen_from` to `reused_at` as reuse sees it: `Ok(|J|)` when the
/// shift is defined and its Jacobian inside the window, otherwise the GI rejection bit that says why
/// (`GI_REJECT_RECONNECTION`: undefined; `GI_REJECT_JACOBIAN`: outside the window).
pub fn reconnection_shift(
    sample_position: Vec3,
    sample_normal: Vec3,
    seen_from: Vec3,
    reused_at: Vec3,
    j_max: f32,
) -> Result<f32, u32> {
    let j = reconnection_jacobian(sample_position, sample_normal, seen_from, reused_at)
        .ok_or(GI_REJECT_RECONNECTION)?;
    if jacobian_in_window(j, j_max) {
        Ok(j)
    } else {
        Err(GI_REJECT_JACOBIAN)
    }
}

#[cfg(test)]
#[path = "jacobian_tests.rs"]
mod tests;
