// ReSTIR GI reservoir math (Ouyang et al. 2021; docs/src/restir-gi.md), mirrored line by line in
// render/src/gi/model.rs and model/jacobian.rs, where it is tested against an exactly
// integrated scene. Same streaming, finalisation and null-sample rules as reservoir.wgsl.
// A GI sample lives in solid angle at its pixel's visible point: reuse at another pixel
// goes through the reconnection Jacobian, in the resampling weight (p̂_here · W · |J|) and
// in the pairwise MIS weights (every target expressed in this pixel's measure).
#include "common/types.wgsl"
#include "common/math.wgsl"
#include "common/reservoir.wgsl"
#include "common/reconnection.wgsl"

// ---- packed: SOURCE_* | GI rejection bits << GI_FLAGS_SHIFT | age << GI_AGE_SHIFT ----

fn gi_pack(source: u32, flags: u32, age: u32) -> u32 {
    return (source & GI_SOURCE_MASK) | ((flags & GI_FLAGS_MASK) << GI_FLAGS_SHIFT) | (min(age, GI_AGE_MAX) << GI_AGE_SHIFT);
}

fn gi_source(r: GiReservoir) -> u32 {
    return r.packed & GI_SOURCE_MASK;
}

fn gi_flags(r: GiReservoir) -> u32 {
    return (r.packed >> GI_FLAGS_SHIFT) & GI_FLAGS_MASK;
}

fn gi_age(r: GiReservoir) -> u32 {
    return r.packed >> GI_AGE_SHIFT;
}

// A stage records its rejection mask on the reservoir it writes (the debug views read it).
fn gi_set_flags(r: ptr<function, GiReservoir>, flags: u32) {
    (*r).packed = ((*r).packed & ~(GI_FLAGS_MASK << GI_FLAGS_SHIFT)) | ((flags & GI_FLAGS_MASK) << GI_FLAGS_SHIFT);
}

// ---- the reservoir ----

fn gi_reservoir_empty() -> GiReservoir {
    return GiReservoir(vec3<f32>(0.0), 0u, vec3<f32>(0.0), 0.0, 0.0, 0.0, 0.0, gi_pack(SOURCE_NULL, 0u, 0u));
}

fn gi_reservoir_is_null(r: GiReservoir) -> bool {
    return gi_source(r) == SOURCE_NULL || !is_positive_finite(r.weight);
}

// Weights that are negative or not finite, or a sample that is not finite: never propagate
// it (the caller counts it and uses the null reservoir instead).
fn gi_reservoir_is_corrupt(r: GiReservoir) -> bool {
    let weights = is_finite_f32(r.weight) && r.weight >= 0.0 && is_finite_f32(r.w_sum) && r.w_sum >= 0.0
        && is_finite_f32(r.m) && r.m >= 0.0 && is_finite_f32(r.p_hat) && r.p_hat >= 0.0;
    return !(weights && is_finite_vec3(r.position) && is_finite_vec3(r.radiance));
}

// ---- the reconnection shift (render/src/gi/model/jacobian.rs) ----


// |J| = (|cos φ_to| / |cos φ_from|) · (‖seen_from − x_s‖² / ‖reused_at − x_s‖²) for a sample at
// `sample_position` (normal `sample_normal`, either orientation) found from `seen_from` and
// reused at `reused_at`; 0 where the shift is undefined: distance → 0 or out of range, a
// grazing cosine at either end, `reused_at` behind the sample's surface, non-finite input. The guards come before
// every division, so nothing here overflows (WGSL leaves that indeterminate).
fn gi_reconnection_jacobian(sample_position: vec3<f32>, sample_normal: vec3<f32>, seen_from: vec3<f32>, reused_at: vec3<f32>) -> f32 {
    let n_len2 = dot(sample_normal, sample_normal);
    if !(n_len2 > 1e-30 && n_len2 <= FLT_MAX) {
        return 0.0;
    }
    let n = sample_normal * inverseSqrt(n_len2);
    let to_from = seen_from - sample_position;
    let to_to = reused_at - sample_position;
    let d2_from = dot(to_from, to_from);
    let d2_to = dot(to_to, to_to);
    if !(reconnection_distance_in_range(d2_from) && reconnection_distance_in_range(d2_to)) {
        return 0.0;
    }
    let cos_from = dot(n, to_from) / sqrt(d2_from);
    let cos_to = dot(n, to_to) / sqrt(d2_to);
    let usable = abs(cos_from) >= RECONNECTION_MIN_COS && abs(cos_to) >= RECONNECTION_MIN_COS && ((cos_from > 0.0) == (cos_to > 0.0));
    if !usable {
        return 0.0;
    }
    let j = (abs(cos_to) * d2_from) / (abs(cos_from) * d2_to);
    return select(0.0, j, is_positive_finite(j));
}

// j in [1/j_max, j_max]; j_max below 1 acts as 1.
fn gi_jacobian_in_window(j: f32, j_max: f32) -> bool {
    let jm = max(j_max, 1.0);
    return is_positive_finite(j) && j >= 1.0 / jm && j <= jm;
}

