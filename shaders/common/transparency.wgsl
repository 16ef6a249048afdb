// Rays through transparent layers (alpha BLEND, KHR_materials_transmission), in the thin-layer
// model of material.wgsl's `Layer`. Shadow rays take the product of the layers'
// pass_through (trace.wgsl, TRACE_TRANSMITTANCE); BSDF rays looking for an emitter (light
// MIS, BSDF candidates) use `find_light_through` here: they go through every non-emitting
// transparent layer, collecting its pass_through, and stop at the first emitter
// (transparent or not) or opaque surface, as a shadow ray to that emitter would see it.
// Camera and path rays find a surface instead (layer_walk.wgsl). Every walk ends after
// MAX_TRANSPARENT_LAYERS layers, the same cap as shadow rays.
#include "common/trace.wgsl"
#include "common/lights.wgsl"

// A point just past a layer's surface, on the far side along `dir`.
fn origin_past_layer(position: vec3<f32>, tri_index: u32, dir: vec3<f32>) -> vec3<f32> {
    let ng = triangle_normal(triangles[tri_index]);
    return offset_ray_origin(position, select(-ng, ng, dot(ng, dir) > 0.0));
}

fn is_transparent_triangle(tri_index: u32) -> bool {
#ifdef TRANSPARENCY
    return (materials[triangles[tri_index].material].flags & MATERIAL_TRANSPARENT) != 0u;
#else
    return false;
#endif
}

struct FoundLight {
    id: LightSampleId,         // light_table index and uv, or NO_LIGHT
    transmittance: vec3<f32>,  // the pass_through of the layers in front of it
}

// The light a BSDF ray from `origin` along `dir` finds: the first emitter through clear
// layers, or the environment when it leaves the scene; NO_LIGHT for anything else. (A path
// that also goes on along the ray finds it with layer_walk.wgsl's follow_ray.)
fn find_light_through(origin: vec3<f32>, dir: vec3<f32>) -> FoundLight {
    var ray_origin = origin;
    var transmittance = vec3<f32>(1.0);
    for (var layer = 0u; layer <= MAX_TRANSPARENT_LAYERS; layer++) {
        let hit = trace_closest(Ray(ray_origin, dir, FLT_MAX), false);
        if hit.t < 0.0 {
#ifdef ENVIRONMENT
            return FoundLight(LightSampleId(env.light, env_direction_to_uv(dir)), transmittance);
#else
            break;
#endif
        }
        let tri = triangles[hit.triangle];
#ifdef TRANSPARENCY
        if tri.light == NO_LIGHT && is_transparent_triangle(hit.triangle) && layer < MAX_TRANSPARENT_LAYERS {
            transmittance *= triangle_layer(hit.triangle, hit.u, hit.v, dir).pass_through;
            if !any(transmittance > vec3<f32>(0.0)) {
                break;
            }
            ray_origin = origin_past_layer(ray_origin + dir * hit.t, hit.triangle, dir);
            continue;
        }
#endif
        return FoundLight(LightSampleId(tri.light, vec2<f32>(hit.u, hit.v)), transmittance);
    }
    return FoundLight(LightSampleId(NO_LIGHT, vec2<f32>(0.0)), vec3<f32>(0.0));
}
