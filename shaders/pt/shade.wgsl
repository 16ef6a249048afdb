// ReSTIR PT shading: the pixel's path contributes f(x̄) · W (f, the path's integrand at this
// pixel, was evaluated where it was picked: traced, or shifted here with its visibility),
// added to the frame DI shaded and kept alone for the `indirect` view.
#include "pt/reservoir.wgsl"
#include "common/indirect_shade.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> pt_reservoirs: array<PtReservoir>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    count_indirect_frame(id, INDIRECT_PT);
    if pixel_in_frame(id) {
        let index = pixel_index(id.xy);
        add_indirect(index, pt_shade(surfaces[index], pt_reservoirs[index]));
    }
}

// The pixel's indirect radiance: 0 where it sees no surface or holds no path.
fn pt_shade(s: Surface, stored: PtReservoir) -> vec3<f32> {
    if !surface_is_valid(s) {
        return vec3<f32>(0.0);
    }
    let r = pt_checked(stored, INDIRECT_PASS_SHADE);
    if pt_reservoir_is_null(r) {
        return vec3<f32>(0.0);
    }
    return s.throughput * r.value * r.weight;
}
