// Final shading: one shadow ray for the survivor, f(x, y) · V · W, plus the emission seen
// directly (or the environment where the camera sees no surface). Also accumulates the running sum for progressive averaging and counts the
// selection source of every pixel for the stats.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"
#ifdef ENVIRONMENT
#include "common/camera_ray.wgsl"
#endif

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> reservoirs: array<Reservoir>;
@group(2) @binding(2) var<storage, read_write> debug: array<PixelDebug>;
@group(2) @binding(3) var<storage, read_write> radiance: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> accumulation: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var color = vec3<f32>(0.0);
    if surface_is_valid(s) {
        count_stat(STAT_SURFACE_PIXELS);
        color = s.emission;
        var r = reservoirs[index];
        var d = debug[index];
        if reservoir_is_corrupt(r) {
            count_stat(STAT_NONFINITE + PASS_SHADE);
            r = reservoir_empty();
        }
        d.weight = 0.0;
        d.p_hat = 0.0;
        if !reservoir_is_null(r) {
            let sp = shading_point_from_surface(s, frame.camera_position);
            let lp = light_point(r.light, r.uv);
            let c = light_contribution(sp, lp);
            d.weight = r.weight;
            d.p_hat = target_pdf(c);
            // With visibility in the target (mis_visibility) every survivor was traced
            // from this very point when it was picked (initial visibility, temporal and
            // spatial reuse): the same ray again would give the same answer.
            var transmittance = select(vec3<f32>(0.0), vec3<f32>(1.0), d.p_hat > 0.0);
            var trace = (params.flags & PARAM_FLAG_MIS_VISIBILITY) == 0u;
#ifdef TEST_TRACE_SURVIVOR
            trace = true;  // test only: trace the ray the shortcut saves (it must change nothing)
#endif
#ifdef TRANSPARENCY
            trace = true;  // visibility reuse knows that light gets through, not its tint
#endif
            if d.p_hat > 0.0 && trace {
                add_stat(STAT_SHADOW_RAYS + PASS_SHADE, 1u);
                transmittance = light_transmittance(sp, lp, c).value;
            }
            color += s.throughput * (c.value * transmittance) * r.weight;
#ifdef ENVIRONMENT
            if lp.kind == LIGHT_POINT_ENVIRONMENT {
                d.flags |= DEBUG_FLAG_ENVIRONMENT_SAMPLE;
            }
#endif
        }
        let source = select(reservoir_source(r), SOURCE_NULL, reservoir_is_null(r));
        count_stat(STAT_SOURCE + source);
        d.source = source;
        debug[index] = d;
    }
#ifdef ENVIRONMENT
    else {
        // The camera ray leaves the scene: the sky, through the jittered sample position
        // the rasteriser used (pixel p sampled p + 0.5 − jitter).
        color = s.emission + s.throughput * env_background(camera_ray_direction(vec2<f32>(id.xy) + 0.5 - frame.jitter));
    }
#else
    else {
        color = s.emission;  // glass seen against nothing
    }
#endif
    if !is_finite_vec3(color) {
        count_stat(STAT_NONFINITE + PASS_SHADE);
        color = vec3<f32>(0.0);
    }
    radiance[index] = vec4<f32>(color, 1.0);
    accumulation[index] += vec4<f32>(color, 1.0);
}
