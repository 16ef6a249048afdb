// Camera and path rays through transparent layers (material.wgsl's thin-layer `Layer`): the
// ray finds a surface, and the layers it passes add their own light. Two walks estimate the
// same transport:
//
// * the random walk (`walk_advance`; the reference's camera rays, path and GI rays, and
//   `follow_ray` for BSDF rays that also look for an emitter): at each layer the ray stops
//   with probability `solid` (the layer is then the surface, shaded as opaque), else it
//   goes on with weight pass_through / (1 − solid).
// * `walk_to_primary` (the G-buffer): no random choice, so a still view gives the same
//   surfaces every frame and the reservoirs behind frosted glass keep their history. The
//   larger of a layer's two shares, solid or passing (by luminance), holds the pixel's
//   primary surface, shaded by ReSTIR; the other is estimated once per frame without
//   reuse: the layer's solid share lit where it is, or what lies behind it seen through a
//   random walk like the first. Clear glass (solid 0) and cut-out texels are passed,
//   fully covered texels hold.
//
// Camera rays also collect what each layer's glass share reflects: direct light off its
// specular lobe, estimated the same way per layer, whichever way the walk goes (the glass
// share is neither solid nor passing). For smooth glass the BSDF sample finds the mirrored
// emitter every frame, so the highlight is as stable as the glass. The reflection of lit
// surfaces (indirect light) is not modelled, in any mode; path rays see glass as tint only.
//
// The light of a layer is estimated by the walk's kind: the reference's camera rays use
// its own one light + one BSDF sample (direct_light_mis.wgsl; reference.wgsl estimates it
// where the walk pauses), the G-buffer's RIS over 8 light and 1 BSDF candidates
// (ris_direct_light.wgsl).
//
// Every walk here traces its rays at one call site and evaluates what it meets at one,
// however many branches lead there: the drivers inline every call, so each call site is a
// copy of the traversal and of the material code (docs/src/compile-time.md).
#include "common/transparency.wgsl"
#include "common/ris_direct_light.wgsl"

const WALK_PATH: u32 = 0u;              // path and GI rays: no culling, no layer light
const WALK_REFERENCE_CAMERA: u32 = 1u;  // culling; layer light by one light + one BSDF sample

