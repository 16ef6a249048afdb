// Light sampling (docs/src/ris.md, "Light sampling"): pick a light in proportion to its power with
// the alias table built on the CPU (render/src/scene/lights.rs), then a uniform point on it. A
// light sample is (light id, barycentric uv): enough to rebuild the point anywhere.
#include "common/scene_bindings.wgsl"
#include "common/material.wgsl"
#include "common/rng.wgsl"
#ifdef ENVIRONMENT
#include "common/environment.wgsl"
#endif

const LIGHT_POINT_AREA: u32 = 0u;
const LIGHT_POINT_POSITION: u32 = 1u;   // point and spot lights
const LIGHT_POINT_DIRECTION: u32 = 2u;  // directional lights
const LIGHT_POINT_ENVIRONMENT: u32 = 3u;  // `position` holds the direction toward the sky

struct LightPoint {
    kind: u32,
    position: vec3<f32>,  // the point on the light; unused (directional) or the direction (environment)
    normal: vec3<f32>,    // emitting-side normal of a triangle light
    radiance: vec3<f32>,  // Le (area), intensity (point, spot) or illuminance (directional)
    source_pdf: f32,      // area measure for triangles, discrete for punctual lights, solid angle for the environment
    double_sided: bool,
    punctual: u32,        // index into punctual_lights
#ifdef ANIMATION
    previous: bool,       // made from last frame's light data (light_point_in_frame)
#endif
}

fn light_kind_of(light: Light) -> u32 {
    return light.kind_prim >> LIGHT_KIND_SHIFT;
}

fn light_prim_of(light: Light) -> u32 {
    return light.kind_prim & LIGHT_PRIM_MASK;
}

// Alias method: one uniform slot, one coin.
fn sample_light_index(u: vec2<f32>) -> u32 {
    let n = frame.light_count;
    let slot = min(u32(u.x * f32(n)), n - 1u);
    let entry = lights[slot];
    return select(entry.alias_index, slot, u.y < entry.alias_threshold);
}

// Uniform point on a triangle as barycentrics (u, v) of p1 and p2.
fn uniform_triangle_uv(u: vec2<f32>) -> vec2<f32> {
    let su = sqrt(u.x);
    return vec2<f32>(su * (1.0 - u.y), su * u.y);
}

fn triangle_area(tri: Triangle) -> f32 {
    return 0.5 * length(cross(tri.p1 - tri.p0, tri.p2 - tri.p0));
}

// Records of the current frame, or with `previous` (animated scenes) of the last one: same
// slots, so a light's records are found under the same index in both (scene_bindings.wgsl).
fn frame_triangle(index: u32, previous: bool) -> Triangle {
#ifdef ANIMATION
    if previous {
        return prev_triangles[index];
    }
#endif
    return triangles[index];
}

fn frame_material(index: u32, previous: bool) -> Material {
#ifdef ANIMATION
    if previous {
        return prev_materials[index];
    }
#endif
    return materials[index];
}

#ifdef PUNCTUAL_LIGHTS
fn frame_punctual(index: u32, previous: bool) -> PunctualLight {
#ifdef ANIMATION
    if previous {
        return prev_punctual_lights[index];
    }
#endif
    return punctual_lights[index];
}
#endif

fn light_point(light_id: u32, uv: vec2<f32>) -> LightPoint {
    return light_point_in_frame(light_id, uv, false);
}

// A light sample's point this frame, or (`previous`, animated scenes) the same light (same
// slot: its identity) as it was last frame: last frame's triangle, emission and punctual
// record. Pairwise MIS needs the latter for the canonical sample's target and visibility
// at the previous pixel (di/temporal.wgsl).
fn light_point_in_frame(light_id: u32, uv: vec2<f32>, previous: bool) -> LightPoint {
    let light = lights[light_id];
    var lp: LightPoint;
    lp.source_pdf = light.select_pdf;
    lp.double_sided = false;
    lp.punctual = 0u;
#ifdef ANIMATION
    lp.previous = previous;
#endif
#ifdef AREA_LIGHTS
    if light_kind_of(light) == LIGHT_KIND_TRIANGLE {
        let tri_index = light_prim_of(light);
        let tri = frame_triangle(tri_index, previous);
        let material = frame_material(tri.material, previous);
        lp.kind = LIGHT_POINT_AREA;
        lp.position = tri.p0 * (1.0 - uv.x - uv.y) + tri.p1 * uv.x + tri.p2 * uv.y;
        lp.normal = triangle_normal(tri);
        lp.radiance = material_emission_of(material, triangle_uv(tri_index, uv.x, uv.y));
        lp.source_pdf = light.select_pdf / triangle_area(tri);
        lp.double_sided = (material.flags & MATERIAL_DOUBLE_SIDED) != 0u;
        return lp;
    }
#endif
#ifdef ENVIRONMENT
    // The environment does not animate: one record for both frames.
    if light_kind_of(light) == LIGHT_KIND_ENVIRONMENT {
        lp.kind = LIGHT_POINT_ENVIRONMENT;
        lp.position = env_uv_to_direction(uv);
        lp.normal = vec3<f32>(0.0);
        lp.radiance = env_radiance_at(uv);
        // P(pick the environment) × the direction's density: per steradian, no Jacobian.
        lp.source_pdf = light.select_pdf * env_pdf(uv);
        return lp;
    }
#endif
#ifdef PUNCTUAL_LIGHTS
    let p = frame_punctual(light_prim_of(light), previous);
    lp.punctual = light_prim_of(light);
    lp.radiance = p.intensity;
    lp.normal = vec3<f32>(0.0);
    lp.position = p.position;
    lp.kind = select(LIGHT_POINT_POSITION, LIGHT_POINT_DIRECTION, p.kind == PUNCTUAL_DIRECTIONAL);
#endif
    return lp;
}

