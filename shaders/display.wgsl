// What the user sees: the tonemapped image or one of the debug views, written as
// sRGB-encoded RGBA8 (the viewer samples it through an sRGB view; PNGs store it as is).
// Palettes are fixed and documented in docs/src/debug-views.md ("The views").
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"
#include "common/display_colors.wgsl"
#include "common/rng.wgsl"
#include "common/regir_grid.wgsl"

@group(2) @binding(0) var<storage, read> image: array<vec4<f32>>;
@group(2) @binding(1) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(2) var<storage, read> debug: array<PixelDebug>;
@group(2) @binding(3) var<storage, read> reservoirs: array<Reservoir>;
@group(2) @binding(4) var<storage, read> reference: array<vec4<f32>>;
@group(2) @binding(5) var<uniform> display: Display;
@group(2) @binding(6) var output: texture_storage_2d<rgba8unorm, write>;
@group(2) @binding(7) var<storage, read> comparison: array<vec4<f32>>;

const NO_SURFACE_COLOR: vec3<f32> = vec3<f32>(0.08, 0.08, 0.08);

// One colour per temporal rejection reason (bit index 0..REJECT_REASON_COUNT): the shared
// checks (check_color), then DI's own.
fn reason_color(bit: u32) -> vec3<f32> {
    if bit < SHARED_REJECT_CHECKS {
        return check_color(bit);
    }
    var palette = array<vec3<f32>, REJECT_REASON_COUNT - SHARED_REJECT_CHECKS>(
        vec3<f32>(0.6, 0.3, 0.1),   // target ≤ 0: brown
        vec3<f32>(1.0, 1.0, 1.0),   // target ratio: white
        vec3<f32>(0.1, 0.9, 0.2),   // light gone (off or removed): green
    );
    return palette[min(bit - SHARED_REJECT_CHECKS, REJECT_REASON_COUNT - SHARED_REJECT_CHECKS - 1u)];
}

// Fraction of spatial neighbours rejected: black (none) to a mid grey (all), darker than
// every reason colour so the two never read alike.
fn spatial_count_color(fraction: f32) -> vec3<f32> {
    return vec3<f32>(0.45 * clamp(fraction, 0.0, 1.0));
}

fn debug_color(index: u32, pixel: vec2<u32>) -> vec3<f32> {
    let s = surfaces[index];
    let d = debug[index];
    if display.view == VIEW_ERROR {
        let value = luminance(image[index].rgb * display.scale);
        let truth = luminance(reference[index].rgb * display.reference_scale);
        // |frame − reference| relative to the exposure's white point.
        return heatmap(abs(value - truth) * display.exposure);
    }
    if display.view == VIEW_DIFFERENCE {
        let a = luminance(image[index].rgb * display.scale);
        let b = luminance(comparison[index].rgb * display.comparison_scale);
        return heatmap(abs(a - b) * display.exposure);
    }
    if s.depth <= 0.0 {
        return NO_SURFACE_COLOR;
    }
    switch display.view {
        case VIEW_SOURCE: {
            // A survivor that is an environment direction: the same hue, half-way to white.
            let env_sample = (d.flags & DEBUG_FLAG_ENVIRONMENT_SAMPLE) != 0u;
            return select(source_color(d.source), mix(source_color(d.source), vec3<f32>(1.0), 0.55), env_sample);
        }
        case VIEW_M: {
            let r = reservoirs[index];
            return heatmap(r.m / max(display.m_scale, 1.0));
        }
        case VIEW_AGE: {
            // Frames since the survivor was first drawn, up to 2 × M cap (yellow).
            let r = reservoirs[index];
            if r.light == NO_LIGHT {
                return vec3<f32>(0.0);
            }
            return heatmap(f32(r.source >> AGE_SHIFT) / max(2.0 * display.m_scale, 1.0));
        }
        case VIEW_REJECTION: {
            // Temporal: the first enabled reason. Elsewhere, spatial: how many of the
            // neighbours tried were rejected, for any reason, as a grey level (the union of
            // K neighbours' reasons paints almost every pixel one colour and says little;
            // the reasons themselves are in the Stats panel and the inspector).
            let mask = d.temporal_mask & display.reason_mask & ((1u << REJECT_REASON_COUNT) - 1u);
            if mask != 0u {
                return reason_color(firstTrailingBit(mask));
            }
            if display.spatial_tries == 0u {
                return vec3<f32>(0.0);
            }
            let rejected = display.spatial_tries - min(d.spatial_accepted, display.spatial_tries);
            return spatial_count_color(f32(rejected) / f32(display.spatial_tries));
        }
        case VIEW_WEIGHT: {
            // log10 W over [-4, 4] → [0, 1]; null samples are black.
            if !(d.weight > 0.0) {
                return vec3<f32>(0.0);
            }
            return heatmap((log2(d.weight) * 0.30103 + 4.0) / 8.0);
        }
        case VIEW_PROPOSER: { return proposer_color(d.proposer); }
        case VIEW_USEFUL_CANDIDATES: { return heatmap(d.useful_candidates); }
        case VIEW_REGIR_CELL: {
            // A colour per cell (hashed), black outside the grid.
            let cell = regir_cell_at(s.position);
            if cell == REGIR_NO_CELL {
                return vec3<f32>(0.0);
            }
            let h = pcg_hash(cell);
            return vec3<f32>(f32(h & 255u), f32((h >> 8u) & 255u), f32((h >> 16u) & 255u)) / 255.0 * 0.8 + 0.2;
        }
        case VIEW_NORMALS: { return oct_decode(s.normal) * 0.5 + 0.5; }
        case VIEW_ALBEDO: { return unpack4x8unorm(s.base_color_metallic).rgb; }
        case VIEW_DEPTH: { return vec3<f32>(1.0 - clamp(s.depth / frame.scene_scale, 0.0, 1.0)); }
        case VIEW_MOTION: {
            let m = s.motion - (vec2<f32>(pixel) + 0.5);
            return vec3<f32>(clamp(m * 0.1 + 0.5, vec2<f32>(0.0), vec2<f32>(1.0)), 0.5);
        }
        default: { return vec3<f32>(0.0); }
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    if display.view == VIEW_FINAL {
        store_display_color(id.xy, tonemap(image[index].rgb * display.scale));
    } else {
        store_display_color(id.xy, debug_color(index, id.xy));
    }
}
