// Per-pixel statistics of the running average for the `bias` view (docs/src/mis-and-bias.md,
// "The bias view"): how far the
// average is from the reference, and how far it could be by noise alone. Frames of a
// reusing estimator are correlated (a sample lives for about an M cap's worth of frames),
// so the spread of single frames understates the noise of their average; the spread of
// means of BIAS_BATCH consecutive frames (batch means) carries most of that correlation.
// moments = (Σ L over all frames, Σ batch means, Σ batch means², frames), L = luminance;
// the current, incomplete batch's sum is Σ L − BIAS_BATCH · Σ batch means. Cleared with
// the accumulation.
#include "common/frame_bindings.wgsl"
#include "common/math.wgsl"

@group(2) @binding(0) var<storage, read> radiance: array<vec4<f32>>;
@group(2) @binding(1) var<storage, read_write> moments: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    var m = moments[index];
    // The shading passes never write a non-finite radiance; a 0 keeps the count honest.
    var l = luminance(radiance[index].rgb);
    if !is_finite_f32(l) {
        l = 0.0;
    }
    m.x += l;
    m.w += 1.0;
    if u32(m.w) % BIAS_BATCH == 0u {
        let batch_mean = (m.x - f32(BIAS_BATCH) * m.y) / f32(BIAS_BATCH);
        m.y += batch_mean;
        m.z += batch_mean * batch_mean;
    }
    moments[index] = m;
}
