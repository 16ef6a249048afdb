// BVH traversal for shadow rays (any hit), BSDF rays and reference camera rays (closest
// hit). The tree is built on the CPU (render/src/scene/bvh.rs), binned SAH, depth ≤ 48.
#include "common/scene_bindings.wgsl"
#include "common/ray.wgsl"
#include "common/material.wgsl"

const BVH_STACK_SIZE: u32 = 64u;

struct Hit {
    t: f32,        // < 0 when nothing was hit
    triangle: u32,
    u: f32,
    v: f32,
}

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

// Whether a hit on this triangle counts. Camera rays skip back faces of single-sided
// materials (glTF back-face culling, the same rule as the rasterised G-buffer).
fn hit_is_accepted(tri_index: u32, u: f32, v: f32, ray: Ray, cull_single_sided_back: bool) -> bool {
    let tri = triangles[tri_index];
    let material = materials[tri.material];
    if cull_single_sided_back && (material.flags & MATERIAL_DOUBLE_SIDED) == 0u {
        let ng = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
        if dot(ng, ray.dir) > 0.0 {
            return false;
        }
    }
#ifdef ALPHA_MASK
    if (material.flags & MATERIAL_ALPHA_MASK) != 0u {
        let uv = triangle_uv(tri_index, u, v);
        if material_alpha(tri.material, uv) < material.alpha_cutoff {
            return false;
        }
    }
#endif
    return true;
}

const TRACE_CLOSEST: u32 = 0u;
const TRACE_ANY: u32 = 1u;
// Every hit in (0, t_max), in no particular order: the product of layer transmittances is
// the same in any order, so a shadow ray through glass needs no sorting and no restart.
const TRACE_TRANSMITTANCE: u32 = 2u;

// What a TRACE_TRANSMITTANCE ray collects: the product of pass_through of every
// transparent layer on the segment (0 at an opaque hit or past MAX_TRANSPARENT_LAYERS), and
// whether one of those layers emits (a BSDF ray would have stopped there: see
// light_sample_mis).
struct Transmittance {
    value: vec3<f32>,
    crossed_emitter: bool,
}

// The one traversal loop. TRACE_ANY returns at the first accepted hit (shadow rays);
// TRACE_CLOSEST shrinks t_max to the nearest hit and visits the nearer child first;
// TRACE_TRANSMITTANCE (transparency.wgsl's model) goes through transparent layers.
fn trace(ray: Ray, mode: u32, cull_single_sided_back: bool, transmittance: ptr<function, Transmittance>) -> Hit {
    var best = Hit(-1.0, 0u, 0.0, 0.0);
    var layers = 0u;
    var t_max = ray.t_max;
    let inv_dir = safe_inverse_dir(ray.dir);
    var stack: array<u32, BVH_STACK_SIZE>;
    var sp = 0u;
    var node_index = 0u;
    loop {
        let node = bvh_nodes[node_index];
        if node.count > 0u {
            for (var i = 0u; i < node.count; i++) {
                let tri_index = node.first + i;
                let h = intersect_triangle(Ray(ray.origin, ray.dir, t_max), triangles[tri_index]);
                if h.x > 0.0 && h.x < t_max && hit_is_accepted(tri_index, h.y, h.z, ray, cull_single_sided_back) {
                    best = Hit(h.x, tri_index, h.y, h.z);
#ifdef TRANSPARENCY
                    if mode == TRACE_TRANSMITTANCE {
                        let layer = triangle_layer(tri_index, h.y, h.z, ray.dir);
                        layers++;
                        (*transmittance).value *= layer.pass_through;
                        (*transmittance).crossed_emitter = (*transmittance).crossed_emitter || triangles[tri_index].light != NO_LIGHT;
                        if layers > MAX_TRANSPARENT_LAYERS || !any((*transmittance).value > vec3<f32>(0.0)) {
                            (*transmittance).value = vec3<f32>(0.0);
                            return best;
                        }
                        continue;
                    }
#endif
                    if mode != TRACE_CLOSEST {
                        (*transmittance).value = vec3<f32>(0.0);
                        return best;
                    }
                    t_max = h.x;
                }
            }
        } else {
            let a = node.first;
            let b = node.first + 1u;
            let na = bvh_nodes[a];
            let nb = bvh_nodes[b];
            let ta = intersect_aabb(ray.origin, inv_dir, na.min, na.max, t_max);
            let tb = intersect_aabb(ray.origin, inv_dir, nb.min, nb.max, t_max);
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
    return best;
}

fn trace_closest(ray: Ray, cull_single_sided_back: bool) -> Hit {
    var unused = Transmittance(vec3<f32>(1.0), false);
    return trace(ray, TRACE_CLOSEST, cull_single_sided_back, &unused);
}

// Any hit in (0, t_max), transparent layers included (rays that must find a surface, not
// light: none at present outside trace_transmittance's opaque test).
fn trace_any(ray: Ray) -> bool {
    var unused = Transmittance(vec3<f32>(1.0), false);
    return trace(ray, TRACE_ANY, false, &unused).t > 0.0;
}

// How much light gets along the segment: 1 or 0 in an opaque scene, the product of the
// layers' pass_through with transparency (shadow rays, visibility in the MIS terms).
fn trace_transmittance(ray: Ray) -> Transmittance {
    var tr = Transmittance(vec3<f32>(1.0), false);
#ifdef TRANSPARENCY
    _ = trace(ray, TRACE_TRANSMITTANCE, false, &tr);
#else
    if trace(ray, TRACE_ANY, false, &tr).t > 0.0 {
        tr.value = vec3<f32>(0.0);
    }
#endif
    return tr;
}
