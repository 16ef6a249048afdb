// Rays through transparent layers (alpha BLEND, KHR_materials_transmission), in the thin-layer
// model of material.wgsl's `Layer`. Shadow rays take the product of the layers'
// pass_through (bvh.wgsl, TRACE_TRANSMITTANCE); the rays here find a surface instead:
//   * `walk_layers`: camera and path rays. At each transparent layer the ray stops with
//     probability `solid` (the layer is then the surface, shaded as opaque), else it goes on
//     with weight pass_through / (1 − solid). Unbiased for the same transport the shadow
//     rays compute, and deterministic where solid is 0 or 1 (clear glass, cut-out BLEND
//     texels): only partial coverage is chosen at random.
//   * `find_light_through`: BSDF rays looking for an emitter (light MIS, BSDF candidates).
//     They go through every non-emitting transparent layer, collecting its pass_through, and
//     stop at the first emitter (transparent or not) or opaque surface, as a shadow ray to
//     that emitter would see it.
// Every walk ends after MAX_TRANSPARENT_LAYERS layers, the same cap as shadow rays.
#include "common/bvh.wgsl"
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

struct LayerWalk {
    hit: Hit,              // the surface the ray stops at (t < 0: it left the scene)
    weight: vec3<f32>,     // what that surface's (or the background's) radiance is worth
    emission: vec3<f32>,   // emission of the layers passed, toward the ray's origin, weighted
    origin: vec3<f32>,     // the origin of the last ray segment (viewer of `hit`)
}

// From `first` (the closest hit of a ray from `origin` along `dir`), through transparent
// layers. `cull`: the camera rule for single-sided back faces, kept for every segment.
fn walk_layers(origin: vec3<f32>, dir: vec3<f32>, first: Hit, cull: bool, rng: ptr<function, u32>) -> LayerWalk {
    var walk = LayerWalk(first, vec3<f32>(1.0), vec3<f32>(0.0), origin);
#ifdef TRANSPARENCY
    for (var layer = 0u; layer < MAX_TRANSPARENT_LAYERS; layer++) {
        if walk.hit.t < 0.0 || !is_transparent_triangle(walk.hit.triangle) {
            return walk;
        }
        let l = triangle_layer(walk.hit.triangle, walk.hit.u, walk.hit.v);
        if rand_f32(rng) < l.solid {
            return walk;
        }
        let hs = hit_surface(walk.hit.triangle, walk.hit.u, walk.hit.v, walk.origin);
        walk.emission += walk.weight * emission_toward_viewer(hs);
        walk.weight *= l.pass_through / max(1.0 - l.solid, 1e-6);
        if !any(walk.weight > vec3<f32>(0.0)) {
            walk.hit.t = -1.0;
            return walk;
        }
        walk.origin = origin_past_layer(hs.position, walk.hit.triangle, dir);
        walk.hit = trace_closest(Ray(walk.origin, dir, FLT_MAX), cull);
    }
    // Past the cap the next transparent surface is as far as light gets: opaque black.
    if walk.hit.t >= 0.0 && is_transparent_triangle(walk.hit.triangle) {
        walk.weight = vec3<f32>(0.0);
    }
#endif
    return walk;
}

struct FoundLight {
    id: LightSampleId,         // light_table index and uv, or NO_LIGHT
    transmittance: vec3<f32>,  // the pass_through of the layers in front of it
}

// The light a BSDF ray from `origin` along `dir` finds: the first emitter through clear
// layers, or the environment when it leaves the scene; NO_LIGHT for anything else.
fn find_light_through(origin: vec3<f32>, dir: vec3<f32>) -> FoundLight {
    return find_light_from(origin, dir, trace_closest(Ray(origin, dir, FLT_MAX), false));
}

// The same from a ray's closest hit `first` (a path that also continues from it).
fn find_light_from(origin: vec3<f32>, dir: vec3<f32>, first: Hit) -> FoundLight {
    var ray_origin = origin;
    var transmittance = vec3<f32>(1.0);
    var hit = first;
    for (var layer = 0u; layer <= MAX_TRANSPARENT_LAYERS; layer++) {
        if layer > 0u {
            hit = trace_closest(Ray(ray_origin, dir, FLT_MAX), false);
        }
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
            transmittance *= triangle_layer(hit.triangle, hit.u, hit.v).pass_through;
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
