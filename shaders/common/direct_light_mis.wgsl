// Direct light at a shading point by the two strategies of the reference (light sampling
// and BSDF sampling) with the balance heuristic (Veach 1997, §9.2): weights
// p_light / (p_light + p_bsdf) and p_bsdf / (p_light + p_bsdf), both pdfs per unit area for
// triangle lights and per steradian for the environment, so an emitter both strategies can
// find is counted once. Used by the one-bounce reference and at every path vertex.
#include "common/shading_point.wgsl"

// One power-sampled light point with a shadow ray. `bsdf_in_weight`: the BSDF strategy
// runs too, so its pdf enters the weight (without it the light sample stands alone).
// Without SHADOWS the scene is convex and every segment between surface points is
// unoccluded (effects.rs).
fn light_sample_mis(sp: ShadingPoint, rng: ptr<function, u32>, bsdf_in_weight: bool) -> vec3<f32> {
    let y = sample_light(rng);
    let lp = light_point(y.light, y.uv);
    let c = light_contribution(sp, lp);
    if !(target_pdf(c) > 0.0) {
        return vec3<f32>(0.0);
    }
    let tr = light_transmittance(sp, lp, c);
    if !any(tr.value > vec3<f32>(0.0)) {
        return vec3<f32>(0.0);
    }
    var p_bsdf = 0.0;
    // A BSDF ray stops at the first emitter (transparency.wgsl): behind a glowing layer
    // this light point is the light strategy's alone.
    if bsdf_in_weight && bsdf_can_hit(lp.kind) && !tr.crossed_emitter {
        p_bsdf = brdf_pdf(sp.brdf, sp.normal, sp.wo, c.wi) * c.cos_light / c.dist2;
    }
    return tr.value * c.value / (lp.source_pdf + p_bsdf);
}

// The emission a BSDF-sampled direction found (`found`: the emitter its ray hit first, or
// the environment; NO_LIGHT for anything else), as the BSDF strategy's weighted estimate:
// Le·f·cos/p_bsdf · p_bsdf/(p_bsdf + p_light) = value / (p_light + p_bsdf) in area measure.
// The hit is the closest surface (or nothing: the environment), hence visible.
fn bsdf_found_emission(sp: ShadingPoint, bsdf_pdf: f32, found: LightSampleId) -> vec3<f32> {
    if found.light == NO_LIGHT {
        return vec3<f32>(0.0);
    }
    let lp = light_point(found.light, found.uv);
    let c = light_contribution(sp, lp);
    if !(target_pdf(c) > 0.0) {
        return vec3<f32>(0.0);
    }
    let p_bsdf = bsdf_pdf * c.cos_light / c.dist2;
#ifdef PLANTED_NO_BSDF_MIS
    return c.value / p_bsdf;
#else
    return c.value / (lp.source_pdf + p_bsdf);
#endif
}
