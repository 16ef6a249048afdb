// ReSTIR PT temporal reuse (docs/src/restir-pt.md, "The passes"): reproject into the previous
// frame, validate the previous surface by G-buffer checks alone (DI's checks and bits; never by its
// path), shift the previous pixel's path from last frame's visible point to this one (pt_shift: the
// chosen mapping, its Jacobian and visibility), shift this pixel's path back to the previous
// visible point for its pairwise weight, and merge the two under defensive pairwise MIS with
// confidences M and min(M_prev, pt_m_cap). A previous path that cannot be moved here is a
// zero-target domain: its confidence stays in the sum and its term in the weights (dropping it is
// the planted error of render/tests/restir_pt.rs).
//
// Both shifts are evaluated in this frame's scene: for a static scene that is last
// frame's too; under animation the previous side sees moving geometry where it is now
// (settings: pt_temporal's documentation names this biased shortcut).
#include "pt/path.wgsl"
#include "pt/probe.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> prev_surfaces: array<Surface>;
@group(2) @binding(2) var<storage, read> pt_in: array<PtReservoir>;
@group(2) @binding(3) var<storage, read> pt_prev: array<PtReservoir>;
@group(2) @binding(4) var<storage, read_write> pt_out: array<PtReservoir>;
@group(2) @binding(5) var<storage, read_write> pt_debug: array<PtPixelDebug>;
@group(2) @binding(6) var<storage, read_write> pt_probe: array<PtProbeStage>;
// The light BVH, for the vertex sampler (common/vertex_light.wgsl); one-element
// placeholders unless VERTEX_LIGHT_BVH is compiled.
@group(2) @binding(7) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(8) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

struct PtPrevious {
    mask: u32,            // REJECT_* bits: not merged
    index: u32,
    surface: Surface,
}

fn pt_validate_previous(pixel: vec2<i32>, s: Surface) -> PtPrevious {
    var c = PtPrevious(0u, 0u, Surface());
    let read = reuse_candidate(pixel, s, true);
    if read.mask != 0u {
        c.mask = read.mask;
        return c;
    }
    c.index = read.index;
    c.surface = prev_surfaces[read.index];
    // No previous visible point: nothing to shift from or back to.
    c.mask = candidate_surface_checks(s, c.surface, true, true);
    return c;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    let current = pt_checked(pt_in[index], INDIRECT_PASS_TEMPORAL);
    var d = pt_debug[index];
    if !surface_is_valid(s) {
        pt_out[index] = current;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = rng_seed(id.xy, STREAM_INDIRECT_TEMPORAL);
    var read = temporal_first_read(s);
    var prev_pixel: PtPrevious;
    loop {
        prev_pixel = pt_validate_previous(read.pixel, s);
        if !temporal_retry(&read, prev_pixel.mask) {
            break;
        }
        count_stat(STAT_INDIRECT_FALLBACK_TRIED);
    }
    if temporal_fell_back(read, prev_pixel.mask) {
        count_stat(STAT_INDIRECT_FALLBACK_USED);
    }
    count_rejections(prev_pixel.mask, STAT_INDIRECT_TEMPORAL_REJECT);
    d.temporal_mask = prev_pixel.mask;

    var r = current;
    if prev_pixel.mask == 0u {
        count_stat(STAT_INDIRECT_TEMPORAL_ACCEPTED);
        let prev = pt_checked(pt_prev[prev_pixel.index], INDIRECT_PASS_TEMPORAL);
        let m_prev = min(prev.m, params.pt.m_cap);
        let c_total = current.m + m_prev;
        // The previous path moved here (a null one is a zero that still stands for M_prev),
        // and this pixel's path moved to the previous pixel: could it have found it?
        let prev_sp = shading_point_from_surface(prev_pixel.surface, frame.prev_camera_position);
        let shifts = pt_shift_pair(prev, sp, current, prev_sp);
        var moved = shifts.moved;
        if !pt_reservoir_is_null(prev) {
            d.temporal_failure = moved.failure;
        }
        var m_current = confidence_share(current.m, c_total);
        if !pt_reservoir_is_null(current) {
            let back = shifts.back;
            var counted = true;
#ifdef PLANTED_PT_FAILED_SHIFT_DROPPED
            // Test-only planted error (render/tests/restir_pt.rs): the history counts in M
            // but leaves the canonical weight when this path cannot be shifted there.
            counted = back.jacobian != 0.0;
#endif
            if counted {
                m_current += shifted_pairwise_canonical_term(c_total, current.m, m_prev, current.p_hat, back.path.p_hat, back.jacobian);
            }
        }
        r = pt_reservoir_empty();
        let m_temporal = shifted_pairwise_noncanonical(c_total, current.m, m_prev, prev.p_hat, moved.path.p_hat, moved.jacobian);
        var own = PtShifted(current, 1.0, PT_FAIL_NONE);
        pt_merge_mis(&r, current, own, m_current, rand_f32(&rng));
        moved.path.packed = pt_with_source(moved.path.packed, SOURCE_TEMPORAL);
        pt_merge_mis(&r, prev, moved, m_temporal, rand_f32(&rng));
        r.m = min(c_total, params.pt.m_cap);
        pt_reservoir_finalize(&r);
        r = pt_guarded(r, INDIRECT_PASS_TEMPORAL);
    }
    d.jacobian = r.jacobian;
    d.m_temporal = r.m;
    d.m_spatial = r.m;
    pt_debug[index] = d;
    pt_probe_write(PT_PROBE_TEMPORAL, index, sp, r);
    pt_out[index] = r;
}
