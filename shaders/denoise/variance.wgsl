// The variance estimate that scales the à-trous luminance gate: the temporal moments'
// variance where the history holds DENOISE_MIN_HISTORY frames; where it is shorter (a new
// or disoccluded pixel) the moments and illumination of a 7 × 7 neighbourhood on the same
// surfaces, the variance raised by 4 / length (SVGF's allowance for a young estimate).
#include "denoise/common.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> history: array<DenoiseHistory>;
@group(2) @binding(2) var<storage, read_write> filtered: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    if !denoise_has_surface(s) {
        filtered[index] = vec4<f32>(0.0);
        return;
    }
    let h = history[index];
    if h.length >= f32(DENOISE_MIN_HISTORY) {
        filtered[index] = vec4<f32>(h.illumination, max(h.moments.y - h.moments.x * h.moments.x, 0.0));
        return;
    }
    let pixel_angle = denoise_pixel_angle();
    let centre = denoise_centre(s);
    let r = i32(DENOISE_VARIANCE_RADIUS);
    var illum = vec3<f32>(0.0);
    var moments = vec2<f32>(0.0);
    var sum = 0.0;
    for (var dy = -r; dy <= r; dy++) {
        for (var dx = -r; dx <= r; dx++) {
            let p = vec2<i32>(id.xy) + vec2<i32>(dx, dy);
            if any(p < vec2<i32>(0)) || any(p >= vec2<i32>(frame.size)) {
                continue;
            }
            let j = pixel_index(vec2<u32>(p));
            let q = surfaces[j];
            if !denoise_has_surface(q) {
                continue;
            }
            let w = denoise_geometry_weight(centre, q, length(vec2<f32>(f32(dx), f32(dy))), pixel_angle);
            illum += w * history[j].illumination;
            moments += w * history[j].moments;
            sum += w;
        }
    }
    // The centre's own weight is 1, so sum ≥ 1.
    illum /= sum;
    moments /= sum;
    let variance = max(moments.y - moments.x * moments.x, 0.0) * 4.0 / max(h.length, 1.0);
    filtered[index] = vec4<f32>(illum, variance);
}
