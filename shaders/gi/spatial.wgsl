// ReSTIR GI spatial reuse (Ouyang et al. 2021 §3.3): k neighbours in a disk of
// gi_spatial_radius pixels; each is validated with DI's surface checks and bits, its
// sample shifted from the neighbour's visible point to this one (reconnection Jacobian,
// window) and, with gi_spatial_visibility, the reconnection segment traced (off is biased:
// an occluded sample is counted as if visible). Merged with 1/M or pairwise MIS, the
// canonical sample's targets at the neighbours taken through |J_here→neighbour|.
#include "gi/reuse.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> gi_in: array<GiReservoir>;
@group(2) @binding(2) var<storage, read_write> gi_out: array<GiReservoir>;
@group(2) @binding(3) var<storage, read_write> gi_debug: array<GiPixelDebug>;

struct GiNeighbour {
    index: u32,
    jacobian: f32,     // |J| neighbour → here
    target_here: f32,
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    let canonical = gi_checked(gi_in[index], INDIRECT_PASS_SPATIAL);
    var d = gi_debug[index];
    if !surface_is_valid(s) {
        gi_out[index] = canonical;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = rng_seed(id.xy, STREAM_INDIRECT_SPATIAL);
    var accepted: array<GiNeighbour, MAX_SPATIAL_NEIGHBOURS>;
    var n_accepted = 0u;
    var pass_mask = 0u;
    var c_total = canonical.m;
    let k = min(params.gi.spatial_neighbours, MAX_SPATIAL_NEIGHBOURS);
    for (var i = 0u; i < k; i++) {
        let offset = disk_neighbour_offset(rand_vec2(&rng), params.gi.spatial_radius);
        let q = vec2<i32>(id.xy) + offset;
        // `mask`: surface checks, which drop the neighbour. `unusable`: its sample cannot
        // reach this pixel (no reconnection, Jacobian outside the window, occluded): the
        // neighbour stays in the MIS (its confidence counts) with weight 0 here, as the
        // tested rules in gi/model.rs do; dropping it would bias the weights.
        var mask = 0u;
        var unusable = 0u;
        var n = GiNeighbour(0u, 0.0, 0.0);
        let candidate = reuse_candidate(q, s, false);
        mask |= candidate.mask;
        if mask == 0u {
            n.index = candidate.index;
            let ns = surfaces[n.index];
            mask |= candidate_surface_checks(s, ns, false, true);
            if (mask & REJECT_SURFACE) == 0u {
                let nr = gi_checked(gi_in[n.index], INDIRECT_PASS_SPATIAL);
                // A null neighbour is a zero-contribution sample with its confidence M:
                // merged, not rejected (rejecting it biased the indirect light +23 %).
                if mask == 0u && !gi_reservoir_is_null(nr) {
                    let shift = gi_shift(nr, ns.position, s.position);
                    unusable |= shift.reject;
                    if unusable == 0u {
                        n.jacobian = shift.jacobian;
                        n.target_here = gi_target_at(sp, nr.position, nr.radiance);
                        if n.target_here > 0.0 && gi_flag_on(PARAM_FLAG_GI_SPATIAL_VISIBILITY) && !gi_reconnection_visible(sp, nr) {
                            unusable |= GI_REJECT_OCCLUDED;
                            n.target_here = 0.0;
                        }
                    }
                }
            }
        }
        if mask == 0u {
            accepted[n_accepted] = n;
            n_accepted++;
            c_total += gi_in[n.index].m;
        }
        count_rejections(mask | unusable, STAT_INDIRECT_SPATIAL_REJECT);
        pass_mask |= mask | unusable;
    }

    var r = gi_reservoir_empty();
    var picked_jacobian = 1.0;
    if gi_flag_on(PARAM_FLAG_GI_PAIRWISE) {
        var m_canonical = confidence_share(canonical.m, c_total);
        for (var i = 0u; i < n_accepted; i++) {
            let n = accepted[i];
            let nr = gi_in[n.index];
            let ns = surfaces[n.index];
            let m_i = shifted_pairwise_noncanonical(c_total, canonical.m, nr.m, nr.p_hat, n.target_here, n.jacobian);
            let packed = gi_pack(SOURCE_SPATIAL, 0u, gi_age(nr));
            if gi_reservoir_merge_mis(&r, nr, n.target_here, n.jacobian, m_i, packed, rand_f32(&rng)) {
                picked_jacobian = n.jacobian;
            }
            if !gi_reservoir_is_null(canonical) {
                let neighbour_sp = shading_point_from_surface(ns, frame.camera_position);
                let back = gi_shift(canonical, s.position, ns.position);
                var j_back = select(0.0, back.jacobian, back.reject == 0u);
                // Whether the neighbour could have produced this pixel's sample: its point must
                // be visible from there too (gi_mis_visibility; off leaves the canonical weight
                // too small where neighbours are shadowed, see docs/src/restir-gi.md, "Rules
                // the shaders follow").
                if j_back > 0.0 && gi_mis_visibility() && !gi_reconnection_visible(neighbour_sp, canonical) {
                    j_back = 0.0;
                }
                let at_neighbour = gi_target_at(neighbour_sp, canonical.position, canonical.radiance);
                m_canonical += shifted_pairwise_canonical_term(c_total, canonical.m, nr.m, canonical.p_hat, at_neighbour, j_back);
            }
        }
        if gi_reservoir_merge_mis(&r, canonical, canonical.p_hat, 1.0, m_canonical, canonical.packed, rand_f32(&rng)) {
            picked_jacobian = 1.0;
        }
        r.m = c_total;
        gi_reservoir_finalize(&r, 1.0);
    } else {
        gi_reservoir_merge(&r, canonical, canonical.p_hat, 1.0, canonical.m, canonical.packed, rand_f32(&rng));
        for (var i = 0u; i < n_accepted; i++) {
            let n = accepted[i];
            let nr = gi_in[n.index];
            let packed = gi_pack(SOURCE_SPATIAL, 0u, gi_age(nr));
            if gi_reservoir_merge(&r, nr, n.target_here, n.jacobian, nr.m, packed, rand_f32(&rng)) {
                picked_jacobian = n.jacobian;
            }
        }
        gi_reservoir_finalize(&r, r.m);
    }
    if gi_source(r) == SOURCE_SPATIAL {
        d.jacobian = picked_jacobian;
    }
    gi_cap_confidence(&r, params.gi.m_cap);
    gi_set_flags(&r, pass_mask);
    r = gi_guarded(r, INDIRECT_PASS_SPATIAL);
    gi_out[index] = r;
    d.m_spatial = r.m;
    d.spatial_mask = pass_mask;
    d.spatial_accepted = n_accepted;
    gi_debug[index] = d;
}
