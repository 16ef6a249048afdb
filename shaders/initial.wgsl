// Initial candidates (docs/src/ris.md, "Resampled importance sampling"): streaming RIS over
// `light_candidates` power-sampled light points and `bsdf_candidates` BSDF rays that hit an
// emitter (or escape to the environment: then the sample is that direction, per steradian),
// combined with
// the balance heuristic: w_i = p̂(y_i) / Σ_s N_s p_s(y_i) (area measure), W = w_sum / p̂(y).
// The result has M = 1: M counts reservoirs' worth of samples, so the M cap counts frames.
// With `initial_visibility` the survivor's shadow ray is traced here already.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read_write> reservoirs_out: array<Reservoir>;
@group(2) @binding(2) var<storage, read_write> debug: array<PixelDebug>;
// Presampled lights (presample_lights.wgsl); a one-element placeholder without tiles.
@group(2) @binding(3) var<storage, read> light_tiles: array<TileSample>;

struct Candidate {
    id: LightSampleId,
    point: LightPoint,
}

// One light candidate drawn from p_src: from this block's tile, or from the alias table.
fn light_candidate(rng: ptr<function, u32>, tile: u32) -> Candidate {
#ifdef LIGHT_TILES
    let j = min(u32(rand_f32(rng) * f32(LIGHT_TILE_SIZE)), LIGHT_TILE_SIZE - 1u);
    let t = light_tiles[tile * LIGHT_TILE_SIZE + j];
    return Candidate(LightSampleId(t.light, t.uv), unpack_tile_sample(t));
#else
    let y = sample_light(rng);
    return Candidate(y, light_point(y.light, y.uv));
#endif
}

// The tile a pixel block uses this frame (a fresh, decorrelated choice every frame).
fn block_tile(pixel: vec2<u32>) -> u32 {
    let block = pixel / LIGHT_TILE_PIXELS;
    return pcg_hash(block.x + pcg_hash(block.y + pcg_hash(frame.frame_index ^ frame.seed))) % LIGHT_TILE_COUNT;
}

fn stream_light_candidates(sp: ShadingPoint, r: ptr<function, Reservoir>, rng: ptr<function, u32>, tile: u32) {
    let n_l = f32(params.light_candidates);
    let n_b = f32(params.bsdf_candidates);
    for (var i = 0u; i < params.light_candidates; i++) {
        let candidate = light_candidate(rng, tile);
        let y = candidate.id;
        let lp = candidate.point;
        let u_select = rand_f32(rng);
        let c = light_contribution(sp, lp);
        let t = target_pdf(c);
#ifdef BSDF_CANDIDATES
        let source = light_candidate_source(sp, lp, c, t, n_l, n_b);
#else
        let source = n_l * lp.source_pdf;
#endif
        reservoir_update(r, y.light, y.uv, t / source, t, SOURCE_INITIAL, u_select);
    }
}

#ifdef BSDF_CANDIDATES
fn stream_bsdf_candidates(sp: ShadingPoint, r: ptr<function, Reservoir>, rng: ptr<function, u32>) {
    let n_l = f32(params.light_candidates);
    let n_b = f32(params.bsdf_candidates);
    for (var j = 0u; j < params.bsdf_candidates; j++) {
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
        let lp = light_point(light, uv);
        let c = light_contribution(sp, lp);
        let t = target_pdf(c);
        let p_bsdf = bs.pdf * c.cos_light / c.dist2;
        reservoir_update(r, light, uv, t / (n_l * lp.source_pdf + n_b * p_bsdf), t, SOURCE_INITIAL, u_select);
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
    if surface_is_valid(s) {
        if frame.light_count > 0u {
            let sp = shading_point_from_surface(s, frame.camera_position);
            var rng = rng_seed(id.xy, STREAM_INITIAL);
            stream_light_candidates(sp, &r, &rng, block_tile(id.xy));
#ifdef BSDF_CANDIDATES
            stream_bsdf_candidates(sp, &r, &rng);
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
    debug[index] = d;
}
