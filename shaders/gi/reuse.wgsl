// What every ReSTIR GI pass shares (docs/src/restir-gi.md): a GI sample's target at a shading
// point, the guard against corrupt reservoirs, and the per-pixel GI debug record. The reservoir
// math itself is gi/reservoir.wgsl (mirrored and tested in gi/model.rs).
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "gi/reservoir.wgsl"

fn gi_flag_on(bit: u32) -> bool {
    return (params.flags & bit) != 0u;
}

// MIS visibility (the canonical sample's weight asks whether each neighbour sees it) only
// together with reconnection visibility: both make visibility part of the target. With
// reconnection visibility off the neighbours' samples are merged unshadowed, and weights
// that assume a shadowed target no longer sum to one: samples fed back through temporal
// reuse grew without bound (W 1e19 after 256 frames on builtin:cornell).
fn gi_mis_visibility() -> bool {
    return gi_flag_on(PARAM_FLAG_GI_MIS_VISIBILITY) && gi_flag_on(PARAM_FLAG_GI_SPATIAL_VISIBILITY);
}

// p̂ of the GI sample (x_s, L_o) at a receiving shading point: luminance(f_r · L_o · cos θ),
// 0 when x_s is below the receiver's geometric or shading hemisphere.
fn gi_target_at(sp: ShadingPoint, sample_position: vec3<f32>, radiance: vec3<f32>) -> f32 {
    let d = sample_position - sp.position;
    let len2 = dot(d, d);
    if !(len2 > 0.0) || dot(sp.geo_normal, d) <= 0.0 {
        return 0.0;
    }
    let wi = d * inverseSqrt(len2);
    let cos_theta = gi_receiver_cosine(sp.position, sp.normal, sample_position);
    return gi_target(eval_brdf(sp.brdf, sp.normal, sp.wo, wi), radiance, cos_theta);
}

// A GI reservoir read from another pixel or frame, or null (counted against GI pass
// `pass_id`) when its weights or sample are not finite.
fn gi_checked(r: GiReservoir, pass_id: u32) -> GiReservoir {
    if gi_reservoir_is_corrupt(r) {
        count_stat(STAT_INDIRECT_NONFINITE + pass_id);
        return gi_reservoir_empty();
    }
    return r;
}

// The reservoir a stage writes: null (with M 1) instead of anything corrupt.
fn gi_guarded(r: GiReservoir, pass_id: u32) -> GiReservoir {
    if gi_reservoir_is_corrupt(r) {
        count_stat(STAT_INDIRECT_NONFINITE + pass_id);
        var empty = gi_reservoir_empty();
        empty.m = 1.0;
        return empty;
    }
    return r;
}

// The shift of a GI sample from the receiver `seen_from` to `reused_at`: its |J| (0 when undefined)
// and the rejection bit it earns (0 when usable).
struct GiShift {
    jacobian: f32,
    reject: u32,
}

fn gi_shift(r: GiReservoir, seen_from: vec3<f32>, reused_at: vec3<f32>) -> GiShift {
    let j = gi_reconnection_jacobian(r.position, oct_decode(r.normal), seen_from, reused_at);
    let reject = gi_shift_rejection(j, params.gi.jacobian_max);
#ifdef PLANTED_GI_NO_JACOBIAN
    // Test-only planted error (render/tests/restir_gi.rs): reuse as if |J| were 1.
    return GiShift(select(0.0, 1.0, j > 0.0), reject);
#else
#ifdef PLANTED_GI_INVERTED_JACOBIAN
    // Test-only planted error: the shift's Jacobian the wrong way round.
    return GiShift(select(0.0, 1.0 / j, j > 0.0), reject);
#else
    return GiShift(j, reject);
#endif
#endif
}

// Whether the segment from the receiver to the sample point is free (reconnection
// visibility; the sample's own surface is excluded by offsetting both ends).
fn gi_reconnection_visible(sp: ShadingPoint, r: GiReservoir) -> bool {
    let n_s = oct_decode(r.normal);
    let toward = select(-n_s, n_s, dot(n_s, sp.position - r.position) > 0.0);
    // Through glass: free when light gets through. The sample's radiance keeps the tint of
    // the glass its own path crossed (a documented GI approximation, docs/src/restir-gi.md,
    // "Through glass").
    let tr = trace_transmittance(segment_ray(sp.position, sp.geo_normal, r.position, toward));
    return any(tr.value > vec3<f32>(0.0));
}
