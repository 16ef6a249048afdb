// ReSTIR GI temporal reuse (Ouyang et al. 2021 §3.2): reproject into the previous frame,
// validate the previous surface (DI's checks and bits) and reservoir, shift the previous
// sample from the previous visible point to this one with the reconnection Jacobian
// (rejected outside [1/gi_jacobian_max, gi_jacobian_max]), rescore it here and merge:
// 1/M with p̂_here · W_prev · |J| · min(M_prev, gi_m_cap), or pairwise MIS (the initial
// sample canonical, its target at the previous visible point through |J_here→prev|).
#include "gi/reuse.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> prev_surfaces: array<Surface>;
@group(2) @binding(2) var<storage, read> gi_in: array<GiReservoir>;
@group(2) @binding(3) var<storage, read> gi_prev: array<GiReservoir>;
@group(2) @binding(4) var<storage, read_write> gi_out: array<GiReservoir>;
@group(2) @binding(5) var<storage, read_write> gi_debug: array<GiPixelDebug>;

struct GiTemporalCandidate {
    mask: u32,          // surface checks: the history is not merged
    unusable: u32,      // the shift failed: merged with weight 0
    reservoir: GiReservoir,
    target_here: f32,
    jacobian: f32,      // |J| of the shift previous visible point → here
    prev_surface: Surface,
}

fn gi_validate_previous(pixel: vec2<i32>, s: Surface, sp: ShadingPoint) -> GiTemporalCandidate {
    var c = GiTemporalCandidate(0u, 0u, gi_reservoir_empty(), 0.0, 0.0, Surface());
    let read = reuse_candidate(pixel, s, true);
    if read.mask != 0u {
        c.mask |= read.mask;
        return c;
    }
    let prev_index = read.index;
    let ps = prev_surfaces[prev_index];
    c.prev_surface = ps;
    // Without a previous surface there is no previous visible point to shift from.
    c.mask |= candidate_surface_checks(s, ps, true, true);
    if (c.mask & REJECT_SURFACE) != 0u {
        return c;
    }
    let prev = gi_checked(gi_prev[prev_index], INDIRECT_PASS_TEMPORAL);
    c.reservoir = prev;
    // A null reservoir is a sample of zero contribution (its secondary hit was dark or the
    // ray left the scene) that still stands for M candidates: merged, not rejected.
    // Rejecting it would average only over the bright histories (biased high: +2 % of the
    // indirect light on builtin:cornell).
    if gi_reservoir_is_null(prev) {
        return c;
    }
    if c.mask != 0u {
        return c;
    }
    // A sample that cannot reach this point (no reconnection, Jacobian outside the window)
    // still merges its confidence, with weight 0 (the rules tested in gi/model.rs).
    let shift = gi_shift(prev, ps.position, s.position);
    c.unusable = shift.reject;
    if shift.reject == 0u {
        c.jacobian = shift.jacobian;
        c.target_here = gi_target_at(sp, prev.position, prev.radiance);
        // From another visible point (a permuted read, a moving camera or object) the
        // sample may be hidden here: trace the reconnection as spatial reuse does. Without
        // this, permutation alone made the indirect light +4 % bright on builtin:cornell.
        var moved = length(ps.position - s.position) > 1e-4 * s.depth;
#ifdef PLANTED_GI_NO_TEMPORAL_VISIBILITY
        moved = false;  // test-only planted error (render/tests/restir_gi.rs)
#endif
        if moved && c.target_here > 0.0 && gi_flag_on(PARAM_FLAG_GI_SPATIAL_VISIBILITY) && !gi_reconnection_visible(sp, prev) {
            c.unusable |= GI_REJECT_OCCLUDED;
            c.target_here = 0.0;
        }
    }
    return c;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    let current = gi_checked(gi_in[index], INDIRECT_PASS_TEMPORAL);
    var d = gi_debug[index];
    if !surface_is_valid(s) {
        gi_out[index] = current;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = rng_seed(id.xy, STREAM_INDIRECT_TEMPORAL);
    var read = temporal_first_read(s);
    var cand: GiTemporalCandidate;
    loop {
        cand = gi_validate_previous(read.pixel, s, sp);
        if !temporal_retry(&read, cand.mask) {
            break;
        }
        count_stat(STAT_INDIRECT_FALLBACK_TRIED);
    }
    if temporal_fell_back(read, cand.mask) {
        count_stat(STAT_INDIRECT_FALLBACK_USED);
    }
    count_rejections(cand.mask | cand.unusable, STAT_INDIRECT_TEMPORAL_REJECT);
    d.temporal_mask = cand.mask | cand.unusable;

    var r = current;
    if cand.mask == 0u {
        count_stat(STAT_INDIRECT_TEMPORAL_ACCEPTED);
        let prev = cand.reservoir;
        let m_prev = min(prev.m, params.gi.m_cap);
        let temporal_packed = gi_pack(SOURCE_TEMPORAL, 0u, gi_age(prev) + 1u);
        let u_current = rand_f32(&rng);
        let u_prev = rand_f32(&rng);
        r = gi_reservoir_empty();
        var picked_previous = false;
        if gi_flag_on(PARAM_FLAG_GI_PAIRWISE) {
            let c_total = current.m + m_prev;
            var m_current = confidence_share(current.m, c_total);
            if !gi_reservoir_is_null(current) {
                // The canonical sample at the previous visible point, in this pixel's measure.
                let prev_sp = shading_point_from_surface(cand.prev_surface, frame.prev_camera_position);
                let back = gi_shift(current, s.position, cand.prev_surface.position);
                var j_back = select(0.0, back.jacobian, back.reject == 0u);
                // As in spatial reuse: could the previous visible point see this sample?
                if j_back > 0.0 && gi_mis_visibility() && !gi_reconnection_visible(prev_sp, current) {
                    j_back = 0.0;
                }
                let prev_at_current = gi_target_at(prev_sp, current.position, current.radiance);
                m_current += shifted_pairwise_canonical_term(c_total, current.m, m_prev, current.p_hat, prev_at_current, j_back);
            }
            let m_temporal = shifted_pairwise_noncanonical(c_total, current.m, m_prev, prev.p_hat, cand.target_here, cand.jacobian);
            gi_reservoir_merge_mis(&r, current, current.p_hat, 1.0, m_current, current.packed, u_current);
            picked_previous = gi_reservoir_merge_mis(&r, prev, cand.target_here, cand.jacobian, m_temporal, temporal_packed, u_prev);
            r.m = c_total;
            gi_reservoir_finalize(&r, 1.0);
        } else {
            gi_reservoir_merge(&r, current, current.p_hat, 1.0, current.m, current.packed, u_current);
            picked_previous = gi_reservoir_merge(&r, prev, cand.target_here, cand.jacobian, m_prev, temporal_packed, u_prev);
            gi_reservoir_finalize(&r, r.m);
        }
        d.jacobian = select(1.0, cand.jacobian, picked_previous);
    }
    gi_cap_confidence(&r, params.gi.m_cap);
    gi_set_flags(&r, cand.mask | cand.unusable);
    r = gi_guarded(r, INDIRECT_PASS_TEMPORAL);
    gi_out[index] = r;
    d.m_temporal = r.m;
    gi_debug[index] = d;
}
