// The denoiser's debug views, drawn over the display pass's output when one is selected
// (and the denoiser runs): `denoise-input` (the frame before denoising, tonemapped like the
// image), `history-length` (frames accumulated / denoise_history_cap: dark purple is a
// new or disoccluded pixel) and `denoise-variance` (the relative standard deviation of the
// luminance from the temporal moments, σ / mean over [0, 1]: where the gate lets the
// filter blur most) and `temporal-gradient` (λ over [0, 1]: the share of the lighting that
// changed since last frame; black where gradients are off).
#include "denoise/common.wgsl"
#include "common/display_colors.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> history: array<DenoiseHistory>;
@group(2) @binding(2) var<storage, read> input: array<vec4<f32>>;
@group(2) @binding(3) var<storage, read> gradient: array<vec4<f32>>;
@group(2) @binding(4) var<uniform> display: Display;
@group(2) @binding(5) var output: texture_storage_2d<rgba8unorm, write>;

const DENOISE_NO_SURFACE: vec3<f32> = vec3<f32>(0.08, 0.08, 0.08);

fn denoise_color(index: u32) -> vec3<f32> {
    if display.view == VIEW_DENOISE_INPUT {
        return tonemap(input[index].rgb);
    }
    if !denoise_has_surface(surfaces[index]) {
        return DENOISE_NO_SURFACE;
    }
    let h = history[index];
    switch display.view {
        case VIEW_HISTORY_LENGTH: {
            return heatmap(h.length / max(params.denoise.history_cap, 1.0));
        }
        case VIEW_DENOISE_VARIANCE: {
            let sigma = sqrt(max(h.moments.y - h.moments.x * h.moments.x, 0.0));
            return heatmap(sigma / max(h.moments.x, 1e-6));
        }
        case VIEW_TEMPORAL_GRADIENT: {
            if (params.flags & PARAM_FLAG_DENOISE_GRADIENTS) == 0u {
                return vec3<f32>(0.0);
            }
            return heatmap(gradient[index].x);
        }
        default: { return vec3<f32>(0.0); }
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    store_display_color(id.xy, denoise_color(pixel_index(id.xy)));
}
