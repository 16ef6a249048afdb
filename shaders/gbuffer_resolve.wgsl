// G-buffer, step 2: turn the visibility buffer into per-pixel surfaces: position, normals,
// material id and parameters, emission toward the camera and the motion vector.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/material.wgsl"
#ifdef TRANSPARENCY
#include "common/layer_walk.wgsl"
#include "common/camera_ray.wgsl"
#endif

@group(2) @binding(0) var visibility: texture_2d<u32>;
@group(2) @binding(1) var<storage, read_write> surfaces: array<Surface>;
// The light BVH, for the vertex sampler (common/vertex_light.wgsl); one-element
// placeholders unless VERTEX_LIGHT_BVH is compiled.
@group(2) @binding(2) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(3) var<storage, read> light_bvh_trails: array<LightBvhTrail>;
// Last frame's triangles (where this surface point was: object motion) are the scene
// group's `prev_triangles` (scene_bindings.wgsl).

fn clamp_barycentrics(uv: vec2<f32>) -> vec2<f32> {
#ifdef PLANTED_UNCLAMPED_BARYCENTRICS
    return uv;  // test only: as rasterised (before)
#endif
    let c = max(uv, vec2<f32>(0.0));
    return c / max(c.x + c.y, 1.0);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let vis = textureLoad(visibility, vec2<i32>(id.xy), 0);
    var s: Surface;
    s.motion = vec2<f32>(NO_MOTION);
    s.throughput = vec3<f32>(1.0);
    if vis.x == 0u {
        surfaces[index] = s;
        return;
    }
    var tri = vis.x - 1u;
    // The rasteriser snaps edges to its sub-pixel grid, so a pixel centre just outside a
    // triangle can land on it with barycentrics slightly outside [0, 1]: the point lies past
    // the edge, at a concave corner behind the other wall, where every shadow ray is blocked
    // (a black pixel). Clamped onto the triangle.
    let raster_uv = clamp_barycentrics(vec2<f32>(bitcast<f32>(vis.y), bitcast<f32>(vis.z)));
    var bu = raster_uv.x;
    var bv = raster_uv.y;
    var in_front = vec3<f32>(0.0);
#ifdef TRANSPARENCY
    // Glass and partial coverage (layer_walk.wgsl): the camera ray goes on from the
    // rasterised layer to the primary surface without a random choice (a still view keeps
    // its surfaces); the layers passed tint it and add their own light, estimated once.
    if is_transparent_triangle(tri) {
        s.transparent_first = 1u;
        let dir = camera_ray_direction(vec2<f32>(id.xy) + 0.5 - frame.jitter);
        var rng = rng_seed(id.xy, STREAM_TRANSPARENCY);
        let walk = walk_to_primary(frame.camera_position, dir, Hit(1.0, tri, bu, bv), &rng);
        s.throughput = walk.weight;
        in_front = walk.in_front;
        add_stat(STAT_SHADOW_RAYS + PASS_GBUFFER, walk.shadow_rays);
        if walk.hit.t < 0.0 {
            // Nothing behind the glass: the background, tinted (di/shade.wgsl).
            s.emission = in_front;
            surfaces[index] = s;
            return;
        }
        tri = walk.hit.triangle;
        bu = walk.hit.u;
        bv = walk.hit.v;
    }
#endif
    let hs = hit_surface(tri, bu, bv, frame.camera_position);
    let m = eval_material(hs.material, hs.uv);
    s.position = hs.position;
    s.depth = length(hs.position - frame.camera_position);
    s.normal = oct_encode(hs.normal);
    s.geo_normal = oct_encode(hs.geo_normal);
    s.material = hs.material;
    s.base_color_metallic = pack4x8unorm(vec4<f32>(m.base_color, m.metallic));
    s.roughness = m.roughness;
    s.specular = m.specular;
    var own_emission = s.throughput * emission_toward_viewer(hs);
#ifdef TRANSPARENCY
    // A transparent primary layer's emission is in in_front already (walk_to_primary).
    if is_transparent_triangle(tri) {
        own_emission = vec3<f32>(0.0);
    }
#endif
    s.emission = in_front + own_emission;
#ifdef MOTION
    var prev_position = hs.position;
#ifdef ANIMATION
    // The same triangle and barycentrics on last frame's geometry: a moving object's
    // surface reprojects to where it was, not to whatever was behind it.
    let pt = prev_triangles[tri];
    prev_position = pt.p0 * (1.0 - bu - bv) + pt.p1 * bu + pt.p2 * bv;
#endif
    let prev_clip = frame.prev_view_proj * vec4<f32>(prev_position, 1.0);
    if prev_clip.w > 0.0 {
        let ndc = prev_clip.xy / prev_clip.w;
        let unjittered = vec2<f32>((ndc.x * 0.5 + 0.5) * f32(frame.size.x), (0.5 - ndc.y * 0.5) * f32(frame.size.y));
        // The previous frame's pixel p sampled the point projecting to p + 0.5 - jitter.
        s.motion = unjittered + frame.prev_jitter;
    }
#else
    // Static camera and scene: every point stays where it is (docs/src/specialisation.md).
    s.motion = vec2<f32>(id.xy) + 0.5;
#endif
    if !is_finite_vec3(s.position) || !is_finite_f32(s.depth) || !is_finite_vec3(s.emission) {
        count_stat(STAT_NONFINITE + PASS_GBUFFER);
        s = Surface();  // throughput 0: black, not the background
        s.motion = vec2<f32>(NO_MOTION);
    }
    surfaces[index] = s;
}
