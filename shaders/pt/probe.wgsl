// The pixel inspector's view of a PT stage: when this invocation's pixel is the inspected
// one (frame.inspect_pixel), the path the stage kept is written to the probe with its
// vertices rebuilt from the record, the way a shift rebuilds them: the prefix replayed
// from this pixel's visible point with the path's numbers, the reconnection vertex from
// its triangle and barycentrics, the step after it along rc_out, later bounces with the
// path's own numbers (past the reconnection they see what the original path saw), and the
// light point z. The including pass declares `pt_probe: array<PtProbeStage>`.

const PT_PROBE_INITIAL: u32 = 0u;
const PT_PROBE_TEMPORAL: u32 = 1u;
const PT_PROBE_SPATIAL: u32 = 2u;

fn pt_probe_vertex(position: vec3<f32>, flags: u32) -> vec4<f32> {
    return vec4<f32>(position, bitcast<f32>(flags));
}

fn pt_probe_write(stage: u32, pixel: u32, first: ShadingPoint, r: PtReservoir) {
    if pixel != frame.inspect_pixel {
        return;
    }
    var out: PtProbeStage;
    out.written = 1u;
    out.reservoir = r;
    out.vertex_count = 0u;
    if !pt_reservoir_is_null(r) {
        var vertices: array<vec4<f32>, PT_PROBE_VERTICES>;
        var count = 0u;
        vertices[0] = pt_probe_vertex(first.position, 0u);
        count = 1u;
#ifdef PLANTED_PT_PROBE_WRONG_NUMBERS
        // Test-only planted error (render/tests/restir_pt_inspect.rs): rebuild the path
        // with another path's random numbers.
        let seed = r.seed ^ 0x5bd1e995u;
#else
        let seed = r.seed;
#endif
        let n = min(pt_n(r), MAX_BOUNCES);
        let k = pt_k(r);
        let reconnects = k != PT_RC_NONE && k < n;
        // x_1 … x_{n−1}: replayed up to the reconnection vertex x_k (stored with the path),
        // then the steps after it (the one leaving x_k along its stored direction). One
        // trace call site for all of them (docs/src/compile-time.md).
        let last = select(select(k - 1u, n - 1u, k == PT_RC_NONE), n - 1u, reconnects);
        var sp = first;
        var complete = true;
        for (var b = 1u; b <= last; b++) {
            if reconnects && b == k {
                let hs = hit_surface(r.rc_triangle, r.rc_u, r.rc_v, sp.position);
                let wi = safe_normalize(hs.position - sp.position, sp.normal);
                sp = hit_shading_point(hs, -wi, hit_brdf(hs), 0.0);
                vertices[count] = pt_probe_vertex(sp.position, PT_VERTEX_RECONNECTION);
                count++;
                continue;
            }
            var rng = pt_rng(seed, b, PT_RNG_BSDF);
            var bn: PtBounce;
            if reconnects && b == k + 1u {
                // The step leaving the reconnection vertex, stored with the path.
                bn.wi = oct_decode(r.rc_out);
                bn.ok = true;
                bn.hit = false;
                rand_f32(&rng);
                rand_f32(&rng);
                rand_f32(&rng);
            } else {
                bn = pt_bounce_direction(sp, &rng);
            }
            if bn.ok {
                pt_follow(sp, &bn, &rng);
            }
            if !bn.hit {
                complete = false;
                break;
            }
            sp = bn.next;
            vertices[count] = pt_probe_vertex(sp.position, 0u);
            count++;
        }
        if complete && r.light != NO_LIGHT {
            let lp = light_point(r.light, vec2<f32>(r.light_u, r.light_v));
            if lp.kind == LIGHT_KIND_ENVIRONMENT {
                vertices[count] = pt_probe_vertex(lp.position, PT_VERTEX_LIGHT | PT_VERTEX_DIRECTION);
            } else {
                vertices[count] = pt_probe_vertex(lp.position, PT_VERTEX_LIGHT);
            }
            count++;
        }
        out.vertices = vertices;
        out.vertex_count = count;
    }
    pt_probe[stage] = out;
}
