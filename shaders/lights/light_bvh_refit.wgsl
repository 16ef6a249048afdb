// The light BVH refitted on the GPU (docs/src/light-samplers.md, "Moving lights"). The CPU
// marks the nodes above the lights that moved or changed power and lists them level by
// level (render/src/light_sampler/gpu_refit.rs); this runs once per level, the changed
// leaves first, then the interior nodes from the deepest up, so that every node reads
// children already refitted. A node keeps its bounds in full precision in `bounds` (what
// the next union reads) and rewrites its record, the quantised node the walk reads
// (light_bvh.wgsl), as light_sampler.rs's `node_record` does on the CPU.

#include "common/types.wgsl"
#include "common/math.wgsl"

@group(0) @binding(0) var<storage, read_write> nodes: array<LightBvhNode>;
@group(0) @binding(1) var<storage, read_write> bounds: array<LightBounds>;
@group(0) @binding(2) var<storage, read> work: array<u32>;
@group(0) @binding(3) var<storage, read> leaf_bounds: array<LightBounds>;
@group(0) @binding(4) var<uniform> level: RefitLevel;

// A unit vector perpendicular to unit w, as light_bvh.rs's.
fn perpendicular(w: vec3<f32>) -> vec3<f32> {
    let e = select(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, 0.0), abs(w.z) > 0.9);
    return normalize(cross(w, e));
}

fn entire_sphere(b: LightBounds) -> LightBounds {
    var out = b;
    out.w = vec3<f32>(0.0, 0.0, 1.0);
    out.cos_theta_o = -1.0;
    return out;
}

// The smallest cone around both normals' cones (pbrt-v4's Union(DirectionCone,
// DirectionCone), as light_bvh.rs's DirectionCone::union), written into `out`.
fn cone_union(out: LightBounds, a: LightBounds, b: LightBounds) -> LightBounds {
    // A cone of every direction holds the other. Said outright: the GPU's acos(-1) may fall
    // a rounding short of PI, which would fail the first test below.
    if a.cos_theta_o <= -1.0 || b.cos_theta_o <= -1.0 {
        return entire_sphere(out);
    }
    let theta_a = acos(clamp(a.cos_theta_o, -1.0, 1.0));
    let theta_b = acos(clamp(b.cos_theta_o, -1.0, 1.0));
    // From its sine and cosine, as light_bvh.rs (acos of a dot near 1 is ill-conditioned).
    let theta_d = atan2(length(cross(a.w, b.w)), dot(a.w, b.w));
    var r = out;
    if min(theta_d + theta_b, PI) <= theta_a {
        r.w = a.w;
        r.cos_theta_o = a.cos_theta_o;
        return r;
    }
    if min(theta_d + theta_a, PI) <= theta_b {
        r.w = b.w;
        r.cos_theta_o = b.cos_theta_o;
        return r;
    }
    // About the cross product; axes nearly opposite: about a fixed perpendicular, with θ_d
    // taken as π (light_bvh.rs says why).
    var k: vec3<f32>;
    var theta_o: f32;
    if theta_d < PI - LIGHT_BVH_NEARLY_OPPOSITE {
        k = safe_normalize(cross(a.w, b.w), perpendicular(a.w));
        theta_o = (theta_a + theta_d + theta_b) / 2.0;
    } else {
        k = perpendicular(a.w);
        theta_o = (theta_a + PI + theta_b) / 2.0;
    }
    if theta_o >= PI {
        return entire_sphere(r);
    }
    // a.w rotated about k by theta_o − theta_a (Rodrigues' formula).
    let angle = theta_o - theta_a;
    let c = cos(angle);
    let s = sin(angle);
    let w = a.w * c + cross(k, a.w) * s + k * dot(k, a.w) * (1.0 - c);
    r.w = normalize(w);
    r.cos_theta_o = cos(theta_o);
    return r;
}

// light_bvh.rs's LightBounds::union: a child without power adds nothing.
fn bounds_union(a: LightBounds, b: LightBounds) -> LightBounds {
    if a.phi <= 0.0 {
        return b;
    }
    if b.phi <= 0.0 {
        return a;
    }
    var out: LightBounds;
    out.min = min(a.min, b.min);
    out.max = max(a.max, b.max);
    out.phi = a.phi + b.phi;
    out.cos_theta_e = min(a.cos_theta_e, b.cos_theta_e);
    return cone_union(out, a, b);
}

@compute @workgroup_size(LIGHT_BVH_REFIT_WORKGROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= level.count {
        return;
    }
    let index = work[level.first + id.x];
    var b: LightBounds;
    if level.leaves != 0u {
        b = leaf_bounds[id.x];
    } else {
        // The first child follows its parent; child_or_light holds the second.
        b = bounds_union(bounds[index + 1u], bounds[nodes[index].child_or_light]);
    }
    bounds[index] = b;
    var record = nodes[index];
    record.min = b.min;
    record.max = b.max;
    record.phi = b.phi;
    record.axis = oct_encode(safe_normalize(b.w, vec3<f32>(0.0, 0.0, 1.0)));
    if b.cos_theta_o <= -1.0 {
        record.cos_theta_o = -1.0;
    } else {
        record.cos_theta_o = cos(min(acos(clamp(b.cos_theta_o, -1.0, 1.0)) + LIGHT_BVH_CONE_SLACK, PI));
    }
    record.cos_theta_e = b.cos_theta_e;
    nodes[index] = record;
}
