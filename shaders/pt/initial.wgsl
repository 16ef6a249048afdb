// ReSTIR PT initial path (docs/src/restir-pt.md, "The path space"; pt/path.wgsl defines it): one
// path per pixel from its visible point, up to max_bounces bounces, with light sampling and the
// BSDF's found emitter weighted by the balance heuristic at every vertex past the first; each of
// those sub-paths is a candidate of the pixel's path reservoir (RIS, weight p̂ / density, p̂ =
// luminance of the path's integrand, visibility included). One path, so M = 1. Draws the GI initial
// pass's random stream (ReSTIR GI is off while PT is on). Starts the pixel's PT debug record and
// probes the inspected pixel's path.
#include "pt/path.wgsl"
#include "pt/probe.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read_write> pt_out: array<PtReservoir>;
@group(2) @binding(2) var<storage, read_write> pt_debug: array<PtPixelDebug>;
@group(2) @binding(3) var<storage, read_write> pt_probe: array<PtProbeStage>;
// The light BVH, for the vertex sampler (common/vertex_light.wgsl); one-element
// placeholders unless VERTEX_LIGHT_BVH is compiled.
@group(2) @binding(4) var<storage, read> light_bvh_nodes: array<LightBvhNode>;
@group(2) @binding(5) var<storage, read> light_bvh_trails: array<LightBvhTrail>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    var r = pt_reservoir_empty();
    var d = PtPixelDebug(0u, PT_FAIL_NOT_TRIED, 0u, 0u, 1.0, 0.0, 0.0, 0.0);
    if surface_is_valid(s) {
        let sp = shading_point_from_surface(s, frame.camera_position);
        var rng = rng_seed(id.xy, STREAM_INDIRECT_INITIAL);
        let seed = pcg_hash(rng);
        var ris = pcg_hash(seed ^ 0x68bc21ebu);
        pt_trace_initial(sp, seed, &r, &ris);
        pt_reservoir_finalize(&r);
        r.m = 1.0;
        r.jacobian = 1.0;
        r = pt_guarded(r, INDIRECT_PASS_INITIAL);
        pt_probe_write(PT_PROBE_INITIAL, index, sp, r);
    }
    d.m_initial = r.m;
    d.m_temporal = r.m;
    d.m_spatial = r.m;
    pt_debug[index] = d;
    pt_out[index] = r;
}
