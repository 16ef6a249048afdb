// ReSTIR PT paths (docs/src/restir-pt.md; the CPU model is render/src/pt/model, whose module docs
// define the shifts): tracing a pixel's path with its sub-paths as candidates, and moving
// a path found at one pixel to another by reconnection, random replay or the hybrid.
//
// The path space. A path x_1 → x_2 → … → x_n → z starts at the pixel's visible point x_1
// and ends at a light point z, 2 ≤ n ≤ max_bounces (n = 1 is direct light, ReSTIR DI's).
// Its coordinates: at each x_b (b < n) a lobe and a direction (lobe-split: the domain is
// lobe × direction, so replaying the same random numbers is a bijection even where two
// lobes overlap), then z, reached by one of two techniques: light sampling (PT_END_NEE)
// or the BSDF's direction at x_n (PT_END_BSDF, with its lobe), both in z's own measure
// (area; solid angle for the sky; discrete for punctual lights). The integrand is the
// path tracer's, split the same way, so the techniques and lobes sum to it:
//
//   f = Π_{b<n} g_b · e_n,   g_b = f_s cos · q_l p_l(ω_b) / p_mix(ω_b),
//   e_n = L_e f_s cos G · {p_light / (p_light + p_mix)  (NEE),  q_l p_l / (p_light + p_mix)  (BSDF)}
//
// with every pdf of the end in z's measure, and transmittance through clear layers in the
// factors of the segments it crosses. Sampled with density Π q_l p_l · (p_light or q_l p_l),
// so f / density is exactly the reference's path throughput (path_trace.wgsl).
//
// Random numbers. A path keeps one seed; bounce b draws its lobe, direction and layer walk
// from pt_rng(seed, b, PT_RNG_BSDF) and its light sample from pt_rng(seed, b, PT_RNG_LIGHT),
// so replaying bounce b anywhere draws the same numbers. A pure replay keeps the light
// point z: power-sampled, the same numbers land on it anywhere; drawn by the light BVH
// (VERTEX_LIGHT_BVH, vertex_light.wgsl) they would not, so z is kept and the shift's
// Jacobian takes the ratio of z's densities at the two vertices (PT_NEE_DENSITY_VARIES).
//
// Transparent layers: the walk's choices come from the bounce's numbers, so replay repeats
// them; their stop/pass probabilities are treated as part of the integrand, exact for clear
// glass and fully solid layers, an approximation for partly solid ones (docs/src/restir-pt.md,
// "Paths through glass").
#include "pt/reservoir.wgsl"
#include "common/layer_walk.wgsl"

// Whether z's light-sampling density depends on the vertex (the light BVH's does), so that
// a replayed path's NEE end enters its density and the replay Jacobian.
#ifdef VERTEX_LIGHT_BVH
const PT_NEE_DENSITY_VARIES: bool = true;
#else
const PT_NEE_DENSITY_VARIES: bool = false;
#endif

const PT_RNG_BSDF: u32 = 0u;
const PT_RNG_LIGHT: u32 = 1u;

fn pt_rng(seed: u32, bounce: u32, purpose: u32) -> u32 {
    return pcg_hash(seed ^ pcg_hash(bounce * 2u + purpose + 0x9e3779b9u));
}

// q_l p_l(ω): the density of drawing lobe `lobe` and then ω (solid angle).
fn pt_lobe_pdf(b: Brdf, n: vec3<f32>, wo: vec3<f32>, wi: vec3<f32>, lobe: u32) -> f32 {
    let n_dot_l = dot(n, wi);
    let n_dot_v = dot(n, wo);
    if n_dot_l <= 0.0 || n_dot_v <= 0.0 {
        return 0.0;
    }
    let pd = diffuse_lobe_probability(b);
    if lobe == PT_LOBE_DIFFUSE {
        return pd * n_dot_l * INV_PI;
    }
#ifdef SPECULAR
    if pd < 1.0 {
        return (1.0 - pd) * ggx_vndf_pdf(n, normalize(wo + wi), n_dot_v, b.alpha);
    }
#endif
    return 0.0;
}

