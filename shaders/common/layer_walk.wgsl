// Camera and path rays through transparent layers (material.wgsl's thin-layer `Layer`): the
// ray finds a surface, and the layers it passes add their own light. Two walks estimate the
// same transport:
//
// * `walk_layers` (the reference, per sample; path and GI rays): at each layer the ray stops
//   with probability `solid` (the layer is then the surface, shaded as opaque), else it
//   goes on with weight pass_through / (1 − solid).
// * `walk_to_primary` (the G-buffer): no random choice, so a still view gives the same
//   surfaces every frame and the reservoirs behind frosted glass keep their history. The
//   larger of a layer's two shares, solid or passing (by luminance), holds the pixel's
//   primary surface, shaded by ReSTIR; the other is estimated once per frame without
//   reuse: the layer's solid share lit where it is, or what lies behind it seen through a
//   random walk like `walk_layers`'. Clear glass (solid 0) and cut-out texels are passed,
//   fully covered texels hold.
//
// Camera rays also collect what each layer's glass share reflects: direct light off its
// specular lobe, estimated the same way per layer, whichever way the walk goes (the glass
// share is neither solid nor passing). For smooth glass the BSDF sample finds the mirrored
// emitter every frame, so the highlight is as stable as the glass. The reflection of lit
// surfaces (indirect light) is not modelled, in any mode; path rays see glass as tint only.
//
// The light of a layer is estimated by the walk's kind: the reference's camera rays use
// its own one light + one BSDF sample (direct_light_mis.wgsl), the G-buffer's RIS over
// 8 light and 1 BSDF candidates (ris_direct_light.wgsl).
#include "common/transparency.wgsl"
#include "common/ris_direct_light.wgsl"

const WALK_PATH: u32 = 0u;              // path and GI rays: no culling, no layer light
const WALK_REFERENCE_CAMERA: u32 = 1u;  // culling; layer light by one light + one BSDF sample
const WALK_GBUFFER_CAMERA: u32 = 2u;    // culling; layer light by RIS

struct LayerWalk {
    hit: Hit,              // the surface the ray stops at (t < 0: it left the scene)
    weight: vec3<f32>,     // what that surface's (or the background's) radiance is worth
    in_front: vec3<f32>,   // radiance toward the ray's origin from the layers met, weighted:
                           // their emission, their glass reflection (camera rays) and, in
                           // walk_to_primary, the share the primary surface leaves out
    origin: vec3<f32>,     // the origin of the last ray segment (viewer of `hit`)
    shadow_rays: u32,      // traced for those estimates
    kind: u32,             // WALK_*
}

// The G-buffer's candidates for a layer's light: the same in every real-time mode (nee,
// ris and restir differ in how they shade the primary surface, not in this), one BSDF
// candidate where shadow rays exist (a smooth pane's mirror image needs it; BSDF rays see
// occlusion, so a convex scene without them relies on light candidates alone).
const LAYER_LIGHT_CANDIDATES: u32 = 8u;
#ifdef SHADOWS
const LAYER_BSDF_CANDIDATES: u32 = 1u;
#else
const LAYER_BSDF_CANDIDATES: u32 = 0u;
#endif

fn add_layer_direct_light(kind: u32, sp: ShadingPoint, rng: ptr<function, u32>, sum: ptr<function, vec3<f32>>) -> u32 {
    if kind == WALK_GBUFFER_CAMERA {
        return add_ris_direct_light(sp, LAYER_LIGHT_CANDIDATES, LAYER_BSDF_CANDIDATES, rng, sum);
    }
    return add_direct_light(sp, rng, sum);
}

// `share` × the direct light `lobe` reflects toward `wo` at a layer's point `hs`, estimated
// as the walk's kind says, added to the walk's in_front with its weight.
fn add_layer_light(walk: ptr<function, LayerWalk>, hs: HitSurface, lobe: Brdf, share: f32, wo: vec3<f32>, rng: ptr<function, u32>) {
    var reflected = vec3<f32>(0.0);
    (*walk).shadow_rays += add_layer_direct_light((*walk).kind, hit_shading_point(hs, wo, lobe, 0.0), rng, &reflected);
    (*walk).in_front += (*walk).weight * share * reflected;
}

