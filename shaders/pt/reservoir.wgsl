// ReSTIR PT path reservoirs (docs/src/restir-pt.md): packing, streaming and finalisation, with
// the same rules as the GI reservoir (gi/reservoir.wgsl: null samples, finite guards) and its
// pairwise weights (shifted_pairwise_*). A path is one sample; its record (PtReservoir in
// types.wgsl) is copied whole when it is picked.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reconnection.wgsl"

// ---- packed: source | n << 4 | end << 8 | k << 9 | lobes << 13 ----
// n: the path's last surface vertex x_n (2..max_bounces); end: PT_END_*; k: the step that
// is reconnected (y_k → x_{k+1}), PT_RC_NONE for a pure replay; lobes: bit b = the lobe
// that sampled ω_b at x_b (PT_LOBE_*, b = 1..8). Shifts report why they failed as
// PT_FAIL_*. These constants, and the packing, are render/src/shader_constants.rs's and
// the inspector's (renderer/inspect_pt.rs) as well.

fn pt_pack(source: u32, n: u32, end: u32, k: u32, lobes: u32) -> u32 {
    return (source & 0xfu) | ((n & 0xfu) << 4u) | ((end & 1u) << 8u) | ((k & 0xfu) << 9u) | ((lobes & 0x1ffu) << 13u);
}

fn pt_source(r: PtReservoir) -> u32 {
    return r.packed & 0xfu;
}

fn pt_n(r: PtReservoir) -> u32 {
    return (r.packed >> 4u) & 0xfu;
}

fn pt_end(r: PtReservoir) -> u32 {
    return (r.packed >> 8u) & 1u;
}

fn pt_k(r: PtReservoir) -> u32 {
    return (r.packed >> 9u) & 0xfu;
}

fn pt_lobes(r: PtReservoir) -> u32 {
    return (r.packed >> 13u) & 0x1ffu;
}

fn pt_lobe(lobes: u32, bounce: u32) -> u32 {
    return (lobes >> bounce) & 1u;
}

fn pt_with_source(packed: u32, source: u32) -> u32 {
    return (packed & ~0xfu) | (source & 0xfu);
}

fn pt_light(r: PtReservoir) -> LightSampleId {
    return LightSampleId(r.light, vec2<f32>(r.light_u, r.light_v));
}

// ---- the reservoir ----

fn pt_reservoir_empty() -> PtReservoir {
    return PtReservoir(vec3<f32>(0.0), 0.0, 0.0, 0.0, 0.0, 0u, pt_pack(SOURCE_NULL, 0u, 0u, PT_RC_NONE, 0u),
        0u, 0.0, 0.0, 0u, NO_LIGHT, 0.0, 0.0, vec3<f32>(0.0), 0.0, 0.0, 0.0, 1.0, 0u);
}

fn pt_reservoir_is_null(r: PtReservoir) -> bool {
    return pt_source(r) == SOURCE_NULL || !is_positive_finite(r.weight);
}

fn pt_reservoir_is_corrupt(r: PtReservoir) -> bool {
    let weights = is_finite_f32(r.weight) && r.weight >= 0.0 && is_finite_f32(r.w_sum) && r.w_sum >= 0.0
        && is_finite_f32(r.m) && r.m >= 0.0 && is_finite_f32(r.p_hat) && r.p_hat >= 0.0;
    return !(weights && is_finite_vec3(r.value) && is_finite_vec3(r.rc_suffix) && is_finite_f32(r.replay_pdf));
}

// A reservoir read from another pixel, or null (counted against GI pass `pass_id`: the
// indirect passes share their counters) when it is corrupt.
fn pt_checked(r: PtReservoir, pass_id: u32) -> PtReservoir {
    if pt_reservoir_is_corrupt(r) {
        count_stat(STAT_INDIRECT_NONFINITE + pass_id);
        return pt_reservoir_empty();
    }
    return r;
}

// The reservoir a stage writes: null (with M 1) instead of anything corrupt.
fn pt_guarded(r: PtReservoir, pass_id: u32) -> PtReservoir {
    if pt_reservoir_is_corrupt(r) {
        count_stat(STAT_INDIRECT_NONFINITE + pass_id);
        var empty = pt_reservoir_empty();
        empty.m = 1.0;
        return empty;
    }
    return r;
}

// Streams one candidate path `sample` (its record; value and p̂ at this pixel) with RIS
// weight w: kept with probability w / w_sum.
fn pt_reservoir_update(r: ptr<function, PtReservoir>, sample: PtReservoir, w: f32, u: f32) -> bool {
    if !is_positive_finite(w) || !is_positive_finite(sample.p_hat) {
        return false;
    }
    let first = !((*r).w_sum > 0.0);
    let w_sum = min((*r).w_sum + w, FLT_MAX);
    let m = (*r).m;
    if first || u * w_sum < w {
        *r = sample;
        (*r).m = m;
    }
    (*r).w_sum = w_sum;
    (*r).weight = 0.0;
    return first || u * w_sum < w;
}

// W = w_sum / p̂ (M-normalised weights are already in w); null when it cannot be formed.
fn pt_reservoir_finalize(r: ptr<function, PtReservoir>) {
    let ok = (*r).w_sum > 0.0 && is_positive_finite((*r).w_sum) && is_positive_finite((*r).p_hat);
    let w = select(0.0, (*r).w_sum / (*r).p_hat, ok);
    if ok && is_positive_finite(w) {
        (*r).weight = w;
    } else {
        let m = (*r).m;
        *r = pt_reservoir_empty();
        (*r).m = m;
    }
}
