// Initial candidates (docs/src/ris.md, "Resampled importance sampling"): streaming RIS over
// `light_candidates` light points from the frame's light sampler (docs/src/light-samplers.md)
// and `bsdf_candidates` BSDF rays that hit an emitter (or escape to the environment: then
// the sample is that direction, per steradian), combined with the balance heuristic:
// w_i = p̂(y_i) / Σ_s N_s p_s(y_i) (area measure), W = w_sum / p̂(y).
// The result has M = 1: M counts reservoirs' worth of samples, so the M cap counts frames.
// With `initial_visibility` the survivor's shadow ray is traced here already.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read_write> reservoirs_out: array<Reservoir>;
@group(2) @binding(2) var<storage, read_write> debug: array<PixelDebug>;
// The light samplers' data (docs/src/light-samplers.md), each a one-element placeholder
// unless its sampler is on: presampled lights (the light tiles, lights/presample_lights.wgsl, or
// ReGIR's slots, lights/regir_fill.wgsl) and the light BVH (render/src/light_sampler.rs).
@group(2) @binding(3) var<storage, read> presampled: array<PresampledLight>;
@group(2) @binding(4) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(5) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

#ifdef REGIR
#include "common/regir.wgsl"
#endif
#ifdef LIGHT_BVH
#include "common/light_bvh.wgsl"
#endif

// A light candidate: the sample, its point, and how its weight departs from
// p̂ / (N_l p_light + N_b p_bsdf): `weight_scale` = 1 / (W · p_light), 1 where the sampler's
// PDF is exact and p_light is it (power, tiles, BVH); for a ReGIR slot p_light is the power
// table's PDF (what the BSDF candidates' MIS weights use too) and W the slot's.
struct Candidate {
    id: LightSampleId,
    point: LightPoint,
    weight_scale: f32,
    proposer: u32,   // PROPOSER_*
}

fn exact_candidate(y: LightSampleId, lp: LightPoint, proposer: u32) -> Candidate {
    return Candidate(y, lp, 1.0, proposer);
}

fn no_candidate() -> Candidate {
    var none: Candidate;
    none.id = LightSampleId(NO_LIGHT, vec2<f32>(0.0));
    none.weight_scale = 0.0;
    none.proposer = PROPOSER_NONE;
    return none;
}

// The tile a pixel block uses this frame (a fresh, decorrelated choice every frame).
fn block_tile(pixel: vec2<u32>) -> u32 {
    let block = pixel / LIGHT_TILE_PIXELS;
    return pcg_hash(block.x + pcg_hash(block.y + pcg_hash(frame.frame_index ^ frame.seed))) % LIGHT_TILE_COUNT;
}

#ifdef LIGHT_BVH
// The BVH's PDF of a light at sp: lights with a position through the tree (their share
// of the power table times the walk's probability), the others by the table.
fn light_bvh_selection(sp: ShadingPoint, light: u32) -> f32 {
    if light_is_finite(light) {
        return frame.finite_light_share * light_bvh_pdf(light, sp.position, sp.normal);
    }
    return lights[light].select_pdf;
}
#endif

// One light candidate from the frame's light sampler.
fn light_candidate(sp: ShadingPoint, rng: ptr<function, u32>, pixel: vec2<u32>) -> Candidate {
#ifdef LIGHT_TILES
    let j = min(u32(rand_f32(rng) * f32(LIGHT_TILE_SIZE)), LIGHT_TILE_SIZE - 1u);
    let t = presampled[block_tile(pixel) * LIGHT_TILE_SIZE + j];
    return exact_candidate(LightSampleId(t.light, t.uv), unpack_presampled_light(t), PROPOSER_TILE);
#else
#ifdef REGIR
    let jitter = (vec3<f32>(rand_f32(rng), rand_f32(rng), rand_f32(rng)) - 0.5) * params.regir_jitter * regir_cell_side();
    let cell = regir_cell_at(sp.position + jitter);
    let u_slot = rand_f32(rng);
    if cell != REGIR_NO_CELL {
        let j = min(u32(u_slot * f32(params.regir_slots)), params.regir_slots - 1u);
        let slot = presampled[cell * params.regir_slots + j];
        if !(slot.weight > 0.0) {
            return no_candidate();
        }
        let lp = unpack_presampled_light(slot);
#ifdef PLANTED_REGIR_WEIGHT_IGNORED
        return exact_candidate(LightSampleId(slot.light, slot.uv), lp, PROPOSER_REGIR);
#else
        return Candidate(LightSampleId(slot.light, slot.uv), lp, 1.0 / (slot.weight * lp.source_pdf), PROPOSER_REGIR);
#endif
    }
#endif
    let y0 = sample_light(rng);
#ifdef LIGHT_BVH
    // The table picks between the lights with a position (then the tree picks which one)
    // and the others (kept): P(light with a position) = share × the walk's probability.
    if light_is_finite(y0.light) {
        let walk = light_bvh_sample(sp.position, sp.normal, 0.0, rand_f32(rng));
        if walk.light == NO_LIGHT {
            return no_candidate();
        }
        let y = sample_point_on_light(walk.light, rng);
#ifdef PLANTED_BVH_PDF_WITHOUT_ORIENTATION
        let selection = light_bvh_selection(sp, walk.light);
#else
        let selection = frame.finite_light_share * walk.pdf;
#endif
        return exact_candidate(y, with_selection_pdf(light_point(y.light, y.uv), y.light, selection), PROPOSER_BVH);
    }
#endif
    return exact_candidate(y0, light_point(y0.light, y0.uv), PROPOSER_POWER);
#endif
}