// What the glass share of a layer reflects: its specular lobe alone (base colour 0,
// metallic 0: brdf.wgsl then has no diffuse term and F = specularFactor·Schlick).
fn add_glass_reflection(walk: ptr<function, LayerWalk>, hs: HitSurface, glass: f32, wo: vec3<f32>, rng: ptr<function, u32>) {
#ifdef SPECULAR
#ifndef PLANTED_NO_FRESNEL
    let m = eval_material(hs.material, hs.uv);
    if glass > 0.0 && m.specular > 0.0 {
        add_layer_light(walk, hs, make_brdf(vec3<f32>(0.0), 0.0, m.roughness, m.specular), glass, wo, rng);
    }
#endif
#endif
}

#ifdef TRANSPARENCY
// The transparent layer a walk has hit: its surface and its shares for this ray, with its
// glass reflection already added for a camera ray.
struct MetLayer {
    hs: HitSurface,
    layer: Layer,
}

fn meet_layer(walk: ptr<function, LayerWalk>, dir: vec3<f32>, rng: ptr<function, u32>) -> MetLayer {
    let hit = (*walk).hit;
    let hs = hit_surface(hit.triangle, hit.u, hit.v, (*walk).origin);
    let l = triangle_layer(hit.triangle, hit.u, hit.v, dir);
    if (*walk).kind != WALK_PATH {
        add_glass_reflection(walk, hs, l.glass, -dir, rng);
    }
    return MetLayer(hs, l);
}
#endif

// Past the cap the next transparent surface is as far as light gets: opaque black.
fn stop_at_cap(walk: ptr<function, LayerWalk>) {
    if (*walk).hit.t >= 0.0 && is_transparent_triangle((*walk).hit.triangle) {
        (*walk).weight = vec3<f32>(0.0);
    }
}

// From `first` (the closest hit of a ray from `origin` along `dir`), through at most
// `max_layers` transparent layers (MAX_TRANSPARENT_LAYERS for a whole ray), choosing at
// random. A camera ray (`kind` not WALK_PATH) keeps the camera rule for single-sided back
// faces on every segment and collects the layers' glass reflections.
fn walk_layers(origin: vec3<f32>, dir: vec3<f32>, first: Hit, kind: u32, max_layers: u32, rng: ptr<function, u32>) -> LayerWalk {
    var walk = LayerWalk(first, vec3<f32>(1.0), vec3<f32>(0.0), origin, 0u, kind);
#ifdef TRANSPARENCY
    for (var layer = 0u; layer < max_layers; layer++) {
        if walk.hit.t < 0.0 || !is_transparent_triangle(walk.hit.triangle) {
            return walk;
        }
        let met = meet_layer(&walk, dir, rng);
        let hs = met.hs;
        let l = met.layer;
        if rand_f32(rng) < l.solid {
            return walk;
        }
        walk.in_front += walk.weight * emission_toward_viewer(hs);
        walk.weight *= l.pass_through / max(1.0 - l.solid, 1e-6);
        if !any(walk.weight > vec3<f32>(0.0)) {
            walk.hit.t = -1.0;
            return walk;
        }
        walk.origin = origin_past_layer(hs.position, walk.hit.triangle, dir);
        walk.hit = trace_closest(Ray(walk.origin, dir, FLT_MAX), kind != WALK_PATH);
    }
    stop_at_cap(&walk);
#endif
    return walk;
}

#ifdef TRANSPARENCY
// A light estimate the G-buffer's walk owes: `weight` × the direct light at `sp` (RIS).
struct LightJob {
    sp: ShadingPoint,
    weight: vec3<f32>,
}

