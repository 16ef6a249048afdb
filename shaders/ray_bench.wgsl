// The tracing backends' throughput (`restir-viewer bench-rays`, render/src/renderer/
// ray_bench.rs): RAY_BENCH_RAYS_PER_PIXEL rays from each G-buffer surface through the same
// functions every pass calls (trace.wgsl), so the time of this dispatch is the price of
// rays alone. Slot 0 (RAY_BENCH_SHADOW): shadow rays toward power-sampled light points, as
// the reuse passes trace them (transmittance: any hit, layers multiplied). Slot 1
// (RAY_BENCH_CLOSEST): closest-hit rays along cosine-distributed directions, as BSDF and
// path rays are. Each pixel writes its ray count and hits, so nothing is optimised away.
#include "common/frame_bindings.wgsl"
#include "common/shading_point.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read_write> ray_counts: array<u32>;
@group(2) @binding(2) var<uniform> pass_info: PassInfo;

// A direction in the hemisphere around n with density cos θ / π.
fn cosine_direction(n: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    let r = sqrt(u.x);
    let phi = 2.0 * PI * u.y;
    return basis_from_normal(n) * vec3<f32>(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var rays = 0u;
    var hits = 0u;
    if surface_is_valid(s) {
        let sp = shading_point_from_surface(s, frame.camera_position);
        var rng = rng_seed(id.xy, STREAM_INITIAL);
        let origin = offset_ray_origin(sp.position, sp.geo_normal);
        for (var i = 0u; i < RAY_BENCH_RAYS_PER_PIXEL; i++) {
            if pass_info.pass_index == RAY_BENCH_SHADOW {
                if frame.light_count == 0u {
                    break;
                }
                let y = sample_light(&rng);
                let lp = light_point(y.light, y.uv);
                let blocked = !any(light_transmittance(sp, lp, light_contribution(sp, lp)).value > vec3<f32>(0.0));
                hits += u32(blocked);
            } else {
                let dir = cosine_direction(sp.geo_normal, rand_vec2(&rng));
                hits += u32(trace_closest(Ray(origin, dir, FLT_MAX), false).t > 0.0);
            }
            rays++;
        }
    }
    ray_counts[index] = rays | (hits << 16u);
}
