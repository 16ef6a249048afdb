// What the denoiser's passes share (docs/src/denoiser.md): demodulation, the reprojected
// history's validation and the edge-stopping weights. render/src/denoise/model.rs is the
// same computation in plain Rust, checked against these passes' output.
#include "common/camera_ray.wgsl"
#include "common/math.wgsl"

fn denoise_has_surface(s: Surface) -> bool {
    return s.depth > 0.0;
}

// What the lighting is divided by before filtering and multiplied by after: the surface
// colour and the weight of the glass in front, so the filter sees illumination alone and
// texture detail survives it.
fn denoise_demodulation(s: Surface) -> vec3<f32> {
    return max(unpack4x8unorm(s.base_color_metallic).rgb * s.throughput, vec3<f32>(DENOISE_ALBEDO_FLOOR));
}

// The radiance's lighting divided by the demodulation (emission is added back unfiltered).
fn denoise_illumination(s: Surface, radiance: vec3<f32>) -> vec3<f32> {
    return max(radiance - s.emission, vec3<f32>(0.0)) / denoise_demodulation(s);
}

// The angle between the camera rays of two neighbouring pixels at the image centre: a
// pixel's world footprint is its depth times this.
fn denoise_pixel_angle() -> f32 {
    let centre = vec2<f32>(frame.size) * 0.5;
    let a = camera_ray_direction(centre);
    let b = camera_ray_direction(centre + vec2<f32>(0.0, 1.0));
    return asin(min(length(cross(a, b)), 1.0));
}

// The centre pixel of a filter, its normals decoded once for all its taps.
struct DenoiseCentre {
    position: vec3<f32>,
    depth: f32,
    normal: vec3<f32>,
    geo_normal: vec3<f32>,
}

fn denoise_centre(s: Surface) -> DenoiseCentre {
    return DenoiseCentre(s.position, s.depth, oct_decode(s.normal), oct_decode(s.geo_normal));
}

// Depth and normal edge-stopping between the centre `a` and `b`, `distance` pixels apart:
// b's distance from a's tangent plane against how far a pixel reaches at a's depth (zero
// on one plane however steep, large across a silhouette), and the normals' agreement.
fn denoise_geometry_weight(a: DenoiseCentre, b: Surface, distance: f32, pixel_angle: f32) -> f32 {
#ifdef PLANTED_NO_EDGE_STOPPING
    return 1.0;  // test only: a plain blur, which the edge test must catch
#else
    let normal = pow(max(dot(a.normal, oct_decode(b.normal)), 0.0), params.denoise.phi_normal);
    let plane = abs(dot(a.geo_normal, b.position - a.position));
    let reach = params.denoise.phi_depth * a.depth * pixel_angle * distance + 1e-6 * a.depth;
    return normal * exp(-plane / reach);
#endif
}