// The walk's state between steps (walk_to_primary).
const STEP_PRIMARY: u32 = 0u;  // going on toward the primary surface
const STEP_BEHIND: u32 = 1u;   // sampling, once, what passes a held layer
const STEP_DONE: u32 = 2u;
#endif

// The G-buffer's walk (see the top of this file): from `first`, through transparent layers
// without a random choice, to the pixel's primary surface. Its `weight` is what the primary
// surface's shading is worth; `in_front` holds everything else, including the primary
// layer's emission (the caller adds emission only for an opaque primary surface).
//
// Written as one loop of small steps with the light estimates queued and taken one per
// step at a single call site: the drivers inline every call and unroll fixed-count loops,
// so the nested form (a random walk behind a held layer, inside the layer loop, each layer
// with two RIS estimates) grew to dozens of copies of RIS and traversal and took minutes to
// compile on lavapipe. Behind a held layer, what passes is one `walk_layers`-style random
// walk (stop at a layer with probability `solid`), ending in the emission and RIS light of
// the surface it reaches, or the environment.
fn walk_to_primary(origin: vec3<f32>, dir: vec3<f32>, first: Hit, rng: ptr<function, u32>) -> LayerWalk {
    var walk = LayerWalk(first, vec3<f32>(1.0), vec3<f32>(0.0), origin, 0u, WALK_GBUFFER_CAMERA);
#ifdef TRANSPARENCY
    var jobs: array<LightJob, 2>;
    var queued = 0u;
    var step = STEP_PRIMARY;
    var layer = 0u;
    // The walk behind a held layer: its ray, how many layers it may still pass, whether it
    // stopped at a layer (chosen as its surface), and what its light is worth.
    var behind = LayerWalk(first, vec3<f32>(0.0), vec3<f32>(0.0), origin, 0u, WALK_GBUFFER_CAMERA);
    var behind_left = 0u;
    var behind_stopped = false;
    // Each step queues at most two estimates and each estimate takes a step: the bound
    // is never reached (8 layers ahead, 8 behind), it only makes termination evident.
    for (var guard = 0u; guard < 8u * MAX_TRANSPARENT_LAYERS + 8u; guard++) {
        if queued > 0u {
            queued -= 1u;
            let job = jobs[queued];
            var reflected = vec3<f32>(0.0);
            walk.shadow_rays += add_ris_direct_light(job.sp, LAYER_LIGHT_CANDIDATES, LAYER_BSDF_CANDIDATES, rng, &reflected);
            walk.in_front += job.weight * reflected;
            continue;
        }
        if step == STEP_DONE {
            break;
        }
        if step == STEP_PRIMARY {
            let transparent = walk.hit.t >= 0.0 && is_transparent_triangle(walk.hit.triangle);
            if !transparent || layer >= MAX_TRANSPARENT_LAYERS {
                if transparent {
                    stop_at_cap(&walk);
                }
                step = STEP_DONE;
                continue;
            }
            let hs = hit_surface(walk.hit.triangle, walk.hit.u, walk.hit.v, walk.origin);
            let l = triangle_layer(walk.hit.triangle, walk.hit.u, walk.hit.v, dir);
            queue_glass_reflection(&jobs, &queued, hs, l.glass, -dir, walk.weight);
            walk.in_front += walk.weight * emission_toward_viewer(hs);
            let past = origin_past_layer(hs.position, walk.hit.triangle, dir);
#ifdef PLANTED_RANDOM_LAYER_CHOICE
            // Test only: the choice before, at random by solid, which a still view redraws
            // every frame (the other share is then left to the choice, not sampled).
            let hold = rand_f32(rng) < l.solid;
            let held_share = 1.0;
            let passed_share = l.pass_through / max(1.0 - l.solid, 1e-6);
            let sample_other = false;
#else
            let hold = l.solid >= luminance(l.pass_through);
            let held_share = l.solid;
            let passed_share = l.pass_through;
            let sample_other = true;
#endif
            if hold {
                // The layer is the primary surface (ReSTIR shades its solid share); what
                // passes is sampled once, by the walk behind.
                step = STEP_DONE;
                if sample_other && any(l.pass_through > vec3<f32>(0.0)) {
                    behind.origin = past;
                    behind.hit = trace_closest(Ray(past, dir, FLT_MAX), true);
                    behind.weight = walk.weight * l.pass_through;
                    behind_left = MAX_TRANSPARENT_LAYERS - layer - 1u;
                    step = STEP_BEHIND;
                }
                walk.weight *= held_share;
                continue;
            }
            // What lies behind holds the primary surface; the layer's solid share is lit once.
            if sample_other && l.solid > 0.0 {
                jobs[queued] = LightJob(hit_shading_point(hs, -dir, hit_brdf(hs), 0.0), walk.weight * l.solid);
                queued += 1u;
            }
            walk.weight *= passed_share;
            if !any(walk.weight > vec3<f32>(0.0)) {
                walk.hit.t = -1.0;
                step = STEP_DONE;
                continue;
            }
            walk.origin = past;
            walk.hit = trace_closest(Ray(past, dir, FLT_MAX), true);
            layer += 1u;
            continue;
        }
        // STEP_BEHIND: one layer of the random walk, or its end.
        let at_layer = behind.hit.t >= 0.0 && is_transparent_triangle(behind.hit.triangle) && !behind_stopped;
        if at_layer && behind_left == 0u {
            stop_at_cap(&behind);
        }
        if !at_layer || behind_left == 0u {
            step = STEP_DONE;
            if behind.hit.t < 0.0 {
#ifdef ENVIRONMENT
                walk.in_front += behind.weight * env_background(dir);
#endif
            } else if any(behind.weight > vec3<f32>(0.0)) {
                let hs = hit_surface(behind.hit.triangle, behind.hit.u, behind.hit.v, behind.origin);
                walk.in_front += behind.weight * emission_toward_viewer(hs);
                jobs[queued] = LightJob(hit_shading_point(hs, -dir, hit_brdf(hs), 0.0), behind.weight);
                queued += 1u;
            }
            continue;
        }
        let hs = hit_surface(behind.hit.triangle, behind.hit.u, behind.hit.v, behind.origin);
        let l = triangle_layer(behind.hit.triangle, behind.hit.u, behind.hit.v, dir);
        queue_glass_reflection(&jobs, &queued, hs, l.glass, -dir, behind.weight);
        if rand_f32(rng) < l.solid {
            behind_stopped = true;  // this layer is the surface the walk reaches
            continue;
        }
        walk.in_front += behind.weight * emission_toward_viewer(hs);
        behind.weight *= l.pass_through / max(1.0 - l.solid, 1e-6);
        if !any(behind.weight > vec3<f32>(0.0)) {
            behind.hit.t = -1.0;
            continue;
        }
        behind.origin = origin_past_layer(hs.position, behind.hit.triangle, dir);
        behind.hit = trace_closest(Ray(behind.origin, dir, FLT_MAX), true);
        behind_left -= 1u;
    }
#endif
    return walk;
}

#ifdef TRANSPARENCY
// Queues what the glass share of a layer reflects (as `add_glass_reflection`, for the
// G-buffer's walk): its specular lobe alone, worth `weight` × `glass`.
fn queue_glass_reflection(jobs: ptr<function, array<LightJob, 2>>, queued: ptr<function, u32>, hs: HitSurface, glass: f32, wo: vec3<f32>, weight: vec3<f32>) {
#ifdef SPECULAR
#ifndef PLANTED_NO_FRESNEL
    let m = eval_material(hs.material, hs.uv);
    if glass > 0.0 && m.specular > 0.0 {
        let lobe = make_brdf(vec3<f32>(0.0), 0.0, m.roughness, m.specular);
        (*jobs)[*queued] = LightJob(hit_shading_point(hs, wo, lobe, 0.0), weight * glass);
        *queued += 1u;
    }
#endif
#endif
}
#endif
