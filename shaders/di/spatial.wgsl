// Spatial reuse (docs/src/spatial-reuse.md): K neighbours in a disk of radius R pixels, each
// checked for depth / normal / material compatibility (its own rejection bits, apart
// from the temporal ones), merged with the neighbour's M (1/M) or with pairwise MIS
// around this pixel's reservoir (unbiased); M is capped after the pass. Under pairwise MIS
// only the G-buffer checks drop a neighbour (reuse.wgsl, rejecting_checks): a null
// neighbour or one whose sample has target 0 here is merged with its confidence and
// contributes nothing. With mis_visibility every pairwise term is p̂·V: each neighbour's
// sample is traced from here, and this pixel's sample from each neighbour. Reads one
// reservoir buffer and writes another, so neighbours never see half-updated data.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> reservoirs_in: array<Reservoir>;
@group(2) @binding(2) var<storage, read_write> reservoirs_out: array<Reservoir>;
@group(2) @binding(3) var<storage, read_write> debug: array<PixelDebug>;
@group(2) @binding(4) var<uniform> pass_info: PassInfo;

fn load_neighbour(index: u32) -> Reservoir {
    return checked_reservoir(reservoirs_in[index], PASS_SPATIAL);
}

// A sample's target T = p̂·V at `sp` for a pairwise term (V with mis_visibility, when
// `visibility`). A sample both pixels hold (`same_sample`) needs no ray: each pixel's
// survivor is visible from it (V = 1 in an opaque scene), and through glass, where V is a
// tint, its T there is the stored p̂ (`stored`).
fn reuse_target(sp: ShadingPoint, light: u32, uv: vec2<f32>, visibility: bool, same_sample: bool, stored: f32, rays: ptr<function, u32>) -> f32 {
    var t = target_at(sp, light, uv);
    if t > 0.0 && visibility && mis_visibility() {
        if !same_sample {
            t *= sample_visibility(sp, light, uv, false, GEOMETRY_CURRENT, rays);
        }
#ifdef TRANSPARENCY
        if same_sample {
            t = stored;
        }
#endif
    }
    return t;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var canonical = load_neighbour(index);
    var d = debug[index];
    if !surface_is_valid(s) {
        reservoirs_out[index] = canonical;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = rng_seed(id.xy, STREAM_SPATIAL + pass_info.pass_index);

    // 1. Pick and validate neighbours.
    var accepted: array<u32, MAX_SPATIAL_NEIGHBOURS>;
    var n_accepted = 0u;
    var pass_mask = 0u;
    var c_total = canonical.m;
    var contribution_sum = canonical.p_hat * canonical.weight;
    let k = min(params.di.spatial_neighbours, MAX_SPATIAL_NEIGHBOURS);
    for (var i = 0u; i < k; i++) {
        let offset = disk_neighbour_offset(rand_vec2(&rng), params.di.spatial_radius);
        let candidate = reuse_candidate(vec2<i32>(id.xy) + offset, s, false);
        var mask = candidate.mask;
        let q_index = candidate.index;
        if mask == 0u {
            mask |= candidate_surface_checks(s, surfaces[q_index], false, false);
            let nr = load_neighbour(q_index);
            if reservoir_is_null(nr) && check_enabled(REJECT_RESERVOIR) {
                mask |= REJECT_RESERVOIR;
            }
            if !reservoir_is_null(nr) && check_enabled(REJECT_TARGET) && target_at(sp, nr.light, nr.uv) <= 0.0 {
                mask |= REJECT_TARGET;
            }
            if rejecting_checks(mask) == 0u {
                accepted[n_accepted] = q_index;
                n_accepted++;
                c_total += nr.m;
                contribution_sum += nr.p_hat * nr.weight;
            }
        }
        count_rejections(mask, STAT_SPATIAL_REJECT);
        pass_mask |= mask;
    }

    // 2. Boiling filter (docs/src/spatial-reuse.md, "The boiling filter"): drop this pixel's
    //    own sample when it outshines the neighbourhood by more than k times; its M still
    //    counts.
    if params.di.boiling_filter > 0.0 && n_accepted > 0u {
        let mean = contribution_sum / f32(n_accepted + 1u);
        if canonical.p_hat * canonical.weight > params.di.boiling_filter * mean {
            count_stat(STAT_BOILING_DROPPED);
            let m = canonical.m;
            canonical = reservoir_empty();
            canonical.m = m;
        }
    }

    // 3. Merge: 1/M in order (this pixel first), or pairwise MIS around this pixel's
    //    reservoir (neighbours first, the canonical sample last with its accumulated share).
    var r = reservoir_empty();
    var rays = 0u;
    let pairwise = pairwise_mis();
    if !pairwise {
        reservoir_merge(&r, canonical, canonical.p_hat, canonical.m, canonical.source, rand_f32(&rng));
    }
    var m_canonical = confidence_share(canonical.m, c_total);
    // Under pairwise MIS each neighbour has two terms: its sample here, T_here(y_i), and this
    // pixel's sample there, T_i(y_c). Both go through one reuse_target call site, the most
    // expensive code of the pass (docs/src/compile-time.md).
    let terms = select(1u, 2u, pairwise);
    for (var i = 0u; i < n_accepted; i++) {
        let q_index = accepted[i];
        let nr = load_neighbour(q_index);
        // Reuse spreads survivors, so a neighbour often holds this pixel's very sample:
        // both visibilities are then known (each pixel's survivor is visible from it).
        let same_sample = !reservoir_is_null(canonical) && nr.light == canonical.light && all(nr.uv == canonical.uv);
        var target_here = 0.0;
        var neighbour_at_canonical = 0.0;
        for (var term = 0u; term < terms; term++) {
            var at = sp;
            var sample = nr;
            var stored = canonical.p_hat;
            if term == 1u {
                at = shading_point_from_surface(surfaces[q_index], frame.camera_position);
                sample = canonical;
                stored = nr.p_hat;
            }
            let t = reuse_target(at, sample.light, sample.uv, pairwise, same_sample, stored, &rays);
            if term == 0u {
                target_here = t;
            } else {
                neighbour_at_canonical = t;
            }
        }
        let source = source_with_age(SOURCE_SPATIAL, reservoir_age(nr));
        if pairwise {
            let m_i = pairwise_mis_noncanonical(c_total, canonical.m, nr.m, nr.p_hat, target_here);
            reservoir_merge_mis(&r, nr, target_here, m_i, source, rand_f32(&rng));
            m_canonical += pairwise_mis_canonical_term(c_total, canonical.m, nr.m, canonical.p_hat, neighbour_at_canonical);
        } else {
            reservoir_merge(&r, nr, target_here, nr.m, source, rand_f32(&rng));
        }
    }
    if pairwise {
        reservoir_merge_mis(&r, canonical, canonical.p_hat, m_canonical, canonical.source, rand_f32(&rng));
        reservoir_finalize(&r, 1.0);
        r.m = c_total;
    } else {
        reservoir_finalize(&r, r.m);
    }
    if r.m > params.di.m_cap {
        r.m = params.di.m_cap;
        d.flags |= DEBUG_FLAG_SPATIAL_CAP;
        count_stat(STAT_SPATIAL_CAP);
    }
    if reservoir_is_corrupt(r) {
        count_stat(STAT_NONFINITE + PASS_SPATIAL);
        r = reservoir_empty();
    }
    add_stat(STAT_SHADOW_RAYS + PASS_SPATIAL, rays);
    reservoirs_out[index] = r;
    d.source = reservoir_source(r);
    d.m_spatial = r.m;
    d.spatial_mask |= pass_mask;
    d.spatial_accepted += n_accepted;
    debug[index] = d;
}
