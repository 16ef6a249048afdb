// G-buffer, step 1: rasterise a visibility buffer (triangle id + barycentrics).
// Vertices are pulled from the same BVH-ordered triangle buffer the rays use, so the
// raster and ray-traced paths agree on every triangle id.
#include "common/frame_bindings.wgsl"
#include "common/scene_bindings.wgsl"
#include "common/material.wgsl"

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) bary: vec2<f32>,
    @location(1) @interpolate(flat) triangle: u32,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut {
    let tri_index = vertex_index / 3u;
    let corner = vertex_index % 3u;
    let tri = triangles[tri_index];
    var p = tri.p0;
    var bary = vec2<f32>(0.0, 0.0);
    if corner == 1u {
        p = tri.p1;
        bary = vec2<f32>(1.0, 0.0);
    } else if corner == 2u {
        p = tri.p2;
        bary = vec2<f32>(0.0, 1.0);
    }
    var clip = frame.view_proj * vec4<f32>(p, 1.0);
    // Sub-pixel jitter (pixels → NDC; NDC y points up, pixel y down).
    let jitter_ndc = vec2<f32>(2.0 * frame.jitter.x / f32(frame.size.x), -2.0 * frame.jitter.y / f32(frame.size.y));
    clip = vec4<f32>(clip.xy + jitter_ndc * clip.w, clip.zw);
    return VertexOut(clip, bary, tri_index);
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> @location(0) vec4<u32> {
    let tri = triangles[in.triangle];
    let material = materials[tri.material];
    // glTF back-face culling of single-sided materials (the reference's camera rays
    // apply the same rule in trace.wgsl).
    if !front && (material.flags & MATERIAL_DOUBLE_SIDED) == 0u {
        discard;
    }
#ifdef ALPHA_MASK
    if (material.flags & MATERIAL_ALPHA_MASK) != 0u {
        let uv = triangle_uv(in.triangle, in.bary.x, in.bary.y);
        if material_alpha(tri.material, uv) < material.alpha_cutoff {
            discard;
        }
    }
#endif
    return vec4<u32>(in.triangle + 1u, bitcast<u32>(in.bary.x), bitcast<u32>(in.bary.y), 0u);
}
