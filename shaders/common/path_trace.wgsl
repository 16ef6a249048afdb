// The reference's multi-bounce estimator (`max_bounces` ≥ 2; docs/src/frame.md, "The reference").
// A path from the first vertex (camera hit or rasterised surface) is shaded at each of its
// first max_bounces vertices with next-event estimation (`reference_light_samples` light
// points, each with a shadow ray) and continued along one BSDF-sampled direction; the emitter (or the
// environment) that direction finds is the BSDF strategy's sample of that vertex's direct
// light, weighted against the light sample by the balance heuristic
// (common/direct_light_mis.wgsl), so every emitter is counted exactly once per vertex.
// Unbiased: no Russian roulette, a path ends only where its throughput is exactly zero
// (no BSDF sample, a direction below the surface, a miss).
//
// max_bounces = N adds Le·(a + a² + … + a^N) to the emission seen directly in a closed
// box of albedo a whose walls all emit Le (render/tests/multi_bounce.rs).
//
// PLANTED_NO_THROUGHPUT_PDF (here) and PLANTED_NO_BSDF_MIS (direct_light_mis.wgsl) exist
// only for the furnace test's power checks (EffectSet::planted): they break the estimator
// in the way the test must notice.
#include "common/layer_walk.wgsl"

// Everything past the emission seen directly: direct light at each of the first
// `bounces` vertices of a BSDF-sampled path starting at `first`.
fn path_estimate(first: ShadingPoint, bounces: u32, rng: ptr<function, u32>) -> vec3<f32> {
    var sp = first;
    var throughput = vec3<f32>(1.0);
    var sum = vec3<f32>(0.0);
    let n = reference_light_samples();
    for (var bounce = 1u; bounce <= bounces; bounce++) {
        if frame.light_count > 0u {
            // Along a path the BSDF ray is always traced (it continues the path), so its
            // pdf is in the light samples' weight whether or not shadows are compiled in.
            sum += throughput * light_samples_mis(sp, rng, true, n).value;
        }
        let u = vec3<f32>(rand_f32(rng), rand_f32(rng), rand_f32(rng));
        let bs = sample_brdf(sp.brdf, sp.normal, sp.wo, u);
        let cos_x = dot(sp.normal, bs.wi);
        // Below the shading or the geometric horizon the integrand is zero (the same rule
        // as light_contribution): the path ends, its expected value unchanged.
        if !(bs.pdf > 0.0) || cos_x <= 0.0 || dot(sp.geo_normal, bs.wi) <= 0.0 {
            break;
        }
#ifdef PLANTED_NO_THROUGHPUT_PDF
        let weight = eval_brdf(sp.brdf, sp.normal, sp.wo, bs.wi) * cos_x;
#else
        let weight = eval_brdf(sp.brdf, sp.normal, sp.wo, bs.wi) * (cos_x / bs.pdf);
#endif
        // A grazing direction with a tiny pdf can overflow: drop the path, not the pixel.
        if !is_finite_vec3(weight) {
            break;
        }
        // The emitter this direction finds through clear layers (the BSDF strategy's
        // sample of direct light), and where the path goes on (layer_walk.wgsl).
        let followed = follow_ray(offset_ray_origin(sp.position, sp.geo_normal), sp.position, bs.wi, true, rng);
        let found = followed.found;
        if frame.light_count > 0u {
            sum += throughput * found.transmittance * bsdf_found_emission(sp, bs, found.id, f32(n));
        }
        let walk = followed.walk;
        let hit = walk.hit;
        throughput *= weight * walk.weight;
        if hit.t <= 0.0 || bounce == bounces || !any(throughput > vec3<f32>(0.0)) {
            break;
        }
        // The next vertex, seen from this one (normals flipped to its side, as for a
        // camera ray; BSDF rays do not cull back faces, so a path may leave a thin
        // single-sided surface from behind).
        let hs = hit_surface(hit.triangle, hit.u, hit.v, walk.origin);
        sp = hit_shading_point(hs, -bs.wi, hit_brdf(hs), sp.depth + length(hs.position - sp.position));
    }
    return sum;
}
