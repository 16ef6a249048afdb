// Direct light at a shading point by the two strategies of the reference (light sampling
// and BSDF sampling) with the balance heuristic (Veach 1997, §9.2): weights
// p_light / (p_light + p_bsdf) and p_bsdf / (p_light + p_bsdf), both pdfs per unit area for
// triangle lights and per steradian for the environment, so an emitter both strategies can
// find is counted once. Used by the one-bounce reference, at every path vertex and for the
// light of transparent layers toward the camera (layer_walk.wgsl).
// With n light samples per vertex (`reference_light_samples`) the multi-sample balance
// heuristic, n·p_light and p_bsdf in place of the two pdfs: each sample of either strategy
// contributes f / (n·p_light + p_bsdf) (Veach 1997, §9.2.2); n = 1 is the one-sample case
// above, to the bit.
#include "common/vertex_light.wgsl"

// A strategy's weighted estimate and the shadow rays it traced (counted per pass).
struct DirectLight {
    value: vec3<f32>,
    shadow_rays: u32,
}

// A light sample traces its shadow ray only where the scene can occlude.
#ifdef SHADOWS
const LIGHT_SAMPLE_RAYS: u32 = 1u;
#else
const LIGHT_SAMPLE_RAYS: u32 = 0u;
#endif

// The light samples a reference vertex draws (at least one).
fn reference_light_samples() -> u32 {
    return max(params.reference_light_samples, 1u);
}

// `count` light points from the vertex sampler, each with its shadow ray and its share of
// the multi-sample weight (above).
fn light_samples_mis(sp: ShadingPoint, rng: ptr<function, u32>, bsdf_in_weight: bool, count: u32) -> DirectLight {
    var total = DirectLight(vec3<f32>(0.0), 0u);
    for (var k = 0u; k < count; k++) {
        let one = light_sample_mis(sp, rng, bsdf_in_weight, f32(count));
        total.value += one.value;
        total.shadow_rays += one.shadow_rays;
    }
    return total;
}

// One light point from the vertex sampler (vertex_light.wgsl) with a shadow ray, one of
// `light_samples` drawn at this vertex.
// `bsdf_in_weight`: the BSDF strategy runs too, so its pdf enters the weight (without it
// the light samples stand alone).
// Without SHADOWS the scene is convex and every segment between surface points is
// unoccluded (effects.rs).
fn light_sample_mis(sp: ShadingPoint, rng: ptr<function, u32>, bsdf_in_weight: bool, light_samples: f32) -> DirectLight {
    let lp = sample_light_point_at(sp, rng);
    let c = light_contribution(sp, lp);
    if !(target_pdf(c) > 0.0) || !(lp.source_pdf > 0.0) {
        return DirectLight(vec3<f32>(0.0), 0u);
    }
    let tr = light_transmittance(sp, lp, c);
    if !any(tr.value > vec3<f32>(0.0)) {
        return DirectLight(vec3<f32>(0.0), LIGHT_SAMPLE_RAYS);
    }
    var p_bsdf = 0.0;
    // A BSDF ray stops at the first emitter (transparency.wgsl): behind a glowing layer
    // this light point is the light strategy's alone.
    if bsdf_in_weight && bsdf_can_hit(lp.kind) && !tr.crossed_emitter {
        p_bsdf = brdf_pdf(sp.brdf, sp.normal, sp.wo, c.wi) * c.cos_light / c.dist2;
    }
#ifdef PLANTED_LIGHT_SAMPLES_UNWEIGHTED
    let p_light = lp.source_pdf;  // planted: n samples each weighed as if alone
#else
    let p_light = light_samples * lp.source_pdf;
#endif
    return DirectLight(tr.value * c.value / (p_light + p_bsdf), LIGHT_SAMPLE_RAYS);
}

// The emission a BSDF-sampled direction found (`found`: the emitter its ray hit first, or
// the environment; NO_LIGHT for anything else), as the BSDF strategy's weighted estimate:
// Le·f·cos/p_bsdf · p_bsdf/(p_bsdf + n·p_light) = value / (n·p_light + p_bsdf) in area
// measure, n = `light_samples` drawn at this vertex, f along the sampled direction
// (shading_point.wgsl, light_contribution_with).
// The hit is the closest surface (or nothing: the environment), hence visible.
fn bsdf_found_emission(sp: ShadingPoint, bs: BrdfSample, found: LightSampleId, light_samples: f32) -> vec3<f32> {
    if found.light == NO_LIGHT {
        return vec3<f32>(0.0);
    }
    let lp = light_point_at(sp, found.light, found.uv);
    let c = light_contribution_with(sp, lp, true, bs.wi);
    if !(target_pdf(c) > 0.0) {
        return vec3<f32>(0.0);
    }
    let p_bsdf = bs.pdf * c.cos_light / c.dist2;
#ifdef PLANTED_NO_BSDF_MIS
    return c.value / p_bsdf;
#else
    return c.value / (light_samples * lp.source_pdf + p_bsdf);
#endif
}

// One BSDF-sampled direction and the emitter (or environment) its ray finds through clear
// layers, weighted against the light sample.
fn bsdf_sample_mis(sp: ShadingPoint, rng: ptr<function, u32>, light_samples: f32) -> vec3<f32> {
    let u = vec3<f32>(rand_f32(rng), rand_f32(rng), rand_f32(rng));
    let bs = sample_brdf(sp.brdf, sp.normal, sp.wo, u);
    if !(bs.pdf > 0.0) {
        return vec3<f32>(0.0);
    }
    let found = bsdf_ray_light(sp, bs.wi);
    return found.transmittance * bsdf_found_emission(sp, bs, found.id, light_samples);
}

// Direct light at sp by `reference_light_samples` light samples and one BSDF sample, added
// to *sum light samples first (the one-bounce reference with one light sample is held to
// its images bit for bit: one_bounce_unchanged.rs).
// BSDF rays see occlusion by construction, so that strategy runs only with shadows (always
// with an environment), and only where it can find a light. Returns the shadow rays traced.
fn add_direct_light(sp: ShadingPoint, rng: ptr<function, u32>, sum: ptr<function, vec3<f32>>) -> u32 {
    var shadow_rays = 0u;
    let n = reference_light_samples();
    if frame.light_count > 0u {
#ifdef SHADOWS
        let light = light_samples_mis(sp, rng, true, n);
#else
        let light = light_samples_mis(sp, rng, false, n);
#endif
        *sum += light.value;
        shadow_rays = light.shadow_rays;
    }
#ifdef SHADOWS
#ifdef ENVIRONMENT
    *sum += bsdf_sample_mis(sp, rng, f32(n));
#else
#ifdef AREA_LIGHTS
    *sum += bsdf_sample_mis(sp, rng, f32(n));
#endif
#endif
#endif
    return shadow_rays;
}
