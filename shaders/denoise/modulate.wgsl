// Remodulation: the filtered illumination times the surface colour, plus the emission,
// becomes the frame's radiance; the running average is corrected by the same difference,
// so everything after (moments, windows, the bench's readbacks) sees the denoised frame.
// The raw radiance is kept for the `denoise-input` view. Pixels without a surface keep
// their radiance.
#include "denoise/common.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> filtered: array<vec4<f32>>;
@group(2) @binding(2) var<storage, read_write> radiance: array<vec4<f32>>;
@group(2) @binding(3) var<storage, read_write> accumulation: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> input: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let raw = radiance[index];
    input[index] = raw;
    let s = surfaces[index];
    if !denoise_has_surface(s) {
        return;
    }
    var out = s.emission + denoise_demodulation(s) * filtered[index].rgb;
    if !is_finite_vec3(out) {
        out = raw.rgb;
    }
    radiance[index] = vec4<f32>(out, raw.w);
    accumulation[index] += vec4<f32>(out - raw.rgb, 0.0);
}