struct LayerWalk {
    hit: Hit,              // the surface the ray stops at (t < 0: it left the scene)
    weight: vec3<f32>,     // what that surface's (or the background's) radiance is worth
    in_front: vec3<f32>,   // radiance toward the ray's origin from the layers met, weighted:
                           // their emission, their glass reflection (camera rays) and, in
                           // walk_to_primary, the share the primary surface leaves out
    origin: vec3<f32>,     // the origin of the last ray segment (viewer of `hit`)
    shadow_rays: u32,      // traced for those estimates
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

// A light estimate a walk owes: `weight` × the direct light at `sp`.
struct LightJob {
    sp: ShadingPoint,
    weight: vec3<f32>,
}

// What the glass share of a layer reflects toward `wo`: its specular lobe alone (base
// colour 0, metallic 0: brdf.wgsl then has no diffuse term and F = specularFactor·Schlick),
// worth `weight` × `glass`. False when it reflects nothing.
fn glass_reflection(hs: HitSurface, glass: f32, wo: vec3<f32>, weight: vec3<f32>, job: ptr<function, LightJob>) -> bool {
#ifdef SPECULAR
#ifndef PLANTED_NO_FRESNEL
    let m = eval_material(hs.material, hs.uv);
    if glass > 0.0 && m.specular > 0.0 {
        let lobe = make_brdf(vec3<f32>(0.0), 0.0, m.roughness, m.specular);
        *job = LightJob(hit_shading_point(hs, wo, lobe, 0.0), weight * glass);
        return true;
    }
#endif
#endif
    return false;
}

// Past the cap the next transparent surface is as far as light gets: opaque black.
fn stop_at_cap(walk: ptr<function, LayerWalk>) {
    if (*walk).hit.t >= 0.0 && is_transparent_triangle((*walk).hit.triangle) {
        (*walk).weight = vec3<f32>(0.0);
    }
}

// A random walk through layers in progress (`walk_layers`). A camera ray's walk stops at
// each layer whose glass share reflects light (`glass`): the caller estimates that light
// at the call site it shades the surface with and resumes the walk, so the reference
// compiles one direct-light estimate, not two (docs/src/compile-time.md). The random
// numbers are drawn in the same order as if the walk estimated that light itself.
struct WalkProgress {
    walk: LayerWalk,
    layer: u32,             // layers passed
    max_layers: u32,
    next_origin: vec3<f32>, // where the next ray starts (offset past the last layer)
    need_ray: bool,
    met_hs: HitSurface,     // the layer met and not yet passed (`met_pending`)
    met_solid: f32,
    met_pass_through: vec3<f32>,
    met_pending: bool,
    glass: LightJob,        // the glass reflection owed when walk_advance returns true
}

// A walk whose first ray starts at `ray_origin` (a camera, or a point offset from the
// surface the ray leaves: `origin` is the viewer of the first hit), through at most
// `max_layers` transparent layers (MAX_TRANSPARENT_LAYERS for a whole ray).
fn walk_begin(ray_origin: vec3<f32>, origin: vec3<f32>, max_layers: u32) -> WalkProgress {
    var p: WalkProgress;
    p.walk = LayerWalk(no_hit(), vec3<f32>(1.0), vec3<f32>(0.0), origin, 0u);
    p.layer = 0u;
    p.max_layers = max_layers;
    p.next_origin = ray_origin;
    p.need_ray = true;
    p.met_pending = false;
    return p;
}

// Advances the walk along `dir`: at each layer the ray stops with probability `solid`
// (the layer is then the surface, shaded as opaque), else it goes on with weight
// pass_through / (1 − solid). Returns true when a camera walk (`kind` not WALK_PATH, which
// also keeps the camera rule for single-sided back faces) stops at a glass reflection it
// owes, false once the walk has found its surface or left the scene (`walk.hit`).
fn walk_advance(p: ptr<function, WalkProgress>, dir: vec3<f32>, kind: u32, rng: ptr<function, u32>) -> bool {
    loop {
#ifdef TRANSPARENCY
        if (*p).met_pending {
            (*p).met_pending = false;
            if rand_f32(rng) < (*p).met_solid {
                return false;
            }
            let hs = (*p).met_hs;
            (*p).walk.in_front += (*p).walk.weight * emission_toward_viewer(hs);
            (*p).walk.weight *= (*p).met_pass_through / max(1.0 - (*p).met_solid, 1e-6);
            if !any((*p).walk.weight > vec3<f32>(0.0)) {
                (*p).walk.hit.t = -1.0;
                return false;
            }
            (*p).walk.origin = origin_past_layer(hs.position, (*p).walk.hit.triangle, dir);
            (*p).next_origin = (*p).walk.origin;
            (*p).need_ray = true;
            (*p).layer += 1u;
        }
#endif
        // The walk's one trace call site (each is compiled as a copy of the traversal).
        if (*p).need_ray {
            (*p).walk.hit = trace_closest(Ray((*p).next_origin, dir, FLT_MAX), kind != WALK_PATH);
            (*p).need_ray = false;
        }
#ifdef TRANSPARENCY
        let hit = (*p).walk.hit;
        if hit.t < 0.0 || !is_transparent_triangle(hit.triangle) {
            return false;
        }
        if (*p).layer == (*p).max_layers {
            // Past the cap this transparent surface is as far as light gets: opaque black.
            (*p).walk.weight = vec3<f32>(0.0);
            return false;
        }
        let hs = hit_surface(hit.triangle, hit.u, hit.v, (*p).walk.origin);
        let l = triangle_layer(hit.triangle, hit.u, hit.v, dir);
        (*p).met_hs = hs;
        (*p).met_solid = l.solid;
        (*p).met_pass_through = l.pass_through;
        (*p).met_pending = true;
        var job: LightJob;
        if kind != WALK_PATH && glass_reflection(hs, l.glass, -dir, (*p).walk.weight, &job) {
            (*p).glass = job;
            return true;
        }
#else
        return false;
#endif
    }
    return false;  // not reached (WGSL wants a return after a loop)
}

// A GI ray's walk, whole, tracing its first ray from `ray_origin` (offset from the
// surface it leaves: `origin` is the viewer of the first hit). Path rays owe no glass
// reflection.
fn trace_and_walk_layers(ray_origin: vec3<f32>, origin: vec3<f32>, dir: vec3<f32>, max_layers: u32, rng: ptr<function, u32>) -> LayerWalk {
    var p = walk_begin(ray_origin, origin, max_layers);
    while walk_advance(&p, dir, WALK_PATH, rng) {}
    return p.walk;
}

// What a BSDF-sampled ray finds (path_trace.wgsl, pt/path.wgsl): the emitter it meets
// first through clear layers (the BSDF strategy's sample of direct light, when
// `find_light`; transparency.wgsl's find_light_through), and where the path goes on (a
// random walk through the layers, as walk_advance). Both follow the same ray, so they share
// its traces and each layer's evaluation: one trace call site, not three
// (docs/src/compile-time.md). The walk draws its random numbers as walk_advance does.
struct FollowedRay {
    found: FoundLight,
    walk: LayerWalk,
}

fn follow_ray(ray_origin: vec3<f32>, origin: vec3<f32>, dir: vec3<f32>, find_light: bool, rng: ptr<function, u32>) -> FollowedRay {
    var out: FollowedRay;
    out.found = FoundLight(LightSampleId(NO_LIGHT, vec2<f32>(0.0)), vec3<f32>(0.0));
    out.walk = LayerWalk(no_hit(), vec3<f32>(1.0), vec3<f32>(0.0), origin, 0u);
    var finding = find_light;
    var walking = true;
    var transmittance = vec3<f32>(1.0);
    var next_origin = ray_origin;
    for (var layer = 0u; layer <= MAX_TRANSPARENT_LAYERS; layer++) {
        let hit = trace_closest(Ray(next_origin, dir, FLT_MAX), false);
        if walking {
            out.walk.hit = hit;
        }
        if hit.t < 0.0 {
#ifdef ENVIRONMENT
            if finding {
                out.found = FoundLight(LightSampleId(env.light, env_direction_to_uv(dir)), transmittance);
            }
#endif
            break;
        }
        let light = triangles[hit.triangle].light;
        let transparent = is_transparent_triangle(hit.triangle);
        // The light search ends at an emitter (transparent or not) or an opaque surface;
        // a clear layer tints it.
        let search_passes = finding && light == NO_LIGHT && transparent && layer < MAX_TRANSPARENT_LAYERS;
        if finding && !search_passes {
            out.found = FoundLight(LightSampleId(light, vec2<f32>(hit.u, hit.v)), transmittance);
            finding = false;
        }
        // The walk ends at an opaque surface; past the cap light gets no further.
        if walking && !transparent {
            walking = false;
        } else if walking && layer == MAX_TRANSPARENT_LAYERS {
            out.walk.weight = vec3<f32>(0.0);
            walking = false;
        }
#ifdef TRANSPARENCY
        if !(finding || walking) {
            break;
        }
        let l = triangle_layer(hit.triangle, hit.u, hit.v, dir);
        next_origin = origin_past_layer(next_origin + dir * hit.t, hit.triangle, dir);
        if finding {
            transmittance *= l.pass_through;
            if !any(transmittance > vec3<f32>(0.0)) {
                finding = false;
            }
        }
        if walking {
            let hs = hit_surface(hit.triangle, hit.u, hit.v, out.walk.origin);
            if rand_f32(rng) < l.solid {
                walking = false;  // the walk stops at this layer, its surface
            } else {
                out.walk.in_front += out.walk.weight * emission_toward_viewer(hs);
                out.walk.weight *= l.pass_through / max(1.0 - l.solid, 1e-6);
                if !any(out.walk.weight > vec3<f32>(0.0)) {
                    out.walk.hit.t = -1.0;
                    walking = false;
                } else {
                    out.walk.origin = origin_past_layer(hs.position, hit.triangle, dir);
                    next_origin = out.walk.origin;
                }
            }
        }
        if !(finding || walking) {
            break;
        }
#else
        break;
#endif
    }
    return out;
}

#ifdef TRANSPARENCY
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
// Written as one loop of small steps, the light estimates queued and taken one per step,
// the rays traced one per step, and each step looking at its surface through one
// evaluation (hit_surface, triangle_layer, emission, a surface's light): the drivers inline
// every call and unroll fixed-count loops, so the nested form (a random walk behind a held
// layer, inside the layer loop, each layer with two RIS estimates) grew to dozens of copies
// of RIS and traversal and took minutes to compile on lavapipe
// (docs/src/compile-time.md). Behind a held layer, what passes is one random walk (stop at
// a layer with probability `solid`), ending in the emission and RIS light of the surface it
// reaches, or the environment.
fn walk_to_primary(origin: vec3<f32>, dir: vec3<f32>, first: Hit, rng: ptr<function, u32>) -> LayerWalk {
    var walk = LayerWalk(first, vec3<f32>(1.0), vec3<f32>(0.0), origin, 0u);
#ifdef TRANSPARENCY
    var jobs: array<LightJob, 2>;
    var queued = 0u;
    var step = STEP_PRIMARY;
    var layer = 0u;
    // The walk behind a held layer: its ray, how many layers it may still pass, whether it
    // stopped at a layer (chosen as its surface), and what its light is worth.
    var behind = LayerWalk(first, vec3<f32>(0.0), vec3<f32>(0.0), origin, 0u);
    var behind_left = 0u;
    var behind_stopped = false;
    // A ray a step asked for, traced at the top of the next iteration. Tracing draws no
    // random number, so the order of the draws is the same as if each step traced its own.
    var ray_pending = false;
    // Each layer takes at most four iterations (its step, two estimates, its ray): the
    // bound is never reached (8 layers ahead, 8 behind), it only makes termination evident.
    for (var guard = 0u; guard < 8u * MAX_TRANSPARENT_LAYERS + 8u; guard++) {
        let in_behind = step == STEP_BEHIND;
        if ray_pending {
            ray_pending = false;
            var ray_from = walk.origin;
            if in_behind {
                ray_from = behind.origin;
            }
            let hit = trace_closest(Ray(ray_from, dir, FLT_MAX), true);
            if in_behind {
                behind.hit = hit;
            } else {
                walk.hit = hit;
            }
            continue;
        }
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
        // The walk this step advances (the primary one, or the one behind a held layer).
        var cur = walk;
        var left = MAX_TRANSPARENT_LAYERS - layer;
        if in_behind {
            cur = behind;
            left = behind_left;
        }
        let hit = cur.hit;
        let at_layer = hit.t >= 0.0 && is_transparent_triangle(hit.triangle) && !(in_behind && behind_stopped);
        let ends = !at_layer || left == 0u;
        // What this step looks at: a layer to pass or hold, or the surface the walk behind
        // ends on (the primary walk's end is the caller's to shade).
        var hs: HitSurface;
        var l = opaque_layer();
        if hit.t >= 0.0 && (in_behind || !ends) {
            hs = hit_surface(hit.triangle, hit.u, hit.v, cur.origin);
            if !ends {
                l = triangle_layer(hit.triangle, hit.u, hit.v, dir);
            }
        }
        var emission_weight = vec3<f32>(0.0);  // this step adds emission × this
        var surface_weight = vec3<f32>(0.0);   // this step queues the surface's light × this
        if ends {
            step = STEP_DONE;
            if at_layer {
                // Past the cap the next transparent surface is as far as light gets.
                cur.weight = vec3<f32>(0.0);
            } else if in_behind {
                if hit.t < 0.0 {
#ifdef ENVIRONMENT
                    walk.in_front += cur.weight * env_background(dir);
#endif
                } else if any(cur.weight > vec3<f32>(0.0)) {
                    emission_weight = cur.weight;
                    surface_weight = cur.weight;
                }
            }
        } else {
            queue_glass_reflection(&jobs, &queued, hs, l.glass, -dir, cur.weight);
            let past = origin_past_layer(hs.position, hit.triangle, dir);
            if in_behind {
                // One layer of the random walk behind.
                if rand_f32(rng) < l.solid {
                    behind_stopped = true;  // this layer is the surface the walk reaches
                } else {
                    emission_weight = cur.weight;
                    cur.weight *= l.pass_through / max(1.0 - l.solid, 1e-6);
                    if !any(cur.weight > vec3<f32>(0.0)) {
                        cur.hit.t = -1.0;
                    } else {
                        cur.origin = past;
                        ray_pending = true;
                        behind_left -= 1u;
                    }
                }
            } else {
                emission_weight = cur.weight;
#ifdef PLANTED_RANDOM_LAYER_CHOICE
                // Test only: the choice before, at random by solid, which a still view
                // redraws every frame (the other share is then left to the choice, not
                // sampled).
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
                    // The layer is the primary surface (ReSTIR shades its solid share);
                    // what passes is sampled once, by the walk behind.
                    step = STEP_DONE;
                    if sample_other && any(l.pass_through > vec3<f32>(0.0)) {
                        behind.origin = past;
                        behind.weight = cur.weight * l.pass_through;
                        behind_left = MAX_TRANSPARENT_LAYERS - layer - 1u;
                        ray_pending = true;
                        step = STEP_BEHIND;
                    }
                    cur.weight *= held_share;
                } else {
                    // What lies behind holds the primary surface; the layer's solid share
                    // is lit once.
                    if sample_other && l.solid > 0.0 {
                        surface_weight = cur.weight * l.solid;
                    }
                    cur.weight *= passed_share;
                    if !any(cur.weight > vec3<f32>(0.0)) {
                        cur.hit.t = -1.0;
                        step = STEP_DONE;
                    } else {
                        cur.origin = past;
                        ray_pending = true;
                        layer += 1u;
                    }
                }
            }
        }
        if any(emission_weight > vec3<f32>(0.0)) {
            walk.in_front += emission_weight * emission_toward_viewer(hs);
        }
        if any(surface_weight > vec3<f32>(0.0)) {
            jobs[queued] = LightJob(hit_shading_point(hs, -dir, hit_brdf(hs), 0.0), surface_weight);
            queued += 1u;
        }
        // Hand the step's walk back (walk.in_front is the primary walk's: keep it).
        if in_behind {
            behind = cur;
        } else {
            cur.in_front = walk.in_front;
            walk = cur;
        }
    }
#endif
    return walk;
}

#ifdef TRANSPARENCY
// Queues what the glass share of a layer reflects (`glass_reflection`) for the G-buffer's
// walk.
fn queue_glass_reflection(jobs: ptr<function, array<LightJob, 2>>, queued: ptr<function, u32>, hs: HitSurface, glass: f32, wo: vec3<f32>, weight: vec3<f32>) {
    var job: LightJob;
    if glass_reflection(hs, glass, wo, weight, &job) {
        (*jobs)[*queued] = job;
        *queued += 1u;
    }
}
#endif