// g = f_s cos · q_l p_l / p_mix at `sp` toward `wi` with lobe `lobe` (0 below either
// hemisphere); `tint` multiplies it (the segment's transmittance).
fn pt_bounce_factor(sp: ShadingPoint, wi: vec3<f32>, lobe: u32) -> vec3<f32> {
    let cos_x = dot(sp.normal, wi);
    let p_mix = brdf_pdf(sp.brdf, sp.normal, sp.wo, wi);
    if cos_x <= 0.0 || dot(sp.geo_normal, wi) <= 0.0 || !(p_mix > 0.0) {
        return vec3<f32>(0.0);
    }
    let share = pt_lobe_pdf(sp.brdf, sp.normal, sp.wo, wi, lobe) / p_mix;
    let g = eval_brdf(sp.brdf, sp.normal, sp.wo, wi) * (cos_x * share);
    return select(vec3<f32>(0.0), g, is_finite_vec3(g));
}

// Whether a vertex is rough enough for the hybrid to reconnect at: no specular lobe, or
// roughness ≥ pt_rough_threshold (α = roughness²).
fn pt_is_rough(sp: ShadingPoint) -> bool {
    return diffuse_lobe_probability(sp.brdf) >= 1.0 || sp.brdf.alpha >= params.pt.rough_threshold * params.pt.rough_threshold;
}

// Whether the hybrid reconnects the step from `a` to `b`.
fn pt_hybrid_reconnects(a: ShadingPoint, b: ShadingPoint) -> bool {
    let d = b.position - a.position;
    let min_d = params.pt.min_distance * frame.scene_scale;
    return pt_is_rough(a) && pt_is_rough(b) && dot(d, d) >= min_d * min_d;
}

// One BSDF bounce from `sp` with bounce `bounce`'s numbers: the lobe and direction drawn,
// their density, the factor g, what the ray finds (the emitter it meets first, for a BSDF
// end) and the next vertex through transparent layers.
struct PtBounce {
    ok: bool,              // a direction above both hemispheres with a density
    wi: vec3<f32>,
    lobe: u32,
    lobe_pdf: f32,         // q_l p_l(ω)
    g: vec3<f32>,
    found: FoundLight,     // the emitter found along wi (NO_LIGHT: none)
    hit: bool,             // the walk stops at a surface
    walk_weight: vec3<f32>,
    next: ShadingPoint,
}

fn pt_bounce(sp: ShadingPoint, seed: u32, bounce: u32) -> PtBounce {
    var rng = pt_rng(seed, bounce, PT_RNG_BSDF);
    var out = pt_bounce_direction(sp, &rng);
    if out.ok {
        pt_follow(sp, &out, &rng);
    }
    return out;
}

// The first half of pt_bounce: the lobe and direction drawn from `rng` (the bounce's
// numbers), their density and factor g; `ok` when the ray is to be traced.
fn pt_bounce_direction(sp: ShadingPoint, rng: ptr<function, u32>) -> PtBounce {
    var out: PtBounce;
    out.ok = false;
    out.hit = false;
    out.found.id.light = NO_LIGHT;
    out.found.transmittance = vec3<f32>(0.0);
    let u = vec3<f32>(rand_f32(rng), rand_f32(rng), rand_f32(rng));
    let bs = sample_brdf(sp.brdf, sp.normal, sp.wo, u);
    out.lobe = select(PT_LOBE_SPECULAR, PT_LOBE_DIFFUSE, u.z < diffuse_lobe_probability(sp.brdf));
    out.wi = bs.wi;
    if !(bs.pdf > 0.0) || dot(sp.normal, bs.wi) <= 0.0 || dot(sp.geo_normal, bs.wi) <= 0.0 {
        return out;
    }
    out.lobe_pdf = pt_lobe_pdf(sp.brdf, sp.normal, sp.wo, bs.wi, out.lobe);
    out.g = pt_bounce_factor(sp, bs.wi, out.lobe);
    if !(out.lobe_pdf > 0.0) || !any(out.g > vec3<f32>(0.0)) {
        return out;
    }
    out.ok = true;
    return out;
}

// Traces `bn.wi` from `sp` (the walk's choices drawn from `rng`, the bounce's numbers after
// its direction): the emitter it meets first, and the surface where the walk stops.
fn pt_follow(sp: ShadingPoint, bn: ptr<function, PtBounce>, rng: ptr<function, u32>) {
    let wi = (*bn).wi;
    let followed = follow_ray(offset_ray_origin(sp.position, sp.geo_normal), sp.position, wi, frame.light_count > 0u, rng);
    (*bn).found = followed.found;
    let walk = followed.walk;
    (*bn).walk_weight = walk.weight;
    if walk.hit.t > 0.0 && any(walk.weight > vec3<f32>(0.0)) {
        (*bn).hit = true;
        let hs = hit_surface(walk.hit.triangle, walk.hit.u, walk.hit.v, walk.origin);
        (*bn).next = hit_shading_point(hs, -wi, hit_brdf(hs), sp.depth + length(hs.position - sp.position));
        pt_last_hit = walk.hit;
    }
}