#ifdef PUNCTUAL_LIGHTS
// The punctual record a light point came from: this frame's, or last frame's for a point
// made with `previous`.
fn punctual_record(lp: LightPoint) -> PunctualLight {
#ifdef ANIMATION
    return frame_punctual(lp.punctual, lp.previous);
#else
    return punctual_lights[lp.punctual];
#endif
}
#endif

struct LightSampleId {
    light: u32,
    uv: vec2<f32>,
}

fn sample_light(rng: ptr<function, u32>) -> LightSampleId {
    return sample_point_on_light(sample_light_index(rand_vec2(rng)), rng);
}

// A point on `light` (uniform on a triangle; by the environment's table on the sky).
fn sample_point_on_light(light: u32, rng: ptr<function, u32>) -> LightSampleId {
    let u = rand_vec2(rng);
    var uv = uniform_triangle_uv(u);
#ifdef ENVIRONMENT
    if light == env.light {
        // Four more numbers: the row and column picks each take a slot and a coin.
        let u_row = rand_vec2(rng);
        uv = env_sample_uv(u_row, rand_vec2(rng), u);
    }
#endif
    return LightSampleId(light, uv);
}

// Whether a light has a position (a triangle, a point or spot light): the light samplers
// with locality (light BVH, ReGIR targets) handle those; the environment and directional
// lights keep their power-table probability (docs/src/light-samplers.md).
fn light_is_finite(light_id: u32) -> bool {
    let light = lights[light_id];
    let kind = light_kind_of(light);
    if kind == LIGHT_KIND_TRIANGLE {
        return true;
    }
#ifdef PUNCTUAL_LIGHTS
    if kind == LIGHT_KIND_PUNCTUAL {
        return punctual_lights[light_prim_of(light)].kind != PUNCTUAL_DIRECTIONAL;
    }
#endif
    return false;
}

// The same point drawn with another selection probability: source_pdf is select_pdf ×
// the point's density on its light, so it scales with the selection.
fn with_selection_pdf(lp: LightPoint, light_id: u32, selection: f32) -> LightPoint {
    var out = lp;
    let table = lights[light_id].select_pdf;
    out.source_pdf = select(0.0, lp.source_pdf * (selection / table), table > 0.0);
    return out;
}

// An environment sample keeps its direction in `position` and kind 3 in the two kind bits.
fn pack_presampled_light(y: LightSampleId, lp: LightPoint, weight: f32) -> PresampledLight {
    let flags = lp.kind | (select(0u, 1u, lp.double_sided) << 2u) | (lp.punctual << 8u);
    return PresampledLight(lp.position, lp.source_pdf, lp.radiance, y.light, y.uv, oct_encode(lp.normal), flags, weight, 0u, 0u, 0u);
}

fn unpack_presampled_light(t: PresampledLight) -> LightPoint {
    var lp: LightPoint;
    lp.kind = t.flags & 3u;
    lp.position = t.position;
    lp.normal = select(vec3<f32>(0.0), oct_decode(t.normal), lp.kind == LIGHT_POINT_AREA);
    lp.radiance = t.radiance;
    lp.source_pdf = t.source_pdf;
    lp.double_sided = ((t.flags >> 2u) & 1u) != 0u;
    lp.punctual = t.flags >> 8u;
    return lp;
}

#ifdef PUNCTUAL_LIGHTS
// Spot cone and range window of KHR_lights_punctual, as the spec recommends.
fn punctual_attenuation(p: PunctualLight, to_light: vec3<f32>, dist2: f32) -> f32 {
    var a = 1.0;
    if p.range > 0.0 {
        let r = dist2 / (p.range * p.range);
        a = clamp(1.0 - r * r, 0.0, 1.0);
    }
    if p.kind == PUNCTUAL_SPOT {
        let cd = dot(p.direction, -to_light);
        let t = clamp((cd - p.cos_outer) / max(p.cos_inner - p.cos_outer, 1e-4), 0.0, 1.0);
        a *= t * t;
    }
    return a;
}
#endif
