// G-buffer, step 2: turn the visibility buffer into per-pixel surfaces: position, normals,
// material id and parameters, emission toward the camera and the motion vector.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/material.wgsl"
#ifdef TRANSPARENCY
#include "common/transparency.wgsl"
#include "common/camera_ray.wgsl"
#endif

@group(2) @binding(0) var visibility: texture_2d<u32>;
@group(2) @binding(1) var<storage, read_write> surfaces: array<Surface>;
// Last frame's triangles (where this surface point was: object motion) are the scene
// group's `prev_triangles` (scene_bindings.wgsl). Group 2 binding 2 of this pass's layout
// holds the same buffer and is no longer read.

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
    var bu = bitcast<f32>(vis.y);
    var bv = bitcast<f32>(vis.z);
    var emission_in_front = vec3<f32>(0.0);
#ifdef TRANSPARENCY
    // Glass and partial coverage (transparency.wgsl): the camera ray goes on from the
    // rasterised layer; the surface is where it stops, the layers passed tint it. Only
    // partial coverage draws a random choice, so clear glass is as stable as a wall.
    if is_transparent_triangle(tri) {
        s.transparent_first = 1u;
        let dir = camera_ray_direction(vec2<f32>(id.xy) + 0.5 - frame.jitter);
        var rng = rng_seed(id.xy, STREAM_TRANSPARENCY);
        let walk = walk_layers(frame.camera_position, dir, Hit(1.0, tri, bu, bv), true, &rng);
        s.throughput = walk.weight;
        emission_in_front = walk.emission;
        if walk.hit.t < 0.0 {
            // Nothing behind the glass: the background, tinted (shade.wgsl).
            s.emission = emission_in_front;
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
    s.emission = emission_in_front + s.throughput * emission_toward_viewer(hs);
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
    // Static camera and scene: every point stays where it is (issue "specialisation").
    s.motion = vec2<f32>(id.xy) + 0.5;
#endif
    if !is_finite_vec3(s.position) || !is_finite_f32(s.depth) || !is_finite_vec3(s.emission) {
        count_stat(STAT_NONFINITE + PASS_GBUFFER);
        s = Surface();  // throughput 0: black, not the background
        s.motion = vec2<f32>(NO_MOTION);
    }
    surfaces[index] = s;
}