// The hit of the last pt_bounce that reached a surface (its triangle and barycentrics: what
// a reconnection vertex is stored as).
var<private> pt_last_hit: Hit;

// The end e_n by light sampling at `sp` toward z (its shadow ray traced): value, and z's
// density under light sampling.
struct PtEnd {
    value: vec3<f32>,
    density: f32,
}

fn pt_nee_end(sp: ShadingPoint, z: LightSampleId) -> PtEnd {
    var e = PtEnd(vec3<f32>(0.0), 0.0);
    if z.light == NO_LIGHT {
        return e;
    }
    let lp = light_point_at(sp, z.light, z.uv);
    let c = light_contribution(sp, lp);
    e.density = lp.source_pdf;
    if !(target_pdf(c) > 0.0) || !(lp.source_pdf > 0.0) {
        return e;
    }
    let tr = light_transmittance(sp, lp, c);
    var p_bsdf = 0.0;
    if bsdf_can_hit(lp.kind) && !tr.crossed_emitter {
        p_bsdf = brdf_pdf(sp.brdf, sp.normal, sp.wo, c.wi) * c.cos_light / c.dist2;
    }
    let v = tr.value * c.value * (lp.source_pdf / (lp.source_pdf + p_bsdf));
    e.value = select(vec3<f32>(0.0), v, is_finite_vec3(v));
    return e;
}

// The end e_n by the BSDF at `sp` along `wi` (lobe `lobe`), having found z through layers
// of transmittance `tint`: value, and z's density under that lobe (z's measure).
fn pt_bsdf_end(sp: ShadingPoint, wi: vec3<f32>, lobe: u32, z: LightSampleId, tint: vec3<f32>) -> PtEnd {
    var e = PtEnd(vec3<f32>(0.0), 0.0);
    if z.light == NO_LIGHT {
        return e;
    }
    let lp = light_point_at(sp, z.light, z.uv);
    let c = light_contribution_with(sp, lp, true, wi);
    if !(target_pdf(c) > 0.0) {
        return e;
    }
    let to_measure = c.cos_light / c.dist2;
    let p_lobe = pt_lobe_pdf(sp.brdf, sp.normal, sp.wo, wi, lobe) * to_measure;
    let p_mix = brdf_pdf(sp.brdf, sp.normal, sp.wo, wi) * to_measure;
    e.density = p_lobe;
    let v = tint * c.value * (p_lobe / (lp.source_pdf + p_mix));
    e.value = select(vec3<f32>(0.0), v, is_finite_vec3(v) && p_lobe > 0.0);
    return e;
}

// ---- the pixel's own path (pt_initial) ----

// What a path candidate carries besides its value: the record fields that depend on where
// along the walk it ends.
struct PtWalkState {
    seed: u32,
    k: u32,                 // PT_RC_NONE until the walk has passed its reconnection step
    lobes: u32,
    prefix_pdf: f32,        // Π q_l p_l over ω_1..ω_{b-1} (the density so far)
    rc_prefix_pdf: f32,     // the same over ω_1..ω_{k-1}
    suffix: vec3<f32>,      // Π of the factors after x_{k+1}'s own (its walk weight on)
    rc_hit: Hit,
    rc_out: vec3<f32>,
    rc_from_d2: f32,
    rc_from_cos: f32,
}

// The candidate record of a sub-path ending at x_n with technique `end` (end value `e`,
// prefix value `prefix`; `suffix_end`: what stands beyond x_{k+1} when x_{k+1} is x_n).
fn pt_candidate(st: PtWalkState, n: u32, end: u32, prefix: vec3<f32>, e: PtEnd, z: LightSampleId, suffix_end: vec3<f32>) -> PtReservoir {
    var c = pt_reservoir_empty();
    c.value = prefix * e.value;
    c.p_hat = luminance(c.value);
    c.seed = st.seed;
    c.packed = pt_pack(SOURCE_INITIAL, n, end, st.k, st.lobes);
    c.light = z.light;
    c.light_u = z.uv.x;
    c.light_v = z.uv.y;
    if st.k == PT_RC_NONE {
        c.replay_pdf = st.prefix_pdf * select(1.0, e.density, end == PT_END_BSDF || PT_NEE_DENSITY_VARIES);
    } else {
        c.replay_pdf = st.rc_prefix_pdf;
        c.rc_triangle = st.rc_hit.triangle;
        c.rc_u = st.rc_hit.u;
        c.rc_v = st.rc_hit.v;
        c.rc_out = oct_encode(st.rc_out);
        c.rc_from_d2 = st.rc_from_d2;
        c.rc_from_cos = st.rc_from_cos;
        c.rc_suffix = select(st.suffix * e.value, suffix_end, st.k + 1u == n);
    }
    return c;
}

