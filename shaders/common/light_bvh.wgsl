// The light BVH sampler (docs/src/light-samplers.md, "The light BVH"; Conty & Kulla 2018,
// pbrt-v4's BVHLightSampler): from the root, each child is taken with probability ∝ an
// upper bound on what its lights can send to the shading point (power over squared
// distance, times the most favourable emission and receiving angles its bounds allow), so
// a light's PDF is the product of the branch probabilities on its path — exact, and the
// same whether the walk drew it or a BSDF ray found it. The plain-Rust model
// (render/src/light_bvh.rs) is the same walk; the tree is uploaded from it. The pass binds
// `light_bvh_nodes` and `light_bvh_trails`.
#include "common/math.wgsl"

// cos(max(0, a − b)) and sin(max(0, a − b)) from the sines and cosines of a and b.
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        return 1.0;
    }
    return cos_a * cos_b + sin_a * sin_b;
}

fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        return 0.0;
    }
    return sin_a * cos_b - cos_a * sin_b;
}

fn sin_from_cos(c: f32) -> f32 {
    return sqrt(max(0.0, 1.0 - c * c));
}

// pbrt-v4's LightBounds::Importance for a node at point p with normal n (zero: none).
// `radius_around` > 0 bounds every point within that distance of p instead (ReGIR's cells: the
// node's sphere is grown by it, so the angle cut-off is 0 only where no light below can
// reach any such point). `orientation` false leaves out both angle terms (only the planted
// error of the tests).
fn light_bvh_importance(node: LightBvhNode, p: vec3<f32>, n: vec3<f32>, radius_around: f32, orientation: bool) -> f32 {
    if !(node.phi > 0.0) {
        return 0.0;
    }
    let pc = 0.5 * (node.min + node.max);
    let diagonal = length(node.max - node.min);
    let dist2 = dot(p - pc, p - pc);
    let d2 = max(dist2, 0.5 * diagonal);
    if !orientation {
        return node.phi / d2;
    }
    var wi = vec3<f32>(0.0);
    if dist2 > 0.0 {
        wi = (p - pc) * inverseSqrt(dist2);
    }
    let cos_w = dot(oct_decode(node.axis), wi);
    let sin_w = sin_from_cos(cos_w);
    // The directions from p the box subtends: its bounding sphere's cone.
    let radius = 0.5 * diagonal + radius_around;
    var cos_b = -1.0;
    if dist2 >= radius * radius {
        cos_b = sqrt(max(0.0, 1.0 - radius * radius / dist2));
    }
    let sin_b = sin_from_cos(cos_b);
    let cos_o = node.cos_theta_o;
    let sin_o = sin_from_cos(cos_o);
    let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o);
    let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
    let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if cos_p <= node.cos_theta_e {
        return 0.0;
    }
    var importance = node.phi * cos_p / d2;
    if any(n != vec3<f32>(0.0)) {
        // Either side of the surface: glass receives from behind.
        let cos_i = abs(dot(wi, n));
        importance *= cos_sub_clamped(sin_from_cos(cos_i), cos_i, sin_b, cos_b);
    }
    return max(importance, 0.0);
}

// The probabilities of the two children of an interior node: ∝ importance or, where both
// are 0 (the parent's looser bounds let the walk this far), ∝ power, so every walk ends
// at a light and the PDF sums to one. (0, 0): neither has power.
fn light_bvh_branch(first: u32, second: u32, p: vec3<f32>, n: vec3<f32>, radius: f32, orientation: bool) -> vec2<f32> {
    let a = light_bvh_nodes[first];
    let b = light_bvh_nodes[second];
    var w = vec2<f32>(light_bvh_importance(a, p, n, radius, orientation), light_bvh_importance(b, p, n, radius, orientation));
    var total = w.x + w.y;
    if !(total > 0.0) || !is_finite_f32(total) {
        w = vec2<f32>(a.phi, b.phi);
        total = w.x + w.y;
        if !(total > 0.0) {
            return vec2<f32>(0.0);
        }
    }
    return w / total;
}

struct LightBvhSample {
    light: u32,   // NO_LIGHT: the tree has no light with power
    pdf: f32,     // the probability of this light among the lights with a position
}

// Walks down from the root with the number u in [0, 1), rescaled at each branch; `radius`:
// as in light_bvh_importance (0 at a shading point).
fn light_bvh_sample(p: vec3<f32>, n: vec3<f32>, radius: f32, u_in: f32) -> LightBvhSample {
    var index = 0u;
    var u = u_in;
    var pdf = 1.0;
    for (var depth = 0u; depth <= 64u; depth++) {
        let node = light_bvh_nodes[index];
        if (node.child_or_light & LIGHT_BVH_LEAF) != 0u {
            return LightBvhSample(node.child_or_light & ~LIGHT_BVH_LEAF, pdf);
        }
        let prob = light_bvh_branch(index + 1u, node.child_or_light, p, n, radius, true);
        if !(prob.x + prob.y > 0.0) {
            break;
        }
        if u < prob.x {
            u = min(u / prob.x, ONE_MINUS_EPSILON);
            pdf *= prob.x;
            index = index + 1u;
        } else {
            u = min((u - prob.x) / prob.y, ONE_MINUS_EPSILON);
            pdf *= prob.y;
            index = node.child_or_light;
        }
    }
    return LightBvhSample(NO_LIGHT, 0.0);
}

// The probability that light_bvh_sample draws `light` at p: the product of the branch
// probabilities along its trail (0 for a light outside the tree). The planted twin
// PLANTED_BVH_PDF_WITHOUT_ORIENTATION evaluates it without the angle terms the walk uses.
fn light_bvh_pdf(light: u32, p: vec3<f32>, n: vec3<f32>) -> f32 {
#ifdef PLANTED_BVH_PDF_WITHOUT_ORIENTATION
    let orientation = false;
#else
    let orientation = true;
#endif
    let trail = light_bvh_trails[light];
    if trail.depth == LIGHT_BVH_NOT_IN_TREE {
        return 0.0;
    }
    var index = 0u;
    var pdf = 1.0;
    for (var k = 0u; k < min(trail.depth, 64u); k++) {
        let node = light_bvh_nodes[index];
        let prob = light_bvh_branch(index + 1u, node.child_or_light, p, n, 0.0, orientation);
        let word = select(trail.bits.y, trail.bits.x, k < 32u);
        let second = ((word >> (k & 31u)) & 1u) == 1u;
        pdf *= select(prob.x, prob.y, second);
        index = select(index + 1u, node.child_or_light, second);
    }
    return pdf;
}
