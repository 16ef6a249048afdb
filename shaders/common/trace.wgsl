// The tracing interface every pass calls: closest hit, any hit, and the transmittance of a
// shadow ray through transparent layers, against this frame's geometry or last frame's
// (`_in`). Two implementations behind it, chosen when the pipeline is compiled
// (render/src/tracing.rs): the software BVH (trace_bvh.wgsl, the default everywhere) and
// hardware ray queries (trace_ray_query.wgsl, under RAY_QUERY). Both find candidate hits
// their own way and hand every one to the same rules here (hit_is_accepted, take_hit), so
// they agree on what a ray sees; only ties between equally near hits may go either way.
#include "common/scene_bindings.wgsl"
#include "common/ray.wgsl"
#include "common/material.wgsl"

struct Hit {
    t: f32,        // < 0 when nothing was hit
    triangle: u32,
    u: f32,
    v: f32,
}

fn no_hit() -> Hit {
    return Hit(-1.0, 0u, 0.0, 0.0);
}

const TRACE_CLOSEST: u32 = 0u;
const TRACE_ANY: u32 = 1u;
// Every hit in (0, t_max), in no particular order: the product of layer transmittances is
// the same in any order, so a shadow ray through glass needs no sorting and no restart.
const TRACE_TRANSMITTANCE: u32 = 2u;

// Which frame's geometry a ray is traced against. Last frame's exists only for animated
// scenes (scene_bindings.wgsl); a static scene's previous geometry is its current one.
const GEOMETRY_CURRENT: u32 = 0u;
const GEOMETRY_PREVIOUS: u32 = 1u;

// What a TRACE_TRANSMITTANCE ray collects: the product of pass_through of every
// transparent layer on the segment (0 at an opaque hit or past MAX_TRANSPARENT_LAYERS), and
// whether one of those layers emits (a BSDF ray would have stopped there: see
// light_sample_mis).
struct Transmittance {
    value: vec3<f32>,
    crossed_emitter: bool,
}

// Triangle `index` as it is (GEOMETRY_CURRENT) or was last frame (same slot).
fn geometry_triangle(index: u32, geometry: u32) -> Triangle {
#ifdef ANIMATION
    if geometry == GEOMETRY_PREVIOUS {
        return prev_triangles[index];
    }
#endif
    return triangles[index];
}

// Whether a hit on this triangle counts. Camera rays skip back faces of single-sided
// materials (glTF back-face culling, the same rule as the rasterised G-buffer); alpha-masked
// texels below the cutoff are holes for every ray.
fn hit_is_accepted(tri_index: u32, tri: Triangle, u: f32, v: f32, ray: Ray, cull_single_sided_back: bool) -> bool {
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

// A trace in progress: the hit to report and, for TRACE_CLOSEST, how far a nearer one may be.
struct TraceState {
    best: Hit,
    t_max: f32,
    layers: u32,
}

fn trace_state(ray: Ray) -> TraceState {
    return TraceState(no_hit(), ray.t_max, 0u);
}

// What a backend does after take_hit.
const HIT_GO_ON: u32 = 0u;   // a layer was crossed: look for more hits as before
const HIT_CLOSER: u32 = 1u;  // the nearest hit so far (TRACE_CLOSEST): keep it, look nearer
const HIT_STOP: u32 = 2u;    // the answer is known: stop the traversal

// The one rule for an accepted hit (t, u, v) = h on triangle `tri_index`, whichever backend
// found it. TRACE_ANY stops at it; TRACE_CLOSEST keeps it and shrinks t_max;
// TRACE_TRANSMITTANCE (transparency.wgsl's model) multiplies its layer's pass_through and
// goes on, stopping once nothing gets through or past MAX_TRANSPARENT_LAYERS.
fn take_hit(state: ptr<function, TraceState>, mode: u32, tri_index: u32, h: vec3<f32>, dir: vec3<f32>, transmittance: ptr<function, Transmittance>) -> u32 {
    (*state).best = Hit(h.x, tri_index, h.y, h.z);
#ifdef TRANSPARENCY
    if mode == TRACE_TRANSMITTANCE {
        let layer = triangle_layer(tri_index, h.y, h.z, dir);
        (*state).layers++;
        (*transmittance).value *= layer.pass_through;
        (*transmittance).crossed_emitter = (*transmittance).crossed_emitter || triangles[tri_index].light != NO_LIGHT;
        if (*state).layers > MAX_TRANSPARENT_LAYERS || !any((*transmittance).value > vec3<f32>(0.0)) {
            (*transmittance).value = vec3<f32>(0.0);
            return HIT_STOP;
        }
        return HIT_GO_ON;
    }
#endif
    if mode != TRACE_CLOSEST {
        (*transmittance).value = vec3<f32>(0.0);
        return HIT_STOP;
    }
    (*state).t_max = h.x;
    return HIT_CLOSER;
}

#ifdef RAY_QUERY
#include "common/trace_ray_query.wgsl"
#else
#include "common/trace_bvh.wgsl"
#endif

fn trace_closest(ray: Ray, cull_single_sided_back: bool) -> Hit {
    var unused = Transmittance(vec3<f32>(1.0), false);
    return trace(ray, TRACE_CLOSEST, cull_single_sided_back, GEOMETRY_CURRENT, &unused);
}

// Any hit in (0, t_max), transparent layers included (rays that must find a surface, not
// light: none at present outside trace_transmittance's opaque test).
fn trace_any(ray: Ray) -> bool {
    var unused = Transmittance(vec3<f32>(1.0), false);
    return trace(ray, TRACE_ANY, false, GEOMETRY_CURRENT, &unused).t > 0.0;
}

// How much light gets along the segment, against `geometry`'s frame: 1 or 0 in an opaque
// scene, the product of the layers' pass_through with transparency (shadow rays,
// visibility in the MIS terms). Last frame's layers are tinted and angled as this frame's
// (the previous frame keeps triangles, not shading records).
fn trace_transmittance_in(ray: Ray, geometry: u32) -> Transmittance {
    var tr = Transmittance(vec3<f32>(1.0), false);
#ifdef TRANSPARENCY
    _ = trace(ray, TRACE_TRANSMITTANCE, false, geometry, &tr);
#else
    if trace(ray, TRACE_ANY, false, geometry, &tr).t > 0.0 {
        tr.value = vec3<f32>(0.0);
    }
#endif
    return tr;
}

fn trace_transmittance(ray: Ray) -> Transmittance {
    return trace_transmittance_in(ray, GEOMETRY_CURRENT);
}
