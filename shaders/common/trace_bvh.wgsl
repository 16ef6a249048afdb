// The software backend of trace.wgsl: the binned-SAH BVH built on the CPU
// (render/src/scene/bvh.rs, depth ≤ 48), walked by a stack loop (the same loop as
// render/src/scene/bvh/traverse.rs). Last frame's geometry is the same tree with last
// frame's boxes (`prev_bvh_nodes`, render/src/gpu_scene/update.rs) over last frame's
// triangles.

const BVH_STACK_SIZE: u32 = 64u;

// Möller–Trumbore, both faces. Returns (t, u, v); t < 0 on a miss.
fn intersect_triangle(ray: Ray, tri: Triangle) -> vec3<f32> {
    let e1 = tri.p1 - tri.p0;
    let e2 = tri.p2 - tri.p0;
    let pv = cross(ray.dir, e2);
    let det = dot(e1, pv);
    if det == 0.0 || !is_finite_f32(det) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    let inv_det = 1.0 / det;
    let tv = ray.origin - tri.p0;
    let u = dot(tv, pv) * inv_det;
    let qv = cross(tv, e1);
    let v = dot(ray.dir, qv) * inv_det;
    let t = dot(e2, qv) * inv_det;
    if u < 0.0 || v < 0.0 || u + v > 1.0 || !(t > 0.0) {
        return vec3<f32>(-1.0, 0.0, 0.0);
    }
    return vec3<f32>(t, u, v);
}

// Slab test; returns the entry distance or a negative value on a miss.
fn intersect_aabb(origin: vec3<f32>, inv_dir: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>, t_max: f32) -> f32 {
    let t0 = (lo - origin) * inv_dir;
    let t1 = (hi - origin) * inv_dir;
    let t_near = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    let t_far = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), t_max));
    return select(-1.0, t_near, t_near <= t_far);
}

// 1/dir without division by zero (WGSL leaves x/0 undefined).
fn safe_inverse_dir(d: vec3<f32>) -> vec3<f32> {
    let tiny = vec3<f32>(1e-30);
    let s = select(vec3<f32>(-1.0), vec3<f32>(1.0), d >= vec3<f32>(0.0));
    return 1.0 / select(d, s * tiny, abs(d) < tiny);
}

// Node `index` of this frame's tree or of last frame's (same topology, last frame's boxes).
fn geometry_node(index: u32, geometry: u32) -> BvhNode {
#ifdef ANIMATION
    if geometry == GEOMETRY_PREVIOUS {
        return prev_bvh_nodes[index];
    }
#endif
    return bvh_nodes[index];
}

// The traversal: every triangle of a reached leaf that the ray hits nearer than t_max and
// that hit_is_accepted takes goes to take_hit (trace.wgsl), which says whether to go on.
// TRACE_CLOSEST visits the nearer child first.
fn trace(ray: Ray, mode: u32, cull_single_sided_back: bool, geometry: u32, transmittance: ptr<function, Transmittance>) -> Hit {
    var state = trace_state(ray);
    let inv_dir = safe_inverse_dir(ray.dir);
#ifdef PLANTED_BVH_LAST_HIT_NOT_NEAREST
    // Test only (render/tests/ray_backends.rs): hits are not limited to nearer than the
    // best so far, so a closest-hit ray reports the last one the traversal meets.
    let limit = ray.t_max;
#endif
    var stack: array<u32, BVH_STACK_SIZE>;
    var sp = 0u;
    var node_index = 0u;
    loop {
        let node = geometry_node(node_index, geometry);
        if node.count > 0u {
            for (var i = 0u; i < node.count; i++) {
                let tri_index = node.first + i;
                let tri = geometry_triangle(tri_index, geometry);
#ifndef PLANTED_BVH_LAST_HIT_NOT_NEAREST
                let limit = state.t_max;
#endif
                let h = intersect_triangle(Ray(ray.origin, ray.dir, limit), tri);
                if h.x > 0.0 && h.x < limit && hit_is_accepted(tri_index, tri, h.y, h.z, ray, cull_single_sided_back) {
                    if take_hit(&state, mode, tri_index, h, ray.dir, transmittance) == HIT_STOP {
                        return state.best;
                    }
                }
            }
        } else {
            let a = node.first;
            let b = node.first + 1u;
            let na = geometry_node(a, geometry);
            let nb = geometry_node(b, geometry);
            let ta = intersect_aabb(ray.origin, inv_dir, na.min, na.max, state.t_max);
            let tb = intersect_aabb(ray.origin, inv_dir, nb.min, nb.max, state.t_max);
            if ta >= 0.0 && tb >= 0.0 {
                let a_first = ta <= tb;
                if sp < BVH_STACK_SIZE {
                    stack[sp] = select(a, b, a_first);
                    sp++;
                }
                node_index = select(b, a, a_first);
                continue;
            } else if ta >= 0.0 {
                node_index = a;
                continue;
            } else if tb >= 0.0 {
                node_index = b;
                continue;
            }
        }
        if sp == 0u {
            break;
        }
        sp--;
        node_index = stack[sp];
    }
    return state.best;
}
