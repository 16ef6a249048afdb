// What ReSTIR GI's and PT's shade passes share: where the indirect light goes (added to the
// frame DI shaded and to its running sum, and kept alone for the `indirect` view) and the
// once-a-frame count of which technique ran (`--stats` names its block by it). The pass
// that includes it binds group 2's bindings 0 (surfaces) and 1 (its reservoirs).
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/math.wgsl"

@group(2) @binding(2) var<storage, read_write> radiance: array<vec4<f32>>;
@group(2) @binding(3) var<storage, read_write> accumulation: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> indirect: array<vec4<f32>>;

fn count_indirect_frame(id: vec3<u32>, technique: u32) {
    if all(id == vec3<u32>(0u)) {
        count_stat(STAT_INDIRECT_FRAMES + technique);
    }
}

fn add_indirect(index: u32, light: vec3<f32>) {
    var color = light;
    if !is_finite_vec3(color) {
        count_stat(STAT_INDIRECT_NONFINITE + INDIRECT_PASS_SHADE);
        color = vec3<f32>(0.0);
    }
    indirect[index] = vec4<f32>(color, 1.0);
    radiance[index] += vec4<f32>(color, 0.0);
    accumulation[index] += vec4<f32>(color, 0.0);
}
