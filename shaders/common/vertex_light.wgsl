// The light sampler at every light-sampling site past DI's candidates (docs/src/light-samplers.md,
// "At every vertex"): next-event estimation at GI's secondary hit and at PT's path vertices,
// the light of transparent layers, and the reference's vertices. With VERTEX_LIGHT_BVH the
// lights with a position are drawn by the light BVH's walk at the vertex, as DI's candidates
// are (di/initial.wgsl); otherwise by the power table. Either way a light point's `source_pdf`
// is the PDF of the sampler that drew it at this vertex, and the BSDF strategy's MIS
// weight reads the same PDF for the emitter its ray found, so the balance heuristic
// compares the two strategies that actually ran. Without VERTEX_LIGHT_BVH both functions
// are `sample_light` and `light_point` (the one-bounce reference stays bit for bit).
//
// A pass that compiles VERTEX_LIGHT_BVH binds `light_bvh_nodes` and `light_bvh_trails`.
#include "common/shading_point.wgsl"
#ifdef VERTEX_LIGHT_BVH
#include "common/light_bvh.wgsl"
#endif

// The point of NO_LIGHT: no radiance, density 0.
fn no_light_point() -> LightPoint {
    var none: LightPoint;
    none.source_pdf = 0.0;
    none.radiance = vec3<f32>(0.0);
    return none;
}

// A light sample drawn at sp, and the selection probability the tree drew its light with
// (`tree_selection` < 0: the power table drew it).
struct VertexLightDraw {
    id: LightSampleId,
    tree_selection: f32,
}

// A light sample at sp (light NO_LIGHT: the tree holds no light with power).
fn draw_light_at(sp: ShadingPoint, rng: ptr<function, u32>) -> VertexLightDraw {
    let y0 = sample_light(rng);
#ifdef VERTEX_LIGHT_BVH
    // As DI's candidates: the table picks between the lights with a position (then the
    // tree picks which one) and the others (kept).
    if light_is_finite(y0.light) {
        let walk = light_bvh_sample(sp.position, sp.normal, 0.0, rand_f32(rng));
        if walk.light == NO_LIGHT {
            return VertexLightDraw(LightSampleId(NO_LIGHT, vec2<f32>(0.0)), 0.0);
        }
        return VertexLightDraw(sample_point_on_light(walk.light, rng), frame.finite_light_share * walk.pdf);
    }
#endif
    return VertexLightDraw(y0, -1.0);
}

// A light sample at sp, without its point (ReSTIR PT keeps the sample and evaluates its
// point where the path needs it, at whichever vertex a shift put it).
fn sample_light_at(sp: ShadingPoint, rng: ptr<function, u32>) -> LightSampleId {
    return draw_light_at(sp, rng).id;
}

// A light sample's point at sp, `source_pdf` the density it was drawn with (0 for NO_LIGHT).
// The tree's density comes from the walk itself: the same product of branch probabilities
// `light_point_at` recomputes along the light's trail, for one traversal.
fn sample_light_point_at(sp: ShadingPoint, rng: ptr<function, u32>) -> LightPoint {
    let d = draw_light_at(sp, rng);
    if d.id.light == NO_LIGHT {
        return no_light_point();
    }
    let lp = light_point(d.id.light, d.id.uv);
#ifndef PLANTED_VERTEX_TABLE_PDF
    if d.tree_selection >= 0.0 {
        return with_selection_pdf(lp, d.id.light, d.tree_selection);
    }
#endif
    return lp;
}

// The point of a light sample with its density under the vertex sampler at sp (area
// measure for triangles, discrete for punctual lights, solid angle for the sky). A point
// of NO_LIGHT has density 0 and no radiance.
fn light_point_at(sp: ShadingPoint, light: u32, uv: vec2<f32>) -> LightPoint {
    if light == NO_LIGHT {
        return no_light_point();
    }
    let lp = light_point(light, uv);
#ifdef VERTEX_LIGHT_BVH
#ifndef PLANTED_VERTEX_TABLE_PDF
    if light_is_finite(light) {
        return with_selection_pdf(lp, light, frame.finite_light_share * light_bvh_pdf(light, sp.position, sp.normal));
    }
#endif
#endif
    return lp;
}
