// The camera ray through a point of the image (pixel units, top-left origin).
#include "common/frame_bindings.wgsl"

fn camera_ray_direction(pixel: vec2<f32>) -> vec3<f32> {
    let ndc = vec2<f32>(pixel.x / f32(frame.size.x) * 2.0 - 1.0, 1.0 - pixel.y / f32(frame.size.y) * 2.0);
    // With the infinite reverse-Z projection, NDC depth 0 is the point at infinity: the
    // inverse maps it to (direction, 0). Subtracting the camera position from a near-plane
    // point instead would cancel catastrophically (the near plane is 1e-5 scene units away).
    let far = frame.inv_view_proj * vec4<f32>(ndc, 0.0, 1.0);
    return normalize(far.xyz);
}
