// ReSTIR GI initial sample (Ouyang et al. 2021 §3.1): one BSDF-sampled ray from the primary hit
// x_v; at the secondary hit x_s its outgoing direct radiance toward x_v, estimated with DI's
// machinery: RIS over `gi_light_candidates` lights from the vertex sampler
// (common/vertex_light.wgsl) with the unshadowed target, one shadow ray for the survivor.
// Emission of x_s itself is not part of L_o: seen from x_v it is direct light, which ReSTIR
// DI already counts (docs/src/restir-gi.md, "The sample"). The sample
// (x_s, n_s, L_o) has source pdf p_ω (solid angle at x_v); one candidate, so W = 1 / p_ω, M = 1.
#include "gi/reuse.wgsl"
#include "common/layer_walk.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read_write> gi_out: array<GiReservoir>;
@group(2) @binding(2) var<storage, read_write> gi_debug: array<GiPixelDebug>;
// The light BVH, for the vertex sampler (common/vertex_light.wgsl); one-element
// placeholders unless VERTEX_LIGHT_BVH is compiled.
@group(2) @binding(3) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(4) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

// f · Le · G · V · W of one RIS-selected light point at `sp` (0 in shadow or without lights).
fn direct_light_estimate(sp: ShadingPoint, rng: ptr<function, u32>) -> vec3<f32> {
    let n = params.gi.light_candidates;
    if frame.light_count == 0u || n == 0u {
        return vec3<f32>(0.0);
    }
    var w_sum = 0.0;
    var chosen_target = 0.0;
    var chosen_point: LightPoint;
    var chosen: LightContribution;
    for (var i = 0u; i < n; i++) {
        let lp = sample_light_point_at(sp, rng);
        let c = light_contribution(sp, lp);
        let t = target_pdf(c);
        let u = rand_f32(rng);
        if !(t > 0.0) || !(lp.source_pdf > 0.0) {
            continue;
        }
        let w = t / (f32(n) * lp.source_pdf);
        w_sum += w;
        if u * w_sum < w {
            chosen_target = t;
            chosen_point = lp;
            chosen = c;
        }
    }
    if !(chosen_target > 0.0) {
        return vec3<f32>(0.0);
    }
    let transmittance = light_transmittance(sp, chosen_point, chosen).value;
    return chosen.value * transmittance * (w_sum / chosen_target);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var r = gi_reservoir_empty();
    var d = GiPixelDebug(0u, 0u, 0u, 1.0, 0.0, 0.0, 0.0, 0u);
    if surface_is_valid(s) {
        let sp = shading_point_from_surface(s, frame.camera_position);
        var rng = rng_seed(id.xy, STREAM_INDIRECT_INITIAL);
        let u = vec3<f32>(rand_f32(&rng), rand_f32(&rng), rand_f32(&rng));
        let bs = sample_brdf(sp.brdf, sp.normal, sp.wo, u);
        if bs.pdf > 0.0 && dot(bs.wi, sp.geo_normal) > 0.0 {
            let ray = Ray(offset_ray_origin(sp.position, sp.geo_normal), bs.wi, FLT_MAX);
            // Back faces of single-sided surfaces are hit too (they occlude and reflect).
            // Through transparent layers, the secondary vertex is where the walk stops.
            let walk = trace_and_walk_layers(ray.origin, sp.position, bs.wi, MAX_TRANSPARENT_LAYERS, &rng);
            let hit = walk.hit;
            if hit.t >= 0.0 {
                let hs = hit_surface(hit.triangle, hit.u, hit.v, walk.origin);
                let m = eval_material(hs.material, hs.uv);
                let brdf = make_brdf(m.base_color, m.metallic, m.roughness, m.specular);
                let secondary = ShadingPoint(hs.position, hs.normal, hs.geo_normal, -bs.wi, brdf, hs.material, length(hs.position - sp.position));
                let radiance = walk.weight * direct_light_estimate(secondary, &rng);
                let p_hat = gi_target_at(sp, hs.position, radiance);
                let w = gi_initial_weight(p_hat, bs.pdf, 1.0);
                gi_reservoir_update(&r, hs.position, oct_encode(hs.geo_normal), radiance, w, p_hat, gi_pack(SOURCE_INITIAL, 0u, 0u), rand_f32(&rng));
                gi_reservoir_finalize(&r, 1.0);
            }
        }
        r.m = 1.0;
        r = gi_guarded(r, INDIRECT_PASS_INITIAL);
        d.m_initial = r.m;
    }
    gi_out[index] = r;
    gi_debug[index] = d;
}