// 0 when a Jacobian from gi_reconnection_jacobian may be used, else the GI rejection bit.
fn gi_shift_rejection(j: f32, j_max: f32) -> u32 {
    if !is_positive_finite(j) {
        return GI_REJECT_RECONNECTION;
    }
    return select(GI_REJECT_JACOBIAN, 0u, gi_jacobian_in_window(j, j_max));
}

// ---- target and weights (render/src/gi/model.rs) ----

// p̂ = luminance(f_r · L_o · cos θ): the sample's contribution at the receiving pixel.
fn gi_target(f_r: vec3<f32>, radiance: vec3<f32>, cos_theta: f32) -> f32 {
    let p = luminance(f_r * radiance * max(cos_theta, 0.0));
    return select(0.0, p, is_positive_finite(p));
}

// cos θ at `position` (unit `normal`) toward the sample point, clamped at 0.
fn gi_receiver_cosine(position: vec3<f32>, normal: vec3<f32>, sample_position: vec3<f32>) -> f32 {
    let d = sample_position - position;
    let len2 = dot(d, d);
    if !(len2 > 1e-30 && len2 <= FLT_MAX) {
        return 0.0;
    }
    let c = dot(normal, d) * inverseSqrt(len2);
    return select(0.0, min(c, 1.0), c > 0.0);
}

// Initial RIS weight p̂ / (N · p_src) of one of N candidates from one strategy.
fn gi_initial_weight(p_hat: f32, source_pdf: f32, candidates: f32) -> f32 {
    if !(is_positive_finite(p_hat) && is_positive_finite(source_pdf) && is_positive_finite(candidates)) {
        return 0.0;
    }
    let w = p_hat / (candidates * source_pdf);
    return select(0.0, w, is_positive_finite(w));
}

// Streams one candidate (keep with probability w / w_sum). `packed` gives the candidate's
// source and age; the reservoir keeps its own rejection flags.
fn gi_reservoir_update(r: ptr<function, GiReservoir>, position: vec3<f32>, normal: u32, radiance: vec3<f32>, w: f32, p_hat: f32, packed: u32, u: f32) -> bool {
    if !is_positive_finite(w) || !is_positive_finite(p_hat) {
        return false;
    }
    // Nothing selected yet ⇔ w_sum = 0 (every accepted candidate adds a positive weight).
    let first = !((*r).w_sum > 0.0);
    (*r).w_sum = min((*r).w_sum + w, FLT_MAX);
    if first || u * (*r).w_sum < w {
        let flag_bits = GI_FLAGS_MASK << GI_FLAGS_SHIFT;
        (*r).position = position;
        (*r).normal = normal;
        (*r).radiance = radiance;
        (*r).p_hat = p_hat;
        (*r).packed = (packed & ~flag_bits) | ((*r).packed & flag_bits);
        return true;
    }
    return false;
}

// W = w_sum / (normalization · p̂); a reservoir that cannot form a finite positive W becomes
// null (its flags kept), and a null sample stays null.
fn gi_reservoir_finalize(r: ptr<function, GiReservoir>, normalization: f32) {
    let inputs = (*r).w_sum > 0.0 && is_positive_finite((*r).w_sum) && is_positive_finite(normalization)
        && is_positive_finite((*r).p_hat);
    let w = select(0.0, (*r).w_sum / (normalization * (*r).p_hat), inputs);
    if inputs && is_positive_finite(w) {
        (*r).weight = w;
    } else {
        let m = (*r).m;
        let flags = gi_flags(*r);
        *r = gi_reservoir_empty();
        (*r).m = m;
        gi_set_flags(r, flags);
    }
}

// The candidate step with an explicit MIS weight (pairwise): w = p̂_here · W · m_i · |J|.
// The stored target is p̂_here, never p̂_here · |J|. `jacobian` = 0: the shift failed.
fn gi_reservoir_merge_mis(r: ptr<function, GiReservoir>, other: GiReservoir, target_here: f32, jacobian: f32, mis_weight: f32, packed: u32, u: f32) -> bool {
    if gi_reservoir_is_null(other) {
        return false;
    }
    let w = target_here * other.weight * (sanitize(mis_weight) * sanitize(jacobian));
    return gi_reservoir_update(r, other.position, other.normal, other.radiance, w, target_here, packed, u);
}

// 1/M merge of a shifted reservoir standing for `m_rep` candidates: M grows by m_rep even
// when the sample cannot be used here (1/M with rejection, see render/src/gi/model.rs).
fn gi_reservoir_merge(r: ptr<function, GiReservoir>, other: GiReservoir, target_here: f32, jacobian: f32, m_rep: f32, packed: u32, u: f32) -> bool {
    (*r).m = min((*r).m + sanitize(m_rep), FLT_MAX);
    return gi_reservoir_merge_mis(r, other, target_here, jacobian, m_rep, packed, u);
}

fn gi_cap_confidence(r: ptr<function, GiReservoir>, m_cap: f32) {
    (*r).m = min((*r).m, sanitize(m_cap));
}
