// The `bias` debug view (docs/src/mis-and-bias.md, "The bias view"), drawn over the display pass's
// output when selected: where the running average differs from the reference by more than its
// noise, and by how much. Its own pass because the display pass already binds as many storage
// buffers as a compute stage may have (19 with the frame and scene groups).
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"
#include "common/display_colors.wgsl"

@group(2) @binding(0) var<storage, read> moments: array<vec4<f32>>;
@group(2) @binding(1) var<storage, read> reference: array<vec4<f32>>;
@group(2) @binding(2) var<uniform> display: Display;
@group(2) @binding(3) var output: texture_storage_2d<rgba8unorm, write>;

// Blue (darker than the reference) – white (0) – red (brighter), t in [−1, 1], linear
// between the three.
fn bias_palette(t: f32) -> vec3<f32> {
    var palette = array<vec3<f32>, 3>(
        vec3<f32>(0.1, 0.3, 1.0),   // darker: blue
        vec3<f32>(1.0, 1.0, 1.0),   // no bias: white
        vec3<f32>(1.0, 0.1, 0.05),  // brighter: red
    );
    let x = clamp(t, -1.0, 1.0);
    return select(mix(palette[1], palette[2], x), mix(palette[1], palette[0], -x), x < 0.0);
}

// The bias view: the running average's luminance minus the reference's, relative to the
// reference and saturating at ±25 %, where it exceeds BIAS_SIGNIFICANCE standard errors of
// the average (batch means, moments.wgsl) and the reference's own noise, and is at least
// BIAS_NEGLIGIBLE of the reference; elsewhere, and until two batches exist, the scene in
// dim grey: within noise, nothing to tell.
fn bias_color(index: u32) -> vec3<f32> {
    let m = moments[index];
    let truth = luminance(reference[index].rgb * display.reference_scale);
    let dim = vec3<f32>(0.2 + 0.35 * luminance(tonemap(vec3<f32>(truth * display.exposure))));
    let batches = floor(m.w / f32(BIAS_BATCH));
    if batches < 2.0 {
        return dim;
    }
    let mean = m.x / m.w;
    let batch_mean = m.y / batches;
    let batch_var = max(m.z / batches - batch_mean * batch_mean, 0.0) * batches / (batches - 1.0);
    let noise2 = batch_var / batches + display.reference_noise * display.reference_noise;
    let d = mean - truth;
    if !(abs(d) > BIAS_SIGNIFICANCE * sqrt(noise2)) || abs(d) < BIAS_NEGLIGIBLE * truth {
        return dim;
    }
    return bias_palette(4.0 * d / max(truth, 1e-6));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    store_display_color(id.xy, bias_color(pixel_index(id.xy)));
}
