// One à-trous iteration (Dammertz et al. 2010, as SVGF uses it): a 5 × 5 B3-spline kernel
// with taps 2^i pixels apart, each tap weighted by depth, normal and luminance
// edge-stopping. The luminance gate scales |Δl| by the standard deviation of the
// difference, both pixels' variances (the centre's blurred 3 × 3): gated by the centre's
// alone, a bright pixel averages dark neighbours in while they keep it out, and bright
// energy is lost. Variance is carried as that of the weighted mean, Σ w² σ² / (Σ w)².
#include "denoise/common.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> input: array<vec4<f32>>;
@group(2) @binding(2) var<uniform> pass_info: PassInfo;
@group(2) @binding(3) var<storage, read_write> output: array<vec4<f32>>;

fn in_image(p: vec2<i32>) -> bool {
    return all(p >= vec2<i32>(0)) && all(p < vec2<i32>(frame.size));
}

// The centre's variance blurred 3 × 3 (Gaussian, over pixels with a surface).
fn prefiltered_variance(pixel: vec2<i32>) -> f32 {
    let k = array<f32, 3>(0.25, 0.5, 0.25);
    var variance = 0.0;
    var sum = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let p = pixel + vec2<i32>(dx, dy);
            if !in_image(p) {
                continue;
            }
            let j = pixel_index(vec2<u32>(p));
            if denoise_has_surface(surfaces[j]) {
                let w = k[dx + 1] * k[dy + 1];
                variance += w * input[j].w;
                sum += w;
            }
        }
    }
    return variance / sum;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    let own = input[index];
    if !denoise_has_surface(s) {
        output[index] = own;
        return;
    }
    let kernel = array<f32, 5>(1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
    let step = i32(1u << pass_info.pass_index);
    let pixel_angle = denoise_pixel_angle();
    let centre = denoise_centre(s);
    let l = luminance(own.rgb);
    let centre_variance = prefiltered_variance(vec2<i32>(id.xy));
    var illum = vec3<f32>(0.0);
    var variance = 0.0;
    var sum = 0.0;
    for (var ky = 0; ky < 5; ky++) {
        for (var kx = 0; kx < 5; kx++) {
            let offset = vec2<i32>(kx - 2, ky - 2) * step;
            let p = vec2<i32>(id.xy) + offset;
            if !in_image(p) {
                continue;
            }
            let j = pixel_index(vec2<u32>(p));
            let qs = surfaces[j];
            if !denoise_has_surface(qs) {
                continue;
            }
            let q = input[j];
            var w = kernel[kx] * kernel[ky];
            w *= denoise_geometry_weight(centre, qs, length(vec2<f32>(offset)), pixel_angle);
#ifndef PLANTED_NO_EDGE_STOPPING
#ifdef PLANTED_CENTRE_VARIANCE_GATE
            let spread = centre_variance;  // test only: the gate the energy test must catch
#else
            let spread = centre_variance + max(q.w, 0.0);
#endif
            w *= exp(-abs(l - luminance(q.rgb)) / (params.denoise.phi_luminance * sqrt(spread) + 1e-10));
#endif
            illum += w * q.rgb;
            variance += w * w * q.w;
            sum += w;
        }
    }
    // The centre's weight is 9/64 > 0 whatever the edges say.
    output[index] = vec4<f32>(illum / sum, variance / (sum * sum));
}
