// The target function p̂ = luminance(Le · fr · G) (docs/src/ris.md, "The target function") and the
// shadow test, evaluated at a shading point rebuilt from a Surface record. Temporal and spatial
// reuse call the same functions at the current pixel, so a reused sample is always rescored where
// it is used (docs/src/temporal-reuse.md, "Re-evaluating the target").
#include "common/lights.wgsl"
#include "common/brdf.wgsl"
#include "common/transparency.wgsl"

struct ShadingPoint {
    position: vec3<f32>,
    normal: vec3<f32>,
    geo_normal: vec3<f32>,
    wo: vec3<f32>,
    brdf: Brdf,
    material: u32,
    depth: f32,
}

fn surface_is_valid(s: Surface) -> bool {
    return s.depth > 0.0;
}

fn surface_base_color(s: Surface) -> vec3<f32> {
    return unpack4x8unorm(s.base_color_metallic).rgb;
}

fn surface_metallic(s: Surface) -> f32 {
    return unpack4x8unorm(s.base_color_metallic).a;
}

fn shading_point_from_surface(s: Surface, viewer: vec3<f32>) -> ShadingPoint {
    let brdf = make_brdf(surface_base_color(s), surface_metallic(s), s.roughness, s.specular);
    let wo = safe_normalize(viewer - s.position, oct_decode(s.normal));
    return ShadingPoint(s.position, oct_decode(s.normal), oct_decode(s.geo_normal), wo, brdf, s.material, s.depth);
}

// A ray's hit as a shading point seen from `wo` (`depth`: the path's length to it).
fn hit_shading_point(hs: HitSurface, wo: vec3<f32>, brdf: Brdf, depth: f32) -> ShadingPoint {
    return ShadingPoint(hs.position, hs.normal, hs.geo_normal, wo, brdf, hs.material, depth);
}

struct LightContribution {
    value: vec3<f32>,  // unshadowed Le · fr · G (the integrand without visibility)
    wi: vec3<f32>,
    dist2: f32,
    cos_light: f32,    // for converting a BSDF pdf to area measure
}

fn no_contribution() -> LightContribution {
    return LightContribution(vec3<f32>(0.0), vec3<f32>(0.0, 0.0, 1.0), 0.0, 0.0);
}

fn light_contribution(sp: ShadingPoint, lp: LightPoint) -> LightContribution {
    return light_contribution_with(sp, lp, false, vec3<f32>(0.0));
}

// The same with the BRDF evaluated along `brdf_wi` when `along` (a BSDF sample: the
// direction it was drawn in, whose pdf it carries). The direction from sp.position to the
// point its ray hit differs by the ray origin's offset (ray.wgsl, ~1e-4 rad), which inside
// a sharp lobe (α = 1e-3) changes D by tens of percent: f and pdf would no longer cancel.
fn light_contribution_with(sp: ShadingPoint, lp: LightPoint, along: bool, brdf_wi: vec3<f32>) -> LightContribution {
    var wi: vec3<f32>;
    var dist2 = 1.0;
    var falloff = 1.0;  // G without cos at x, or 1/d² and cone for punctual lights
    var cos_light = 1.0;
    if lp.kind == LIGHT_POINT_AREA {
        let d = lp.position - sp.position;
        dist2 = dot(d, d);
        if !(dist2 > 0.0) {
            return no_contribution();
        }
        wi = d * inverseSqrt(dist2);
        cos_light = dot(lp.normal, -wi);
        if lp.double_sided {
            cos_light = abs(cos_light);
        }
        if cos_light <= 0.0 {
            return no_contribution();
        }
        falloff = cos_light / dist2;
    }
#ifdef ENVIRONMENT
    else if lp.kind == LIGHT_POINT_ENVIRONMENT {
        // A direction: falloff, dist2 and cos_light stay 1, so a BSDF pdf converted "to
        // area measure" (× cos_light / dist2) stays per steradian like the source pdf.
        wi = lp.position;
    }
#endif
#ifdef PUNCTUAL_LIGHTS
    else if lp.kind == LIGHT_POINT_POSITION {
        let d = lp.position - sp.position;
        dist2 = dot(d, d);
        if !(dist2 > 0.0) {
            return no_contribution();
        }
        wi = d * inverseSqrt(dist2);
        falloff = punctual_attenuation(punctual_record(lp), wi, dist2) / dist2;
    } else {
        wi = -punctual_record(lp).direction;
        dist2 = frame.scene_scale * frame.scene_scale * 4.0;
    }
#endif
    let cos_x = dot(sp.normal, wi);
    // Both normals must see the light: the shading normal for the BRDF, the geometric
    // one so light never leaks through the surface.
    if cos_x <= 0.0 || dot(sp.geo_normal, wi) <= 0.0 {
        return no_contribution();
    }
#ifdef PLANTED_BSDF_F_TOWARD_HIT
    let f = eval_brdf(sp.brdf, sp.normal, sp.wo, wi);  // test only: the code before
#else
    let f = eval_brdf(sp.brdf, sp.normal, sp.wo, select(wi, brdf_wi, along));
#endif
    let value = lp.radiance * f * (cos_x * falloff);
    return LightContribution(value, wi, dist2, cos_light);
}

