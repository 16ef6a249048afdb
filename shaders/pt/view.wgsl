// The ReSTIR PT debug views, drawn over the display pass's output when one is selected
// and PT runs: `pt-length` (the survivor's path length n: its surface vertices x_1 … x_n),
// `pt-reconnection` (the depth k + 1 of its reconnection vertex x_{k+1}; magenta: a pure
// replay, no reconnection vertex), `pt-failure` (the shifts into this pixel this frame,
// the previous pixel's and the spatial neighbours': the colour of the commonest failure,
// brighter the larger the share that failed; dark green: every one moved), `pt-jacobian`
// (log2 |J| of the survivor's last shift: blue below 1, white at 1, red above, saturating
// at 1/16 and 16), and `indirect` (the PT light alone). Null paths are black. The legends
// (app/src/viewer/panels/palette.rs) read these palettes from this file.
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"
#include "common/display_colors.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> pt_reservoirs: array<PtReservoir>;
@group(2) @binding(2) var<storage, read> pt_debug: array<PtPixelDebug>;
@group(2) @binding(3) var<storage, read> indirect: array<vec4<f32>>;
@group(2) @binding(4) var<uniform> display: Display;
@group(2) @binding(5) var output: texture_storage_2d<rgba8unorm, write>;

const PT_NO_SURFACE: vec3<f32> = vec3<f32>(0.08, 0.08, 0.08);
// log2 |J| at which pt-jacobian saturates (|J| = 1/16 or 16).
const PT_JACOBIAN_SPAN: f32 = 4.0;

// Vertex depth d = 2 … 8 (path length n, or the reconnection vertex x_d).
fn pt_depth_color(d: u32) -> vec3<f32> {
    var palette = array<vec3<f32>, 7>(
        vec3<f32>(0.15, 0.35, 1.0),   // 2
        vec3<f32>(0.1, 0.85, 0.25),   // 3
        vec3<f32>(1.0, 0.9, 0.1),     // 4
        vec3<f32>(1.0, 0.55, 0.05),   // 5
        vec3<f32>(1.0, 0.1, 0.05),    // 6
        vec3<f32>(0.6, 0.3, 0.1),     // 7
        vec3<f32>(1.0, 1.0, 1.0),     // 8
    );
    return palette[clamp(d, 2u, 8u) - 2u];
}

const PT_PURE_REPLAY: vec3<f32> = vec3<f32>(1.0, 0.0, 1.0);

// A shift's outcome (PT_FAIL_*).
fn pt_failure_color(failure: u32) -> vec3<f32> {
    var palette = array<vec3<f32>, PT_FAIL_REASON_COUNT>(
        vec3<f32>(0.0, 0.35, 0.0),    // moved: dark green
        vec3<f32>(1.0, 0.55, 0.05),   // replay left the path: orange
        vec3<f32>(0.55, 0.0, 1.0),    // reconnection undefined: violet
        vec3<f32>(0.1, 0.9, 0.2),     // reconnection occluded: green
        vec3<f32>(0.0, 0.8, 1.0),     // reconnects elsewhere: cyan
        vec3<f32>(1.0, 1.0, 0.0),     // zero where moved: yellow
    );
    return palette[min(failure, PT_FAIL_REASON_COUNT - 1u)];
}

// The shifts into the pixel: the commonest failure's colour, brighter with the failed share.
fn pt_outcome_color(d: PtPixelDebug) -> vec3<f32> {
    var counts: array<u32, PT_FAIL_REASON_COUNT>;
    var tried = 0u;
    for (var f = 0u; f < PT_FAIL_REASON_COUNT; f++) {
        counts[f] = (d.spatial_outcomes >> (4u * f)) & 0xfu;
        tried += counts[f];
    }
    if d.temporal_failure < PT_FAIL_REASON_COUNT {
        counts[d.temporal_failure] += 1u;
        tried += 1u;
    }
    if tried == 0u {
        return vec3<f32>(0.0);
    }
    var worst = 0u;
    for (var f = 1u; f < PT_FAIL_REASON_COUNT; f++) {
        if counts[f] > 0u && (worst == 0u || counts[f] > counts[worst]) {
            worst = f;
        }
    }
    if worst == 0u {
        return pt_failure_color(PT_FAIL_NONE);
    }
    let failed = f32(tried - counts[PT_FAIL_NONE]) / f32(tried);
    return pt_failure_color(worst) * (0.35 + 0.65 * failed);
}

fn pt_color(index: u32) -> vec3<f32> {
    if display.view == VIEW_INDIRECT {
        return tonemap(indirect[index].rgb);
    }
    let s = surfaces[index];
    if s.depth <= 0.0 {
        return PT_NO_SURFACE;
    }
    let r = pt_reservoirs[index];
    if display.view == VIEW_PT_FAILURE {
        return pt_outcome_color(pt_debug[index]);
    }
    if !(r.weight > 0.0) {
        return vec3<f32>(0.0);
    }
    switch display.view {
        case VIEW_PT_LENGTH: {
            return pt_depth_color((r.packed >> 4u) & 0xfu);
        }
        case VIEW_PT_RECONNECTION: {
            let k = (r.packed >> 9u) & 0xfu;
            if k == PT_RC_NONE {
                return PT_PURE_REPLAY;
            }
            return pt_depth_color(k + 1u);
        }
        case VIEW_PT_JACOBIAN: {
            return log_jacobian_color(pt_debug[index].jacobian, PT_JACOBIAN_SPAN);
        }
        default: { return vec3<f32>(0.0); }
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    store_display_color(id.xy, pt_color(pixel_index(id.xy)));
}
