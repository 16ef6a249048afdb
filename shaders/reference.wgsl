// Ground truth: an unbiased progressive estimator, independent of the raster G-buffer.
// Per sample: a jittered camera ray through the BVH, the emission it sees, one
// power-sampled light point (or environment direction) with a shadow ray and one BSDF ray
// (which finds an emitter or escapes to the environment), combined with the balance
// heuristic (both are unbiased on their own; MIS only lowers the variance on glossy
// surfaces). Many samples per pixel, averaged over frames by the accumulation buffer.
// With max_bounces ≥ 2 the BSDF ray continues the path and every vertex is shaded the
// same way (common/path_trace.wgsl).
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/camera_ray.wgsl"
#include "common/path_trace.wgsl"
#include "common/layer_walk.wgsl"

@group(2) @binding(0) var<storage, read_write> radiance: array<vec4<f32>>;
@group(2) @binding(1) var<storage, read_write> accumulation: array<vec4<f32>>;
// pass_index = which chunk of REFERENCE_SAMPLES_PER_DISPATCH samples this dispatch takes.
@group(2) @binding(2) var<uniform> pass_info: PassInfo;
@group(2) @binding(3) var<storage, read> surfaces: array<Surface>;
// The light BVH, for the vertex sampler (common/vertex_light.wgsl); one-element
// placeholders unless VERTEX_LIGHT_BVH is compiled.
@group(2) @binding(4) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(5) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let chunk = pass_info.pass_index;
    var rng = pcg_hash(rng_seed(id.xy, STREAM_REFERENCE) ^ pcg_hash(chunk));
    var sum = vec3<f32>(0.0);
    let spp = max(params.reference_spp, 1u);
    let first = chunk * REFERENCE_SAMPLES_PER_DISPATCH;
    let last = min(spp, first + REFERENCE_SAMPLES_PER_DISPATCH);
    let jitter = (params.flags & PARAM_FLAG_JITTER) != 0u;
    var camera_ray = jitter;
#ifdef TRANSPARENCY
    // Jitter off, but the pixel centre meets a transparent layer: the G-buffer's surface is
    // one frame's choice of layer, so each sample traces the centre ray and draws its own.
    camera_ray = camera_ray || surfaces[index].transparent_first != 0u;
#endif
    for (var i = first; i < last; i++) {
        var sample_value = vec3<f32>(0.0);
        // What the shading at sp is worth: < 1 behind glass (transparency.wgsl).
        var throughput = vec3<f32>(1.0);
        // The camera ray (jitter, or glass at the pixel centre): the pixel-area integral,
        // a jittered ray through the BVH, on through transparent layers (each sample draws
        // its own choices). It stops at each glass reflection it owes.
        var dir = vec3<f32>(0.0);
        var walk: WalkProgress;
        if camera_ray {
            // Jitter off: the point the G-buffer was rasterised at (the pixel centre, or a
            // jitter phase's offset: docs/src/viewer.md, "Accuracy with jitter on").
            var at = vec2<f32>(0.5) - frame.jitter;
            if jitter {
                at = rand_vec2(&rng);
            }
            dir = camera_ray_direction(vec2<f32>(id.xy) + at);
            walk = walk_begin(frame.camera_position, frame.camera_position, MAX_TRANSPARENT_LAYERS);
        }
        // Direct light is estimated at one call site, first for each glass reflection the
        // camera ray meets, then for the surface (each call site is compiled as a copy of
        // the estimator: docs/src/compile-time.md).
        loop {
            var job: LightJob;
            let at_glass = camera_ray && walk_advance(&walk, dir, WALK_REFERENCE_CAMERA, &rng);
            if at_glass {
                job = walk.glass;
            } else {
                var sp: ShadingPoint;
                if camera_ray {
                    let hit = walk.walk.hit;
                    throughput = walk.walk.weight;
                    sum += walk.walk.in_front;
                    if hit.t < 0.0 {
#ifdef ENVIRONMENT
                        sum += throughput * env_background(dir);
#endif
                        break;
                    }
                    let hs = hit_surface(hit.triangle, hit.u, hit.v, frame.camera_position);
                    sp = hit_shading_point(hs, -dir, hit_brdf(hs), length(hs.position - frame.camera_position));
                    sample_value = emission_toward_viewer(hs);
                } else {
                    // Jitter off: the surface the rasterised G-buffer sees at the pixel
                    // centre (or a jitter phase's offset), so a comparison with the real-time modes measures lighting
                    // error alone (a ray and the rasteriser may disagree on a pixel centre
                    // exactly on an edge). Behind glass the G-buffer's own choice of layer
                    // is taken as well, so this averages over that choice only as far as
                    // the frames do (docs/src/transparency.md, "Camera rays").
                    let s = surfaces[index];
                    if !surface_is_valid(s) {
#ifdef TRANSPARENCY
                        sum += s.emission;
#endif
#ifdef ENVIRONMENT
                        sum += s.throughput * env_background(camera_ray_direction(vec2<f32>(id.xy) + 0.5 - frame.jitter));
#endif
                        break;
                    }
                    sp = shading_point_from_surface(s, frame.camera_position);
#ifdef TRANSPARENCY
                    // s.emission already holds the layers in front, weighted: shading is
                    // added with the throughput below.
                    throughput = s.throughput;
                    sum += s.emission;
                    sample_value = vec3<f32>(0.0);
#else
                    sample_value = s.emission;
#endif
                }
                if params.max_bounces > 1u {
                    // Indirect light too: a BSDF-sampled path (common/path_trace.wgsl).
                    sample_value += path_estimate(sp, min(params.max_bounces, MAX_BOUNCES), &rng);
                    sample_value *= throughput;
                    if is_finite_vec3(sample_value) {
                        sum += sample_value;
                    } else {
                        count_stat(STAT_NONFINITE + PASS_REFERENCE);
                    }
                    break;
                }
                // One bounce: the code as it was before paths, so max_bounces=1 renders the
                // same image bit for bit (render/tests/one_bounce_unchanged.rs).
                job = LightJob(sp, throughput);
            }
            var light = select(vec3<f32>(0.0), sample_value, !at_glass);
            add_direct_light(job.sp, &rng, &light);
            if at_glass {
                walk.walk.in_front += job.weight * light;
                continue;
            }
            sample_value = light * throughput;
            if is_finite_vec3(sample_value) {
                sum += sample_value;
            } else {
                count_stat(STAT_NONFINITE + PASS_REFERENCE);
            }
            break;
        }
    }
    // This chunk's share of the pixel's average; the first chunk starts the frame.
    let share = sum / f32(spp);
    let previous = select(radiance[index].rgb, vec3<f32>(0.0), chunk == 0u);
    radiance[index] = vec4<f32>(previous + share, 1.0);
    accumulation[index] += vec4<f32>(share, select(0.0, 1.0, chunk == 0u));
}