fn target_pdf(c: LightContribution) -> f32 {
    let t = luminance(c.value);
    return select(0.0, t, is_finite_f32(t) && t > 0.0);
}

// p̂ of a stored light sample at this shading point.
fn target_at(sp: ShadingPoint, light: u32, uv: vec2<f32>) -> f32 {
    if light == NO_LIGHT {
        return 0.0;
    }
    return target_pdf(light_contribution(sp, light_point(light, uv)));
}

// One shadow ray between the shading point and the light point: 1 or 0 in an opaque
// scene, the tint of the transparent layers between them otherwise (trace.wgsl), against
// this frame's geometry or last frame's (`geometry`).
fn light_transmittance_in(sp: ShadingPoint, lp: LightPoint, c: LightContribution, geometry: u32) -> Transmittance {
#ifdef SHADOWS
    var ray: Ray;
    var distant = lp.kind == LIGHT_POINT_DIRECTION;
#ifdef ENVIRONMENT
    distant = distant || lp.kind == LIGHT_POINT_ENVIRONMENT;
#endif
    if distant {
        let o = offset_ray_origin(sp.position, sp.geo_normal);
        ray = Ray(o, c.wi * (frame.scene_scale * 2.0), 1.0);
    } else {
        let light_n = select(-lp.normal, lp.normal, dot(lp.normal, sp.position - lp.position) > 0.0);
        ray = segment_ray(sp.position, sp.geo_normal, lp.position, light_n);
    }
    return trace_transmittance_in(ray, geometry);
#else
    return Transmittance(vec3<f32>(1.0), false);
#endif
}

fn light_transmittance(sp: ShadingPoint, lp: LightPoint, c: LightContribution) -> Transmittance {
    return light_transmittance_in(sp, lp, c, GEOMETRY_CURRENT);
}

// The visibility factor V of a target p̂·V (visibility in the target, the pairwise MIS
// terms): the luminance of the transmittance. In an opaque scene it is exactly 0 or 1; with
// glass it is a valid target factor (> 0 wherever light gets through), used alike in every
// term, while shading multiplies by the full colour (di/shade.wgsl).
fn light_visibility_in(sp: ShadingPoint, lp: LightPoint, c: LightContribution, geometry: u32) -> f32 {
    return luminance(light_transmittance_in(sp, lp, c, geometry).value);
}

fn light_visibility(sp: ShadingPoint, lp: LightPoint, c: LightContribution) -> f32 {
    return light_visibility_in(sp, lp, c, GEOMETRY_CURRENT);
}

fn light_visible(sp: ShadingPoint, lp: LightPoint, c: LightContribution) -> bool {
    return light_visibility(sp, lp, c) > 0.0;
}

// Whether a BSDF ray can find this kind of light (and so the BSDF pdf enters its MIS
// weight): area lights, and the environment when there is one; never punctual lights.
fn bsdf_can_hit(kind: u32) -> bool {
#ifdef ENVIRONMENT
    if kind == LIGHT_POINT_ENVIRONMENT {
        return true;
    }
#endif
    return kind == LIGHT_POINT_AREA;
}

// The balance-heuristic denominator of a light candidate y among N_l light and N_b BSDF
// candidates: N_l p_light(y) + N_b p_bsdf(y), area measure (p_bsdf only where a BSDF ray
// could find y; `t`: y's target, 0 when it contributes nothing).
fn light_candidate_source(sp: ShadingPoint, lp: LightPoint, c: LightContribution, t: f32, n_l: f32, n_b: f32) -> f32 {
    var p_bsdf = 0.0;
    if n_b > 0.0 && t > 0.0 && bsdf_can_hit(lp.kind) {
        p_bsdf = brdf_pdf(sp.brdf, sp.normal, sp.wo, c.wi) * c.cos_light / c.dist2;
    }
    return n_l * lp.source_pdf + n_b * p_bsdf;
}

// The light a BSDF ray from sp along wi finds (transparency.wgsl): the emitter it hits
// first through clear layers, or the environment; NO_LIGHT for anything else.
fn bsdf_ray_light(sp: ShadingPoint, wi: vec3<f32>) -> FoundLight {
    return find_light_through(offset_ray_origin(sp.position, sp.geo_normal), wi);
}