// cos at a reconnection vertex toward `toward`, against its triangle's own normal (signed,
// so both sides of a shift can be required to see the same face).
fn pt_rc_cos(rc: Hit, rc_position: vec3<f32>, toward: vec3<f32>) -> f32 {
    let ng = triangle_normal(triangles[rc.triangle]);
    return dot(ng, safe_normalize(toward - rc_position, ng));
}

// Traces the pixel's path from x_1 = `first` and streams its sub-paths (NEE and BSDF ends
// at x_2 … x_max_bounces) into `r` with RIS weights p̂ / density; M = 1 (one path).
fn pt_trace_initial(first: ShadingPoint, seed: u32, r: ptr<function, PtReservoir>, ris: ptr<function, u32>) {
    let bounces = clamp(params.max_bounces, 2u, MAX_BOUNCES);
    var st: PtWalkState;
    st.seed = seed;
    st.k = PT_RC_NONE;
    st.lobes = 0u;
    st.prefix_pdf = 1.0;
    st.rc_prefix_pdf = 1.0;
    st.suffix = vec3<f32>(1.0);
    var sp = first;
    var prefix = vec3<f32>(1.0);   // Π g_b · walk_b over b < the current vertex
    for (var b = 1u; b <= bounces; b++) {
        if b >= 2u && frame.light_count > 0u {
            var lrng = pt_rng(seed, b, PT_RNG_LIGHT);
            let z = sample_light_at(sp, &lrng);
            let e = pt_nee_end(sp, z);
            if e.density > 0.0 {
                let c = pt_candidate(st, b, PT_END_NEE, prefix, e, z, vec3<f32>(1.0));
                pt_reservoir_update(r, c, c.p_hat / (st.prefix_pdf * e.density), rand_f32(ris));
            }
        }
        let bn = pt_bounce(sp, seed, b);
        if !bn.ok {
            break;
        }
        st.lobes |= bn.lobe << b;
        if st.k != PT_RC_NONE && b == st.k + 1u {
            st.rc_out = bn.wi;
        }
        if b >= 2u && bn.found.id.light != NO_LIGHT {
            let e = pt_bsdf_end(sp, bn.wi, bn.lobe, bn.found.id, bn.found.transmittance);
            if e.density > 0.0 {
                let c = pt_candidate(st, b, PT_END_BSDF, prefix, e, bn.found.id, bn.found.transmittance);
                pt_reservoir_update(r, c, c.p_hat / (st.prefix_pdf * e.density), rand_f32(ris));
            }
        }
        if b == bounces || !bn.hit {
            break;
        }
        let step = bn.g * bn.walk_weight;
        if st.k != PT_RC_NONE {
            // x_{k+1}'s own factor is re-evaluated by every shift; its walk weight is not.
            st.suffix *= select(step, bn.walk_weight, b == st.k + 1u);
        }
        prefix *= step;
        st.rc_prefix_pdf = select(st.rc_prefix_pdf, st.prefix_pdf, st.k == PT_RC_NONE);
        st.prefix_pdf *= bn.lobe_pdf;
        if st.k == PT_RC_NONE {
            let reconnect = (params.pt.shift == PT_SHIFT_RECONNECTION && b == 1u)
                || (params.pt.shift == PT_SHIFT_HYBRID && pt_hybrid_reconnects(sp, bn.next));
            if reconnect {
                st.k = b;
                st.rc_hit = pt_last_hit;
                let d = bn.next.position - sp.position;
                st.rc_from_d2 = dot(d, d);
                st.rc_from_cos = pt_rc_cos(pt_last_hit, bn.next.position, sp.position);
                st.suffix = vec3<f32>(1.0);
            }
        }
        sp = bn.next;
        if !any(prefix > vec3<f32>(0.0)) {
            break;
        }
    }
}

// ---- shifts ----

// A path moved to another pixel: its record there (value and p̂ at the new pixel, the
// densities and geometry of the new side) and |J|; jacobian 0 and `failure` when it could
// not be moved (the zero-target domain of pairwise MIS).
struct PtShifted {
    path: PtReservoir,
    jacobian: f32,
    failure: u32,
}