// The light strategy's PDF (area measure) of a point a BSDF ray found, as the light
// candidates' MIS weights use it: the BVH's at sp, the power table's for every other
// sampler (the tiles draw from it; ReGIR's weights are taken against it).
fn light_strategy_point(sp: ShadingPoint, light: u32, lp: LightPoint) -> LightPoint {
#ifdef LIGHT_BVH
    return with_selection_pdf(lp, light, light_bvh_selection(sp, light));
#else
    return lp;
#endif
}

// What the debug record keeps of the candidates: which strategy proposed the survivor,
// and how many light candidates could contribute at all (p̂ > 0, unshadowed).
struct CandidateTally {
    proposer: u32,
    useful: u32,
}

fn stream_light_candidates(sp: ShadingPoint, r: ptr<function, Reservoir>, rng: ptr<function, u32>, pixel: vec2<u32>, tally: ptr<function, CandidateTally>) {
    let n_l = f32(params.di.light_candidates);
    let n_b = f32(params.di.bsdf_candidates);
    for (var i = 0u; i < params.di.light_candidates; i++) {
        let candidate = light_candidate(sp, rng, pixel);
        let u_select = rand_f32(rng);
        if !(candidate.weight_scale > 0.0) {
            continue;
        }
        let y = candidate.id;
        let lp = candidate.point;
        let c = light_contribution(sp, lp);
        let t = target_pdf(c);
#ifdef BSDF_CANDIDATES
        let source = light_candidate_source(sp, lp, c, t, n_l, n_b);
#else
        let source = n_l * lp.source_pdf;
#endif
        if t > 0.0 {
            (*tally).useful += 1u;
        }
        if reservoir_update(r, y.light, y.uv, t / (source * candidate.weight_scale), t, SOURCE_INITIAL, u_select) {
            (*tally).proposer = candidate.proposer;
        }
    }
}

#ifdef BSDF_CANDIDATES
fn stream_bsdf_candidates(sp: ShadingPoint, r: ptr<function, Reservoir>, rng: ptr<function, u32>, tally: ptr<function, CandidateTally>) {
    let n_l = f32(params.di.light_candidates);
    let n_b = f32(params.di.bsdf_candidates);
    for (var j = 0u; j < params.di.bsdf_candidates; j++) {
        let u = vec3<f32>(rand_f32(rng), rand_f32(rng), rand_f32(rng));
        let u_select = rand_f32(rng);
        let bs = sample_brdf(sp.brdf, sp.normal, sp.wo, u);
        if !(bs.pdf > 0.0) {
            continue;
        }
        // The candidate's target is unshadowed, so the tint of glass in front of the
        // emitter (found.transmittance) does not enter it.
        let found = bsdf_ray_light(sp, bs.wi).id;
        if found.light == NO_LIGHT {
            continue;
        }
        let light = found.light;
        let uv = found.uv;
        let lp = light_strategy_point(sp, light, light_point(light, uv));
        let c = light_contribution(sp, lp);
        let t = target_pdf(c);
        let p_bsdf = bs.pdf * c.cos_light / c.dist2;
        if reservoir_update(r, light, uv, t / (n_l * lp.source_pdf + n_b * p_bsdf), t, SOURCE_INITIAL, u_select) {
            (*tally).proposer = PROPOSER_BSDF;
        }
    }
}
#endif

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var r = reservoir_empty();
    var tally = CandidateTally(PROPOSER_NONE, 0u);
    if surface_is_valid(s) {
        if frame.light_count > 0u {
            let sp = shading_point_from_surface(s, frame.camera_position);
            var rng = rng_seed(id.xy, STREAM_INITIAL);
            stream_light_candidates(sp, &r, &rng, id.xy, &tally);
#ifdef BSDF_CANDIDATES
            stream_bsdf_candidates(sp, &r, &rng, &tally);
#endif
            reservoir_finalize(&r, 1.0);
#ifdef SHADOWS
            // Visibility reuse (ReSTIR paper §4, RTXDI "initial visibility"): one shadow
            // ray for the survivor; an occluded one becomes a zero-contribution sample, so
            // reuse never spreads samples that are in shadow where they were found.
            // With mis_visibility this is the canonical sample's own V (settings.rs turns the
            // flag on): the reservoir is then a sample of the target p̂·V.
            if (params.flags & PARAM_FLAG_INITIAL_VISIBILITY) != 0u && !reservoir_is_null(r) {
                let lp = light_point(r.light, r.uv);
                add_stat(STAT_SHADOW_RAYS + PASS_INITIAL, 1u);
                let v = light_visibility(sp, lp, light_contribution(sp, lp));
                if v > 0.0 {
                    // The target here is p̂·V (V < 1 only through glass): the stored p̂ is
                    // what every pairwise term compares with.
                    r.p_hat *= v;
                } else {
                    r = reservoir_empty();
                }
            }
#endif
        }
        r.m = 1.0;
        if reservoir_is_corrupt(r) {
            count_stat(STAT_NONFINITE + PASS_INITIAL);
            r = reservoir_empty();
            r.m = 1.0;
        }
    }
    reservoirs_out[index] = r;
    var d: PixelDebug;
    d.source = reservoir_source(r);
    d.m_initial = r.m;
    d.proposer = select(tally.proposer, PROPOSER_NONE, reservoir_is_null(r));
    d.useful_candidates = f32(tally.useful) / f32(max(params.di.light_candidates, 1u));
    if surface_is_valid(s) && frame.light_count > 0u {
        add_stat(STAT_LIGHT_CANDIDATES, params.di.light_candidates);
        add_stat(STAT_USEFUL_CANDIDATES, tally.useful);
    }
    debug[index] = d;
}
