// MCMC mutation of each pixel's DI sample (docs/src/mcmc-mutation.md; Sawhney et al. 2024,
// "Decorrelating ReSTIR Samplers via MCMC Mutations"): `params.di.mutations` Metropolis–Hastings
// steps toward this pixel's own target T, after the last reuse pass and before shading.
// A kernel that leaves T invariant keeps the contribution weight unbiased when
// W' = W · T(y) / T(y') (the book derives it); w_sum and M stay as they are. Each step is,
// with probability 1/2 each:
//  - a local move: the point slides on its triangle light, uv' = uv + δ, δ uniform in
//    [−s, s]² (s = mutation_step, barycentric units); symmetric and on one triangle (whose
//    area is the same at both ends), so it is accepted with T(y') / T(y). A sample on any
//    other kind of light stays where it is (the identity leaves T invariant too).
//  - an independent move: a fresh sample from the power table, q its density (per area on
//    a triangle: select_pdf / area; discrete for punctual lights; per steradian for the
//    sky), accepted with T(y') q(y) / (T(y) q(y')).
// T carries visibility where reuse's targets do (pairwise MIS with mis_visibility): the
// proposal's shadow ray is traced only when the unshadowed ratio could accept it. The
// mutated reservoir is also next frame's history, so temporal chains decorrelate too.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> reservoirs_in: array<Reservoir>;
@group(2) @binding(2) var<storage, read_write> reservoirs_out: array<Reservoir>;

// The power table's density of a light sample, in the sample's own measure.
fn proposal_density(light: u32, uv: vec2<f32>) -> f32 {
#ifdef PLANTED_MCMC_PROPOSAL_WITHOUT_AREA
    return lights[light].select_pdf;  // test only: the triangle's 1/area (the Jacobian) left out
#else
    return light_point(light, uv).source_pdf;
#endif
}

fn inside_triangle(uv: vec2<f32>) -> bool {
    return uv.x >= 0.0 && uv.y >= 0.0 && uv.x + uv.y <= 1.0;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    var r = checked_reservoir(reservoirs_in[index], PASS_MUTATION);
    let s = surfaces[index];
    if !surface_is_valid(s) || reservoir_is_null(r) || !is_positive_finite(r.p_hat) {
        reservoirs_out[index] = r;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = pcg_hash(rng_seed(id.xy, STREAM_INITIAL) ^ MUTATION_STREAM_SALT);
    let visibility = pairwise_mis() && mis_visibility();
    let steps = min(params.di.mutations, MAX_MUTATIONS);
    var rays = 0u;
    var accepted = 0u;
    for (var i = 0u; i < steps; i++) {
        let local = rand_f32(&rng) < 0.5;
        let u_move = rand_vec2(&rng);
        let u_accept = rand_f32(&rng);
        var y = LightSampleId(r.light, r.uv);
        var proposal_ratio = 1.0;  // q(y) / q(y')
        if local {
            if light_kind_of(lights[r.light]) != LIGHT_KIND_TRIANGLE {
                continue;
            }
            y.uv = r.uv + (u_move * 2.0 - 1.0) * params.di.mutation_step;
            if !inside_triangle(y.uv) {
                continue;
            }
        } else {
            y = sample_light(&rng);
            let q_new = proposal_density(y.light, y.uv);
            if !(q_new > 0.0) {
                continue;
            }
            proposal_ratio = proposal_density(r.light, r.uv) / q_new;
        }
        let lp = light_point(y.light, y.uv);
        let c = light_contribution(sp, lp);
        var t_new = target_pdf(c);
#ifdef PLANTED_MCMC_NO_TARGET_RATIO
        var ratio = proposal_ratio;  // test only: the target left out of the acceptance
#else
        var ratio = t_new / r.p_hat * proposal_ratio;
#endif
        if !(t_new > 0.0) || !(u_accept < ratio) {
            continue;
        }
        if visibility {
            rays += 1u;
            let v = light_visibility(sp, lp, c);
            t_new *= v;
            ratio *= v;
            if !(t_new > 0.0) || !(u_accept < ratio) {
                continue;
            }
        }
        accepted += 1u;
#ifndef PLANTED_MCMC_WEIGHT_KEPT
        r.weight *= r.p_hat / t_new;
#endif
        r.light = y.light;
        r.uv = y.uv;
        r.p_hat = t_new;
    }
    if reservoir_is_corrupt(r) {
        count_stat(STAT_NONFINITE + PASS_MUTATION);
        r = reservoir_empty();
    }
    add_stat(STAT_MUTATIONS_TRIED, steps);
    add_stat(STAT_MUTATIONS_ACCEPTED, accepted);
    add_stat(STAT_SHADOW_RAYS + PASS_MUTATION, rays);
    reservoirs_out[index] = r;
}