// The candidate step with an explicit MIS weight: w = p̂_here(T(y)) · W · m · |J|.
fn pt_merge_mis(r: ptr<function, PtReservoir>, other: PtReservoir, moved: PtShifted, mis_weight: f32, u: f32) -> bool {
    if pt_reservoir_is_null(other) {
        return false;
    }
    let w = moved.path.p_hat * other.weight * (sanitize(mis_weight) * sanitize(moved.jacobian));
    var sample = moved.path;
    sample.jacobian = moved.jacobian;
    return pt_reservoir_update(r, sample, w, u);
}

fn pt_shift_failed(r: PtReservoir, failure: u32) -> PtShifted {
    var out = r;
    out.value = vec3<f32>(0.0);
    out.p_hat = 0.0;
    return PtShifted(out, 0.0, failure);
}

// The two shifts of a pairwise MIS pair (temporal and spatial reuse): `other`'s path moved
// here (to `here`), and this pixel's path `own` moved to the other pixel (to `there`: could
// it have found it?). A null path is not shifted (a failed shift, Jacobian 0). Both go
// through one pt_shift call site, the largest code of a reuse pass: each call site is a
// copy of it (docs/src/compile-time.md).
struct PtShiftPair {
    moved: PtShifted,  // other → here
    back: PtShifted,   // own → there
}

fn pt_shift_pair(other: PtReservoir, here: ShadingPoint, own: PtReservoir, there: ShadingPoint) -> PtShiftPair {
    var out = PtShiftPair(pt_shift_failed(other, PT_FAIL_NONE), pt_shift_failed(own, PT_FAIL_NONE));
    // Bit 0: other → here; bit 1: own → there.
    var shifts = select(0u, 1u, !pt_reservoir_is_null(other)) | select(0u, 2u, !pt_reservoir_is_null(own));
    while shifts != 0u {
        let back = (shifts & 1u) == 0u;
        shifts &= shifts - 1u;
        var path = other;
        var to = here;
        if back {
            path = own;
            to = there;
        }
        let shifted = pt_shift(path, to);
        if back {
            out.back = shifted;
        } else {
            out.moved = shifted;
        }
    }
    return out;
}

