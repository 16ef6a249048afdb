// The boiling and survivor-change views, drawn over the display pass's output when one
// is selected (the display pass is at the storage-buffer limit): `boiling` paints each
// pixel's σ/mean of luminance over the temporal window (0 → BOILING_VIEW_MAX, viridis),
// `survivor-change` the fraction of the window's frames in which the survivor's light
// changed (0 → 1). Below two frames in the window there is nothing to measure: black.
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"
#include "common/display_colors.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> window: array<WindowPixel>;
@group(2) @binding(2) var<uniform> display: Display;
@group(2) @binding(3) var output: texture_storage_2d<rgba8unorm, write>;

const WINDOW_NO_SURFACE: vec3<f32> = vec3<f32>(0.08, 0.08, 0.08);

fn window_color(index: u32) -> vec3<f32> {
    if surfaces[index].depth <= 0.0 {
        return WINDOW_NO_SURFACE;
    }
    let w = window[index];
    if w.count < 2u {
        return vec3<f32>(0.0);
    }
    if display.view == VIEW_BOILING {
        return heatmap(w.rel_std / BOILING_VIEW_MAX);
    }
    return heatmap(w.change_fraction);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    store_display_color(id.xy, window_color(pixel_index(id.xy)));
}
