// G-buffer, step 2: turn the visibility buffer into per-pixel surfaces: position, normals,
// material id and parameters, emission toward the camera and the motion vector.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/material.wgsl"

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
    if vis.x == 0u {
        surfaces[index] = s;
        return;
    }
    let hs = hit_surface(vis.x - 1u, bitcast<f32>(vis.y), bitcast<f32>(vis.z), frame.camera_position);
    let m = eval_material(hs.material, hs.uv);
    s.position = hs.position;
    s.depth = length(hs.position - frame.camera_position);
    s.normal = oct_encode(hs.normal);
    s.geo_normal = oct_encode(hs.geo_normal);
    s.material = hs.material;
    s.base_color_metallic = pack4x8unorm(vec4<f32>(m.base_color, m.metallic));
    s.roughness = m.roughness;
    s.specular = m.specular;
    s.emission = emission_toward_viewer(hs);
#ifdef MOTION
    var prev_position = hs.position;
#ifdef ANIMATION
    // The same triangle and barycentrics on last frame's geometry: a moving object's
    // surface reprojects to where it was, not to whatever was behind it.
    let pt = prev_triangles[vis.x - 1u];
    let bu = bitcast<f32>(vis.y);
    let bv = bitcast<f32>(vis.z);
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
        s = Surface();
        s.motion = vec2<f32>(NO_MOTION);
    }
    surfaces[index] = s;
}
