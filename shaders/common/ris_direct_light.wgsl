// Direct light at a shading point by resampled importance sampling: the `ris` mode's
// estimator (di/initial.wgsl's candidates, docs/src/ris.md) without a reservoir to keep.
// N_l light points from the vertex sampler (vertex_light.wgsl) and N_b BSDF rays that
// find an emitter, each weighted p̂ / (N_l p_light + N_b p_bsdf) (the balance heuristic),
// one survivor picked in proportion, one shadow ray for it: f·Le·G·V · w_sum / p̂(survivor).
// BSDF rays see occlusion by construction, so only a scene that compiles shadow rays may ask
// for them.
// The G-buffer estimates the light of transparent layers with it (layer_walk.wgsl): far
// less noise than one light sample where a few lights dominate (a shade's own bulb).
//
// A BSDF candidate's target is evaluated along its own direction (light_contribution_with,
// as the MIS estimator's BSDF strategy) and the survivor is shaded with the contribution
// its weight was computed with, so in a mirror-like lobe f and p̂ cancel exactly.
#include "common/direct_light_mis.wgsl"

struct RisChoice {
    w_sum: f32,
    p_hat: f32,             // p̂ of the survivor (0: none yet)
    point: LightPoint,
    contribution: LightContribution,
}

fn ris_consider(choice: ptr<function, RisChoice>, lp: LightPoint, c: LightContribution, p_hat: f32, source: f32, u: f32) {
    let w = p_hat / source;
    if !(w > 0.0) || !is_finite_f32(w) {
        return;
    }
    (*choice).w_sum += w;
    if u * (*choice).w_sum < w {
        (*choice).p_hat = p_hat;
        (*choice).point = lp;
        (*choice).contribution = c;
    }
}

// Adds the estimate with `light_candidates` and `bsdf_candidates` to *sum; returns the
// shadow rays traced (one for the survivor).
fn add_ris_direct_light(sp: ShadingPoint, light_candidates: u32, bsdf_candidates: u32, rng: ptr<function, u32>, sum: ptr<function, vec3<f32>>) -> u32 {
    var choice: RisChoice;
    choice.w_sum = 0.0;
    choice.p_hat = 0.0;
    let n_l = f32(light_candidates);
    let n_b = f32(bsdf_candidates);
    if frame.light_count > 0u {
        for (var i = 0u; i < light_candidates; i++) {
            let lp = sample_light_point_at(sp, rng);
            let u = rand_f32(rng);
            let c = light_contribution(sp, lp);
            let t = target_pdf(c);
            ris_consider(&choice, lp, c, t, light_candidate_source(sp, lp, c, t, n_l, n_b), u);
        }
    }
    for (var j = 0u; j < bsdf_candidates; j++) {
        let u3 = vec3<f32>(rand_f32(rng), rand_f32(rng), rand_f32(rng));
        let u = rand_f32(rng);
        let bs = sample_brdf(sp.brdf, sp.normal, sp.wo, u3);
        if !(bs.pdf > 0.0) {
            continue;
        }
        let found = bsdf_ray_light(sp, bs.wi).id;
        if found.light == NO_LIGHT {
            continue;
        }
        let lp = light_point_at(sp, found.light, found.uv);
        let c = light_contribution_with(sp, lp, true, bs.wi);
        let t = target_pdf(c);
        ris_consider(&choice, lp, c, t, n_l * lp.source_pdf + n_b * bs.pdf * c.cos_light / c.dist2, u);
    }
    if !(choice.p_hat > 0.0) {
        return 0u;
    }
    let transmittance = light_transmittance(sp, choice.point, choice.contribution).value;
    *sum += choice.contribution.value * transmittance * (choice.w_sum / choice.p_hat);
    return LIGHT_SAMPLE_RAYS;
}
