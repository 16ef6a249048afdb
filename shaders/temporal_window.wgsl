// The temporal window behind the boiling and survivor-change views (docs/src/debug-views.md,
// "Boiling and survivor change"): each pixel's luminance over the last TEMPORAL_WINDOW_FRAMES
// frames and the frames in which its survivor's light changed, with the two figures the views
// paint. Runs once the frame's radiance is final (after DI and GI shading, or the reference).
// `pass_info.pass_index` is 1 on real-time frames, whose reservoirs are this frame's survivors, and
// 0 on reference frames, which have none (no change is recorded).
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"

@group(2) @binding(0) var<storage, read> radiance: array<vec4<f32>>;
@group(2) @binding(1) var<storage, read> reservoirs: array<Reservoir>;
@group(2) @binding(2) var<uniform> pass_info: PassInfo;
@group(2) @binding(3) var<storage, read_write> window: array<WindowPixel>;

fn frame_luminance(index: u32) -> f32 {
    let l = luminance(radiance[index].rgb);
    return select(0.0, l, is_finite_f32(l));
}

// σ / mean of `n` samples from their sum and the sums of their offsets from `shift`, one
// of the samples (sample σ, n − 1): offsets keep the variance exact where all samples are
// equal (0, not a rounding residue) and free of cancellation. 0 for fewer than two
// samples or a black pixel, where flicker is not defined.
fn relative_std(sum: f32, offset_sum: f32, offset_sum_sq: f32, n: f32) -> f32 {
    if n < 2.0 || !(sum > 0.0) {
        return 0.0;
    }
    let variance = max(offset_sum_sq - offset_sum * offset_sum / n, 0.0) / (n - 1.0);
    return sqrt(variance) / (sum / n);
}

// The bits of the slots whose change bit describes a transition inside the window: every
// filled slot but the oldest (its bit, if any, is a change from a frame that has left).
fn transitions_mask(count: u32) -> u32 {
    let all = (1u << TEMPORAL_WINDOW_FRAMES) - 1u;
    if count >= TEMPORAL_WINDOW_FRAMES {
        return all & ~(1u << (count % TEMPORAL_WINDOW_FRAMES));
    }
    return ((1u << count) - 1u) & ~1u;
}

#ifdef PLANTED_WINDOW_CURRENT_FRAME_ONLY
// A planted error for render/tests/temporal_window.rs: "boiling" from this frame alone,
// σ/mean over the 3 × 3 neighbourhood. It reads noise, not flicker, and must fail the
// frozen-scene test (an image that never changes does not boil).
fn planted_spatial_std(pixel: vec2<u32>) -> f32 {
    let shift = frame_luminance(pixel_index(pixel));
    var sum = 0.0;
    var offsets = 0.0;
    var offsets_sq = 0.0;
    var n = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let p = vec2<i32>(pixel) + vec2<i32>(dx, dy);
            if any(p < vec2<i32>(0)) || any(p >= vec2<i32>(frame.size)) {
                continue;
            }
            let l = frame_luminance(pixel_index(vec2<u32>(p)));
            sum += l;
            offsets += l - shift;
            offsets_sq += (l - shift) * (l - shift);
            n += 1.0;
        }
    }
    return relative_std(sum, offsets, offsets_sq, n);
}
#endif

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    var w = window[index];
    let slot = w.count % TEMPORAL_WINDOW_FRAMES;
    let bit = 1u << slot;
    w.luma[slot] = frame_luminance(index);
    w.changes &= ~bit;
    if pass_info.pass_index == 1u {
        // The survivor that was shaded (a null sample is NO_LIGHT, a light of its own).
        let light = reservoirs[index].light;
        if w.count > 0u && light != w.last_light {
            w.changes |= bit;
        }
        w.last_light = light;
    }
    w.count += 1u;

    let filled = min(w.count, TEMPORAL_WINDOW_FRAMES);
    let shift = w.luma[0];
    var sum = 0.0;
    var offsets = 0.0;
    var offsets_sq = 0.0;
    for (var s = 0u; s < filled; s++) {
        let d = w.luma[s] - shift;
        sum += w.luma[s];
        offsets += d;
        offsets_sq += d * d;
    }
    w.rel_std = relative_std(sum, offsets, offsets_sq, f32(filled));
#ifdef PLANTED_WINDOW_CURRENT_FRAME_ONLY
    w.rel_std = planted_spatial_std(id.xy);
#endif
    let transitions = filled - min(filled, 1u);
    w.change_fraction = select(
        0.0,
        f32(countOneBits(w.changes & transitions_mask(w.count))) / f32(max(transitions, 1u)),
        transitions > 0u
    );
    window[index] = w;
}
