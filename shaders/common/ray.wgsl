// Ray origins that do not self-intersect at any scene scale.
#include "common/frame_bindings.wgsl"

// Offsets p along the normal n by a few float ULPs of p's own coordinates (Wächter and
// Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems
// ch. 6). Near the origin, where ULPs vanish, it falls back to an epsilon relative to the
// scene size, so a 1e-3 and a 1e4 scene both work (no fixed 1e-3 offset).
fn offset_ray_origin(p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let int_scale = 256.0;
    let origin_band = frame.scene_scale * (1.0 / 1024.0);
    let float_scale = frame.scene_scale * 1e-5;
    let of_i = vec3<i32>(int_scale * n);
    let p_i = vec3<f32>(
        bitcast<f32>(bitcast<i32>(p.x) + select(of_i.x, -of_i.x, p.x < 0.0)),
        bitcast<f32>(bitcast<i32>(p.y) + select(of_i.y, -of_i.y, p.y < 0.0)),
        bitcast<f32>(bitcast<i32>(p.z) + select(of_i.z, -of_i.z, p.z < 0.0)),
    );
    return select(p_i, p + float_scale * n, abs(p) < vec3<f32>(origin_band));
}

struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,   // not necessarily unit length: t is in units of |dir|
    t_max: f32,
}

// A segment between two surface points, each pushed off its own surface; t in (0, 1).
fn segment_ray(from_p: vec3<f32>, from_n: vec3<f32>, to_p: vec3<f32>, to_n: vec3<f32>) -> Ray {
    let o = offset_ray_origin(from_p, from_n);
    let e = offset_ray_origin(to_p, to_n);
    return Ray(o, e - o, 1.0);
}
