// ReSTIR PT initial path (issue 27; common/pt_path.wgsl defines the path space): one path
// per pixel from its visible point, up to max_bounces bounces, with light sampling and the
// BSDF's found emitter weighted by the balance heuristic at every vertex past the first;
// each of those sub-paths is a candidate of the pixel's path reservoir (RIS, weight
// p̂ / density, p̂ = luminance of the path's integrand, visibility included). One path, so
// M = 1. Draws the GI initial pass's random stream (ReSTIR GI is off while PT is on).
#include "common/pt_path.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read_write> pt_out: array<PtReservoir>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var r = pt_reservoir_empty();
    if surface_is_valid(s) {
        let sp = shading_point_from_surface(s, frame.camera_position);
        var rng = rng_seed(id.xy, STREAM_GI_INITIAL);
        let seed = pcg_hash(rng);
        var ris = pcg_hash(seed ^ 0x68bc21ebu);
        pt_trace_initial(sp, seed, &r, &ris);
        pt_reservoir_finalize(&r);
        r.m = 1.0;
        r.jacobian = 1.0;
        r = pt_guarded(r, GI_PASS_INITIAL);
    }
    pt_out[index] = r;
}
