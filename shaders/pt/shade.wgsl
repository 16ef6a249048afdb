// ReSTIR PT shading: the pixel's path contributes f(x̄) · W (f, the path's integrand at this
// pixel, was evaluated where it was picked: traced, or shifted here with its visibility),
// added to the frame DI shaded and kept alone for the `indirect` view.
#include "pt/reservoir.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> pt_reservoirs: array<PtReservoir>;
@group(2) @binding(2) var<storage, read_write> radiance: array<vec4<f32>>;
@group(2) @binding(3) var<storage, read_write> accumulation: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> indirect: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    // Once a frame: which indirect technique ran (`--stats` names its block by it).
    if all(id == vec3<u32>(0u)) {
        count_stat(STAT_INDIRECT_FRAMES + INDIRECT_PT);
    }
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var color = vec3<f32>(0.0);
    if surface_is_valid(s) {
        let r = pt_checked(pt_reservoirs[index], INDIRECT_PASS_SHADE);
        if !pt_reservoir_is_null(r) {
            color = s.throughput * r.value * r.weight;
        }
    }
    if !is_finite_vec3(color) {
        count_stat(STAT_INDIRECT_NONFINITE + INDIRECT_PASS_SHADE);
        color = vec3<f32>(0.0);
    }
    indirect[index] = vec4<f32>(color, 1.0);
    radiance[index] += vec4<f32>(color, 0.0);
    accumulation[index] += vec4<f32>(color, 0.0);
}
