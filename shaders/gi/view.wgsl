// The ReSTIR GI debug views, drawn over the display pass's output when one is selected
// (and GI runs): `indirect` (the indirect radiance alone, tonemapped like the image),
// `gi-source`, `gi-m` (M / gi_m_cap), `gi-rejection` (the first GI temporal reason, else
// the share of spatial neighbours rejected as grey) and `gi-jacobian` (log2 |J| of the
// survivor's last shift: blue below 1, white at 1, red above, saturating at the window).
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"
#include "common/display_colors.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> gi_reservoirs: array<GiReservoir>;
@group(2) @binding(2) var<storage, read> gi_debug: array<GiPixelDebug>;
@group(2) @binding(3) var<storage, read> indirect: array<vec4<f32>>;
@group(2) @binding(4) var<uniform> display: Display;
@group(2) @binding(5) var output: texture_storage_2d<rgba8unorm, write>;

const GI_NO_SURFACE: vec3<f32> = vec3<f32>(0.08, 0.08, 0.08);

// One colour per GI rejection bit: the shared checks in DI's colours (check_color), then
// GI's own three.
fn gi_reason_color(bit: u32) -> vec3<f32> {
    if bit < SHARED_REJECT_CHECKS {
        return check_color(bit);
    }
    var palette = array<vec3<f32>, GI_REJECT_REASON_COUNT - SHARED_REJECT_CHECKS>(
        vec3<f32>(0.55, 0.0, 1.0),  // reconnection undefined: violet
        vec3<f32>(1.0, 1.0, 1.0),   // Jacobian outside the window: white
        vec3<f32>(0.1, 0.9, 0.2),   // reconnection occluded: green
    );
    return palette[min(bit - SHARED_REJECT_CHECKS, GI_REJECT_REASON_COUNT - SHARED_REJECT_CHECKS - 1u)];
}

// log2 |J| over ±log2(window).
fn jacobian_color(j: f32) -> vec3<f32> {
    return log_jacobian_color(j, max(log2(max(params.gi.jacobian_max, 2.0)), 1.0));
}

fn gi_color(index: u32) -> vec3<f32> {
    if display.view == VIEW_INDIRECT {
        return tonemap(indirect[index].rgb);
    }
    let s = surfaces[index];
    if s.depth <= 0.0 {
        return GI_NO_SURFACE;
    }
    let r = gi_reservoirs[index];
    let d = gi_debug[index];
    switch display.view {
        case VIEW_GI_SOURCE: {
            return source_color(select(r.packed & GI_SOURCE_MASK, SOURCE_NULL, !(r.weight > 0.0)));
        }
        case VIEW_GI_M: {
            return heatmap(r.m / max(params.gi.m_cap, 1.0));
        }
        case VIEW_GI_REJECTION: {
            let mask = d.temporal_mask & ((1u << GI_REJECT_REASON_COUNT) - 1u);
            if mask != 0u {
                return gi_reason_color(firstTrailingBit(mask));
            }
            let tries = min(params.gi.spatial_neighbours, MAX_SPATIAL_NEIGHBOURS);
            if tries == 0u || (params.flags & PARAM_FLAG_GI_SPATIAL) == 0u {
                return vec3<f32>(0.0);
            }
            let rejected = tries - min(d.spatial_accepted, tries);
            return vec3<f32>(0.45 * f32(rejected) / f32(tries));
        }
        case VIEW_GI_JACOBIAN: {
            if !(r.weight > 0.0) {
                return vec3<f32>(0.0);
            }
            return jacobian_color(d.jacobian);
        }
        default: { return vec3<f32>(0.0); }
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    store_display_color(id.xy, gi_color(pixel_index(id.xy)));
}