// `r`, a path found where its record says, moved to the pixel whose visible point is `to`.
fn pt_shift(r: PtReservoir, to: ShadingPoint) -> PtShifted {
    let n = pt_n(r);
    let k = pt_k(r);
    let end = pt_end(r);
    let z = pt_light(r);
    let hybrid = params.pt.shift == PT_SHIFT_HYBRID;
    if n < 2u || n > MAX_BOUNCES || (k != PT_RC_NONE && k + 1u > n) {
        return pt_shift_failed(r, PT_FAIL_UNDEFINED);
    }
    let replayed = select(k - 1u, n - 1u, k == PT_RC_NONE);
    // A pure replay with a BSDF end draws one bounce more, the one that finds the light:
    // one pt_bounce call site for all of them (each is compiled as a copy of the tracing:
    // docs/src/compile-time.md).
    let bounces = select(replayed, n, k == PT_RC_NONE && end != PT_END_NEE);
    var sp = to;
    var value = vec3<f32>(1.0);
    var density = 1.0;
    var lobes = 0u;
    var end_bounce: PtBounce;
    for (var b = 1u; b <= bounces; b++) {
        let bn = pt_bounce(sp, r.seed, b);
        if b > replayed {
            end_bounce = bn;
            break;
        }
        if !bn.ok || !bn.hit {
            return pt_shift_failed(r, PT_FAIL_REPLAY);
        }
        // Hybrid: a step the rule would reconnect must not come before k (bijection).
        if hybrid && pt_hybrid_reconnects(sp, bn.next) {
            return pt_shift_failed(r, PT_FAIL_ELSEWHERE);
        }
        value *= bn.g * bn.walk_weight;
        density *= bn.lobe_pdf;
        lobes |= bn.lobe << b;
        sp = bn.next;
    }
    var out = r;
    var jacobian = 1.0;
    if k == PT_RC_NONE {
        // Pure replay: the end from y_n, with the same numbers (NEE: the same z).
        var e: PtEnd;
        if end == PT_END_NEE {
            e = pt_nee_end(sp, z);
            if PT_NEE_DENSITY_VARIES {
                if !(e.density > 0.0) {
                    return pt_shift_failed(r, PT_FAIL_ZERO);
                }
                density *= e.density;
            }
        } else {
            let bn = end_bounce;
            if !bn.ok || bn.found.id.light == NO_LIGHT {
                return pt_shift_failed(r, PT_FAIL_REPLAY);
            }
            e = pt_bsdf_end(sp, bn.wi, bn.lobe, bn.found.id, bn.found.transmittance);
            lobes |= bn.lobe << n;
            density *= e.density;
            out.light = bn.found.id.light;
            out.light_u = bn.found.id.uv.x;
            out.light_v = bn.found.id.uv.y;
        }
        value *= e.value;
        jacobian = r.replay_pdf / density;
        out.replay_pdf = density;
    } else {
        // Reconnect y_k → x_{k+1}.
        let rc = Hit(1.0, r.rc_triangle, r.rc_u, r.rc_v);
        let hs = hit_surface(rc.triangle, rc.u, rc.v, sp.position);
        let d = hs.position - sp.position;
        let d2 = dot(d, d);
        let cos_to = pt_rc_cos(rc, hs.position, sp.position);
        let usable = reconnection_distance_in_range(d2) && reconnection_distance_in_range(r.rc_from_d2)
            && abs(cos_to) >= RECONNECTION_MIN_COS && abs(r.rc_from_cos) >= RECONNECTION_MIN_COS
            && (cos_to > 0.0) == (r.rc_from_cos > 0.0);
        if !usable {
            return pt_shift_failed(r, PT_FAIL_UNDEFINED);
        }
        let wi = d * inverseSqrt(d2);
        let lobes_x = pt_lobes(r);
        let g_k = pt_bounce_factor(sp, wi, pt_lobe(lobes_x, k));
        if !any(g_k > vec3<f32>(0.0)) {
            return pt_shift_failed(r, PT_FAIL_ZERO);
        }
        let tr = trace_transmittance(segment_ray(sp.position, sp.geo_normal, hs.position, hs.geo_normal));
        if !any(tr.value > vec3<f32>(0.0)) {
            return pt_shift_failed(r, PT_FAIL_OCCLUDED);
        }
        let rc_sp = hit_shading_point(hs, -wi, hit_brdf(hs), 0.0);
        if hybrid && !pt_hybrid_reconnects(sp, rc_sp) {
            return pt_shift_failed(r, PT_FAIL_ELSEWHERE);
        }
        value *= g_k * tr.value;
        lobes |= pt_lobe(lobes_x, k) << k;
        let out_dir = oct_decode(r.rc_out);
        if k + 1u < n {
            value *= pt_bounce_factor(rc_sp, out_dir, pt_lobe(lobes_x, k + 1u)) * r.rc_suffix;
        } else if end == PT_END_NEE {
            value *= pt_nee_end(rc_sp, z).value;
        } else {
            value *= pt_bsdf_end(rc_sp, out_dir, pt_lobe(lobes_x, n), z, r.rc_suffix).value;
        }
        // Lobes past the reconnection are the path's own.
        lobes |= lobes_x & ~((2u << k) - 1u);
        let j_geo = (abs(cos_to) * r.rc_from_d2) / (abs(r.rc_from_cos) * d2);
        jacobian = (r.replay_pdf / density) * j_geo;
        out.replay_pdf = density;
        out.rc_from_d2 = d2;
        out.rc_from_cos = cos_to;
    }
#ifdef PLANTED_PT_NO_JACOBIAN
    // Test-only planted errors (render/tests/restir_pt.rs): reuse as if |J| were 1, or
    // with |J| the wrong way round.
    jacobian = 1.0;
#endif
#ifdef PLANTED_PT_INVERTED_JACOBIAN
    jacobian = 1.0 / jacobian;
#endif
    if params.pt.jacobian_clamp > 0.0 && jacobian > 0.0 {
        // The biased option (off by default): a wrong change of measure, bounded fireflies.
        jacobian = clamp(jacobian, 1.0 / params.pt.jacobian_clamp, params.pt.jacobian_clamp);
    }
    out.value = value;
    out.p_hat = luminance(value);
    out.packed = pt_pack(pt_source(r), n, end, k, lobes);
    if !is_positive_finite(jacobian) || !is_finite_vec3(value) {
        return pt_shift_failed(r, PT_FAIL_UNDEFINED);
    }
    if !(out.p_hat > 0.0) {
        return PtShifted(out, jacobian, PT_FAIL_ZERO);
    }
    return PtShifted(out, jacobian, PT_FAIL_NONE);
}
