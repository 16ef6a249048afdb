// Temporal accumulation (SVGF, Schied et al. 2017): this frame's demodulated illumination
// blended into last frame's, read through the motion vector with a bilinear filter over
// the taps that see the same surface, and the first two moments of its luminance alike.
// The blend weight is 1/length while the history is young, then `denoise_alpha`; with
// temporal gradients, α + (1 − α) λ where a share λ of the lighting changed (gradient.wgsl).
#include "denoise/common.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> prev_surfaces: array<Surface>;
@group(2) @binding(2) var<storage, read> radiance: array<vec4<f32>>;
@group(2) @binding(3) var<storage, read> history: array<DenoiseHistory>;
@group(2) @binding(4) var<uniform> pass_info: PassInfo;
@group(2) @binding(5) var<storage, read> gradient: array<vec4<f32>>;
@group(2) @binding(6) var<storage, read_write> next: array<DenoiseHistory>;

// Whether last frame's surface `prev` is this pixel's point seen again.
fn same_surface(s: Surface, prev: Surface) -> bool {
    return denoise_has_surface(prev)
        && dot(oct_decode(s.normal), oct_decode(prev.normal)) >= DENOISE_NORMAL_COS
        && length(prev.position - s.position) <= DENOISE_POSITION_TOLERANCE * s.depth;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var out: DenoiseHistory;
    if !denoise_has_surface(s) {
        next[index] = out;
        return;
    }
    let illum = denoise_illumination(s, radiance[index].rgb);
    let l = luminance(illum);
    var sum_illum = vec3<f32>(0.0);
    var sum_moments = vec2<f32>(0.0);
    var sum_length = 0.0;
    var sum_w = 0.0;
    if pass_info.pass_index == DENOISE_HISTORY_SLOT && s.motion.x >= 0.0 && s.motion.y >= 0.0 {
        var c = s.motion - 0.5;
#ifdef PLANTED_NO_REPROJECTION
        c = vec2<f32>(id.xy);  // test only: history read where the pixel is now
#endif
        let base = floor(c);
        let f = c - base;
        for (var t = 0u; t < 4u; t++) {
            let o = vec2<u32>(t & 1u, t >> 1u);
            let w = select(1.0 - f.x, f.x, o.x == 1u) * select(1.0 - f.y, f.y, o.y == 1u);
            let p = vec2<i32>(base) + vec2<i32>(o);
            if w <= 0.0 || any(p < vec2<i32>(0)) || any(p >= vec2<i32>(frame.size)) {
                continue;
            }
            let j = pixel_index(vec2<u32>(p));
            let h = history[j];
            if !same_surface(s, prev_surfaces[j]) || !(h.length > 0.0) {
                continue;
            }
            sum_illum += w * h.illumination;
            sum_length += w * h.length;
            sum_moments += w * h.moments;
            sum_w += w;
        }
    }
    let moments = vec2<f32>(l, l * l);
    out.illumination = illum;
    out.length = 1.0;
    out.moments = moments;
    if sum_w > 1e-3 {
        let length = min(sum_length / sum_w + 1.0, max(params.denoise.history_cap, 1.0));
        var lambda = 0.0;
        if (params.flags & PARAM_FLAG_DENOISE_GRADIENTS) != 0u {
            lambda = gradient[index].x;
        }
        let alpha = mix(max(params.denoise.alpha, 1.0 / length), 1.0, lambda);
        let moments_alpha = mix(max(params.denoise.moments_alpha, 1.0 / length), 1.0, lambda);
        out.illumination = mix(sum_illum / sum_w, illum, alpha);
        out.moments = mix(sum_moments / sum_w, moments, moments_alpha);
        out.length = length;
    }
    if !is_finite_vec3(out.illumination) || !is_finite_f32(out.moments.x + out.moments.y) {
        out.illumination = vec3<f32>(0.0);
        out.moments = vec2<f32>(0.0);
        out.length = 1.0;
    }
    next[index] = out;
}
