// ReSTIR PT spatial reuse (docs/src/restir-pt.md, "The passes"): k neighbours in a disk of
// pt_spatial_radius pixels, chosen and validated by G-buffer checks alone (never by their paths).
// Each neighbour's path is shifted here (pt_shift: reconnection, random replay or hybrid, its
// Jacobian, its visibility traced), and this pixel's path is shifted to each neighbour for its
// pairwise MIS weight (Bitterli et al. 2020's defensive pairwise MIS, the targets in this pixel's
// measure through |J|, as gi/spatial.wgsl). A path that cannot be shifted is a zero in its domain:
// the neighbour keeps its confidence in the sum and its term in the weights.
#include "pt/path.wgsl"
#include "pt/probe.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> pt_in: array<PtReservoir>;
@group(2) @binding(2) var<storage, read_write> pt_out: array<PtReservoir>;
@group(2) @binding(3) var<storage, read_write> pt_debug: array<PtPixelDebug>;
@group(2) @binding(4) var<storage, read_write> pt_probe: array<PtProbeStage>;
// The light BVH, for the vertex sampler (common/vertex_light.wgsl); one-element
// placeholders unless VERTEX_LIGHT_BVH is compiled.
@group(2) @binding(5) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(6) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    let canonical = pt_checked(pt_in[index], INDIRECT_PASS_SPATIAL);
    var d = pt_debug[index];
    if !surface_is_valid(s) {
        pt_out[index] = canonical;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = rng_seed(id.xy, STREAM_INDIRECT_SPATIAL);
    var accepted: array<u32, MAX_SPATIAL_NEIGHBOURS>;
    var n_accepted = 0u;
    var c_total = canonical.m;
    let k = min(params.pt.spatial_neighbours, MAX_SPATIAL_NEIGHBOURS);
    for (var i = 0u; i < k; i++) {
        let offset = disk_neighbour_offset(rand_vec2(&rng), params.pt.spatial_radius);
        let candidate = reuse_candidate(vec2<i32>(id.xy) + offset, s, false);
        var mask = candidate.mask;
        let q_index = candidate.index;
        if mask == 0u {
            mask |= candidate_surface_checks(s, surfaces[q_index], false, true);
        }
        if mask == 0u {
            accepted[n_accepted] = q_index;
            n_accepted++;
            c_total += pt_checked(pt_in[q_index], INDIRECT_PASS_SPATIAL).m;
        }
        count_rejections(mask, STAT_INDIRECT_SPATIAL_REJECT);
    }

    var r = pt_reservoir_empty();
    var m_canonical = confidence_share(canonical.m, c_total);
    for (var i = 0u; i < n_accepted; i++) {
        let q_index = accepted[i];
        let nr = pt_checked(pt_in[q_index], INDIRECT_PASS_SPATIAL);
        // The neighbour's path moved here, and this pixel's path moved to the neighbour:
        // could the neighbour have found it?
        let neighbour_sp = shading_point_from_surface(surfaces[q_index], frame.camera_position);
        let shifts = pt_shift_pair(nr, sp, canonical, neighbour_sp);
        var moved = shifts.moved;
        if !pt_reservoir_is_null(nr) {
            d.spatial_tried += 1u;
            // Saturating 4-bit counters, one per outcome (MAX_SPATIAL_NEIGHBOURS ≤ 15).
            let shift = 4u * min(moved.failure, 7u);
            if ((d.spatial_outcomes >> shift) & 0xfu) < 0xfu {
                d.spatial_outcomes += 1u << shift;
            }
        }
        var counted = !pt_reservoir_is_null(canonical);
#ifdef PLANTED_PT_FAILED_SHIFT_DROPPED
        // Test-only planted error: a neighbour this path cannot be shifted to still counts
        // in M but leaves the canonical weight (RTXDI PT's 2026 bug class).
        counted = counted && shifts.back.jacobian != 0.0;
#endif
        if counted {
            m_canonical += shifted_pairwise_canonical_term(c_total, canonical.m, nr.m, canonical.p_hat, shifts.back.path.p_hat, shifts.back.jacobian);
        }
        if !pt_reservoir_is_null(nr) {
            let m_i = shifted_pairwise_noncanonical(c_total, canonical.m, nr.m, nr.p_hat, moved.path.p_hat, moved.jacobian);
            moved.path.packed = pt_with_source(moved.path.packed, SOURCE_SPATIAL);
            pt_merge_mis(&r, nr, moved, m_i, rand_f32(&rng));
        }
    }
    var own = PtShifted(canonical, 1.0, PT_FAIL_NONE);
    if pt_merge_mis(&r, canonical, own, m_canonical, rand_f32(&rng)) {
        r.jacobian = canonical.jacobian;  // its last shift is still the temporal one
    }
    r.m = c_total;
    pt_reservoir_finalize(&r);
    r = pt_guarded(r, INDIRECT_PASS_SPATIAL);
    d.jacobian = r.jacobian;
    d.m_spatial = r.m;
    pt_debug[index] = d;
    pt_probe_write(PT_PROBE_SPATIAL, index, sp, r);
    pt_out[index] = r;
}
