// Temporal gradients (A-SVGF, Schied et al. 2018): how much of the lighting changed since
// last frame. DI's temporal pass left each pixel its history's sample shaded as last frame
// saw it and as it shades now (this frame's lights and occluders, at this frame's surface);
// one sample's change is noise, so both are summed over a 13 × 13 neighbourhood (5 × 5
// taps 3 px apart, on the same surfaces), and λ = |Σ now − Σ before| / max(Σ now, Σ before)
// is the share of the neighbourhood's shading that changed: 0 where nothing did, 1 where a
// light went off. The temporal pass weighs this frame by α + (1 − α) λ.
#include "denoise/common.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> debug: array<PixelDebug>;
@group(2) @binding(2) var<storage, read_write> gradient: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    if !denoise_has_surface(s) {
        gradient[index] = vec4<f32>(0.0);
        return;
    }
    let pixel_angle = denoise_pixel_angle();
    let centre = denoise_centre(s);
    let r = i32(DENOISE_GRADIENT_TAPS);
    var before = 0.0;
    var now = 0.0;
    for (var dy = -r; dy <= r; dy++) {
        for (var dx = -r; dx <= r; dx++) {
            let offset = vec2<i32>(dx, dy) * i32(DENOISE_GRADIENT_STRIDE);
            let p = vec2<i32>(id.xy) + offset;
            if any(p < vec2<i32>(0)) || any(p >= vec2<i32>(frame.size)) {
                continue;
            }
            let j = pixel_index(vec2<u32>(p));
            let q = surfaces[j];
            if !denoise_has_surface(q) {
                continue;
            }
            let w = denoise_geometry_weight(centre, q, length(vec2<f32>(offset)), pixel_angle);
            let g = debug[j].gradient;
            before += w * g.x;
            now += w * g.y;
        }
    }
    let larger = max(before, now);
    var lambda = 0.0;
    if larger > 0.0 {
        lambda = clamp(abs(now - before) / larger, 0.0, 1.0);
    }
    if !is_finite_f32(lambda) {
        lambda = 0.0;
    }
    gradient[index] = vec4<f32>(lambda, before, now, 0.0);
}
