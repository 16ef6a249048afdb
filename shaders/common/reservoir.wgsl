// Reservoir math, mirrored line by line in render/src/reservoir.rs (tested there).
#include "common/types.wgsl"
#include "common/math.wgsl"

fn reservoir_empty() -> Reservoir {
    return Reservoir(NO_LIGHT, 0.0, vec2<f32>(0.0), 0.0, 0.0, 0.0, SOURCE_NULL);
}

fn reservoir_is_null(r: Reservoir) -> bool {
    return r.light == NO_LIGHT || !(r.weight > 0.0) || !is_finite_f32(r.weight);
}

// A weight, sum or M that is negative or not finite cannot be trusted: the reservoir is
// treated as null (the caller counts it) rather than propagated (docs/src/ris.md, "Conventions").
fn reservoir_is_corrupt(r: Reservoir) -> bool {
    let ok = is_finite_f32(r.weight) && r.weight >= 0.0 && is_finite_f32(r.w_sum) && r.w_sum >= 0.0
        && is_finite_f32(r.m) && r.m >= 0.0 && is_finite_f32(r.p_hat) && r.p_hat >= 0.0;
    return !ok;
}

fn is_positive_finite(x: f32) -> bool {
    return x > 0.0 && is_finite_f32(x);
}

// Negative, NaN and infinite confidences count as nothing seen.
fn sanitize(x: f32) -> f32 {
    return select(0.0, max(x, 0.0), is_finite_f32(x));
}

// Streaming weighted selection: keep the candidate with probability w / w_sum. A weight or
// target that is not finite and positive cannot contribute and is ignored; w_sum saturates
// instead of overflowing.
// The SOURCE_* of a reservoir, and the age of its sample (frames since it was first
// drawn), packed together in `source` (see shader_constants.rs).
fn reservoir_source(r: Reservoir) -> u32 {
    return r.source & SOURCE_MASK;
}

fn reservoir_age(r: Reservoir) -> u32 {
    return r.source >> AGE_SHIFT;
}

fn source_with_age(source: u32, age: u32) -> u32 {
    return source | (min(age, AGE_MAX) << AGE_SHIFT);
}

fn reservoir_update(r: ptr<function, Reservoir>, light: u32, uv: vec2<f32>, w: f32, p_hat: f32, source: u32, u: f32) -> bool {
    if !is_positive_finite(w) || !is_positive_finite(p_hat) {
        return false;
    }
    (*r).w_sum = min((*r).w_sum + w, FLT_MAX);
    // The null check only matters once w_sum saturated: the first candidate is always kept.
    if (*r).light == NO_LIGHT || u * (*r).w_sum < w {
        (*r).light = light;
        (*r).uv = uv;
        (*r).p_hat = p_hat;
        (*r).source = source;
        return true;
    }
    return false;
}

// W = w_sum / (normalization · p̂). A reservoir that cannot form a finite positive W is
// null, and a null sample stays null (never redrawn).
fn reservoir_finalize(r: ptr<function, Reservoir>, normalization: f32) {
    let w = (*r).w_sum / (normalization * (*r).p_hat);
    let valid = (*r).light != NO_LIGHT && is_positive_finite((*r).w_sum) && is_positive_finite(normalization)
        && is_positive_finite((*r).p_hat) && is_positive_finite(w);
    if valid {
        (*r).weight = w;
    } else {
        (*r).light = NO_LIGHT;
        (*r).weight = 0.0;
        (*r).w_sum = 0.0;
        (*r).p_hat = 0.0;
        (*r).source = SOURCE_NULL;
    }
}

// The candidate step of a merge with an explicit MIS weight (pairwise MIS):
// w = p̂_here · W_other · mis_weight. M is left to the caller.
fn reservoir_merge_mis(r: ptr<function, Reservoir>, other: Reservoir, target_here: f32, mis_weight: f32, source: u32, u: f32) -> bool {
    if other.light == NO_LIGHT {
        return false;
    }
    return reservoir_update(r, other.light, other.uv, target_here * other.weight * mis_weight, target_here, source, u);
}

// Another reservoir's sample as one candidate standing for `m_rep` candidates
// (docs/src/temporal-reuse.md, "The merge"): w = p̂_here · W_other · m_rep. M grows even when the
// candidate loses.
fn reservoir_merge(r: ptr<function, Reservoir>, other: Reservoir, target_here: f32, m_rep: f32, source: u32, u: f32) -> bool {
    (*r).m = min((*r).m + sanitize(m_rep), FLT_MAX);
    return reservoir_merge_mis(r, other, target_here, m_rep, source, u);
}

fn clamp_unit(x: f32) -> f32 {
    return select(clamp(x, 0.0, 1.0), 0.0, x != x);
}

// c / c_total in [0, 1]; 0 when either is degenerate.
fn confidence_share(c: f32, c_total: f32) -> f32 {
    return clamp_unit(sanitize(c) / sanitize(c_total));
}

// a / (a + b) for non-negative a, b in [0, 1]; 0/0 (and any overflow) gives 0.
fn balance(a: f32, b: f32) -> f32 {
    let sa = sanitize(a);
    return clamp_unit(sa / (sa + sanitize(b)));
}

// Defensive pairwise MIS with confidence weights (docs/src/mis-and-bias.md, "Pairwise MIS";
// Bitterli 2022): the pair (canonical, neighbour j) at a point y splits the neighbour's share c_j /
// c_total in proportion (c_total − c_c)·p̂_j(y) : c_c·p̂_c(y). Mirrors render/src/reservoir.rs.
fn pairwise_mis_noncanonical(c_total: f32, c_canonical: f32, c_i: f32, p_hat_i_at_y: f32, p_hat_c_at_y: f32) -> f32 {
    let neighbour = max(c_total - c_canonical, 0.0) * p_hat_i_at_y;
#ifdef PLANTED_DROPPED_ONE_OVER_M
    // The bias matrix's planted twin (render/tests/bias_matrix.rs): the neighbour's share
    // c_i / c_total dropped, so the weights no longer sum to one.
    return balance(neighbour, c_canonical * p_hat_c_at_y);
#else
    return confidence_share(c_i, c_total) * balance(neighbour, c_canonical * p_hat_c_at_y);
#endif
}

// One neighbour's term of the canonical sample's weight c_c / c_total + Σ_j term_j.
fn pairwise_mis_canonical_term(c_total: f32, c_canonical: f32, c_j: f32, p_hat_c_at_yc: f32, p_hat_j_at_yc: f32) -> f32 {
    let neighbour = max(c_total - c_canonical, 0.0) * p_hat_j_at_yc;
    return confidence_share(c_j, c_total) * balance(c_canonical * p_hat_c_at_yc, neighbour);
}
