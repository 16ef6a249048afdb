// ReSTIR GI shading: the indirect radiance f_r(x_v) · L_o · cos θ · W of the pixel's GI
// sample, added to the frame DI shaded (radiance and running sum) and kept alone for the
// `indirect` view. No visibility ray here: an initial sample is visible by construction,
// spatial reuse traces the reconnection (gi_spatial_visibility), and a temporal sample
// was visible from the previous visible point (docs/src/restir-gi.md, "The passes").
#include "gi/reuse.wgsl"
#include "common/indirect_shade.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> gi_reservoirs: array<GiReservoir>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    count_indirect_frame(id, INDIRECT_GI);
    if pixel_in_frame(id) {
        let index = pixel_index(id.xy);
        add_indirect(index, gi_shade(surfaces[index], gi_reservoirs[index]));
    }
}

// The pixel's indirect radiance: 0 where it sees no surface or holds no usable sample.
fn gi_shade(s: Surface, stored: GiReservoir) -> vec3<f32> {
    if !surface_is_valid(s) {
        return vec3<f32>(0.0);
    }
    let r = gi_checked(stored, INDIRECT_PASS_SHADE);
    if gi_reservoir_is_null(r) {
        return vec3<f32>(0.0);
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    let d = r.position - sp.position;
    let len2 = dot(d, d);
    if !(len2 > 0.0 && dot(sp.geo_normal, d) > 0.0) {
        return vec3<f32>(0.0);
    }
    let wi = d * inverseSqrt(len2);
    let cos_theta = gi_receiver_cosine(sp.position, sp.normal, r.position);
    return s.throughput * eval_brdf(sp.brdf, sp.normal, sp.wo, wi) * r.radiance * (cos_theta * r.weight);
}
