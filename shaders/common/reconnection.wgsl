// What ReSTIR GI and ReSTIR PT share: a sample (GI's secondary vertex, PT's reconnection
// vertex) found from one point and reused from another, and pairwise MIS across pixels
// whose targets live in different measures. Mirrored in render/src/gi/model.rs and
// render/src/gi/model/jacobian.rs, tested against an exactly integrated scene.
#include "common/math.wgsl"
#include "common/reservoir.wgsl"

// The squared distances a reconnection may span: below the minimum the Jacobian's
// 1/distance² blows up, above the maximum it underflows (shader_constants.rs).
fn reconnection_distance_in_range(d2: f32) -> bool {
    return d2 >= RECONNECTION_MIN_DISTANCE_SQ && d2 <= RECONNECTION_MAX_DISTANCE_SQ;
}

// ---- pairwise MIS with shifted samples (render/src/gi/model.rs, resample_with) ----
// A sample reused at another pixel moves through a shift with Jacobian |J| (GI's
// reconnection, PT's shift mappings): every target in these weights is expressed in this
// pixel's measure.

// Neighbour i's sample y (shifted here with |J_{i→here}| = jacobian_i_to_here): its pairwise
// weight, with p̂_i(y) brought into this pixel's measure (p̂_i / |J_{i→here}|).
fn shifted_pairwise_noncanonical(c_total: f32, c_canonical: f32, c_i: f32, p_hat_i_at_y: f32, p_hat_here_at_y: f32, jacobian_i_to_here: f32) -> f32 {
    let p_i = select(0.0, p_hat_i_at_y / jacobian_i_to_here, is_positive_finite(jacobian_i_to_here));
    return pairwise_mis_noncanonical(c_total, c_canonical, c_i, p_i, p_hat_here_at_y);
}

// Neighbour j's term of the canonical sample's weight (c_c / c_total + Σ_j terms), with
// p̂_j(y_c) · |J_{here→j}|. Pass jacobian_here_to_j = 0 when that shift fails, is outside
// the window, or x_j does not see y_c's point (GI's MIS visibility; a PT path that
// cannot be shifted there): then j could not have found y_c, and counting it anyway
// darkens reuse behind occluders (render/src/gi/model.rs).
fn shifted_pairwise_canonical_term(c_total: f32, c_canonical: f32, c_j: f32, p_hat_here_at_yc: f32, p_hat_j_at_yc: f32, jacobian_here_to_j: f32) -> f32 {
    let p_j = p_hat_j_at_yc * sanitize(jacobian_here_to_j);
    return pairwise_mis_canonical_term(c_total, c_canonical, c_j, p_hat_here_at_yc, p_j);
}
