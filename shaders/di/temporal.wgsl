// Temporal reuse (docs/src/temporal-reuse.md): reproject the current hit into the previous frame,
// validate the previous surface and reservoir (every failed check sets its own bit of the
// rejection mask), re-evaluate the target here, and merge the previous sample with weight
// p̂(x, y_prev) · W_prev · min(M_prev, M_cap) (1/M) or a pairwise MIS weight (unbiased).
// Under pairwise MIS only the G-buffer checks drop the history (reuse.wgsl,
// rejecting_checks); the sample checks are counted and the history stays a domain.
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"
#include "common/reuse.wgsl"

@group(2) @binding(0) var<storage, read> surfaces: array<Surface>;
@group(2) @binding(1) var<storage, read> prev_surfaces: array<Surface>;
@group(2) @binding(2) var<storage, read> reservoirs_in: array<Reservoir>;
@group(2) @binding(3) var<storage, read> prev_reservoirs: array<Reservoir>;
@group(2) @binding(4) var<storage, read_write> reservoirs_out: array<Reservoir>;
@group(2) @binding(5) var<storage, read_write> debug: array<PixelDebug>;

struct TemporalCandidate {
    mask: u32,             // REJECT_* bits of the failed checks
    reservoir: Reservoir,
    target_here: f32,      // p̂(x, y_prev), re-evaluated at the current point
    target_there: f32,     // p̂(x_prev, y_prev), the other side of the target-ratio window
    prev_surface: Surface,
}

fn validate_previous(pixel: vec2<i32>, s: Surface, sp: ShadingPoint) -> TemporalCandidate {
    var c = TemporalCandidate(0u, reservoir_empty(), 0.0, 0.0, Surface());
    let read = reuse_candidate(pixel, s, true);
    if read.mask != 0u {
        c.mask |= read.mask;
        return c;
    }
    let prev_index = read.index;
    let ps = prev_surfaces[prev_index];
    c.prev_surface = ps;
    c.mask |= candidate_surface_checks(s, ps, true, false);
    if (c.mask & REJECT_SURFACE) != 0u {
        return c;
    }
    let prev = checked_reservoir(prev_reservoirs[prev_index], PASS_TEMPORAL);
    c.reservoir = prev;
    let prev_null = reservoir_is_null(prev);
    if prev_null && check_enabled(REJECT_RESERVOIR) {
        c.mask |= REJECT_RESERVOIR;
    }
#ifdef ANIMATION
    // Light identity is the table slot (fixed for the animation); a slot with select_pdf 0
    // is a light that is off now. Its sample cannot be reused, whatever the checks say:
    // not a switchable heuristic, so not behind check_enabled.
    // Under pairwise MIS the history still takes part: its sample's target here stays 0.
    if !prev_null && (prev.light >= arrayLength(&lights) || lights[prev.light].select_pdf <= 0.0) {
        c.mask |= REJECT_LIGHT_GONE;
        return c;
    }
#endif
    c.target_here = target_at(sp, prev.light, prev.uv);
    if c.target_here <= 0.0 && check_enabled(REJECT_TARGET) {
        c.mask |= REJECT_TARGET;
    }
    c.target_there = window_target_previous(shading_point_from_surface(ps, frame.prev_camera_position), prev);
    if !prev_null && check_enabled(REJECT_TARGET_RATIO) && !target_ratio_in_window(c.target_here, c.target_there) {
        c.mask |= REJECT_TARGET_RATIO;
    }
    return c;
}

// The target-ratio window compares p̂ here with p̂ there, both *unshadowed*, for either
// sample: then whether the history takes part at a sample y is a function of y alone and the
// pairwise weights still sum to one. The stored p̂ of a reservoir is p̂·V; in an opaque scene
// V is 1 wherever p̂·V > 0, so the stored value is the unshadowed one and serves as is.
// Through glass V is a tint in (0, 1): comparing p̂ with p̂·V made the window depend on
// which side the sample came from (−2.9 % on builtin:lamps with grey glass, temporal only;
// PLANTED_WINDOW_ON_STORED_TARGETS keeps that for its test).
fn window_target_previous(prev_sp: ShadingPoint, prev: Reservoir) -> f32 {
#ifdef TRANSPARENCY
#ifndef PLANTED_WINDOW_ON_STORED_TARGETS
    if prev.light != NO_LIGHT {
        return target_pdf(light_contribution(prev_sp, light_point_in_frame(prev.light, prev.uv, previous_lights())));
    }
#endif
#endif
    return prev.p_hat;
}

// Whether the previous pixel's targets use last frame's lights (animated scenes).
fn previous_lights() -> bool {
#ifdef ANIMATION
    return (params.flags & PARAM_FLAG_PREVIOUS_LIGHTS) != 0u;
#else
    return false;
#endif
}

// Which frame's geometry the previous pixel's visibility is traced against: last frame's
// (`previous_geometry`, animated scenes) or, as a shortcut, this frame's. A moving occluder
// makes the two differ: with this frame's the previous pixel's domain is credited with
// samples it could not see (moving-occluder 2 % dark, docs/src/measured/unbiased-reuse.md).
fn previous_geometry() -> u32 {
#ifdef ANIMATION
    if (params.flags & PARAM_FLAG_PREVIOUS_GEOMETRY) != 0u {
        return GEOMETRY_PREVIOUS;
    }
#endif
    return GEOMETRY_CURRENT;
}

fn window_target_here(sp: ShadingPoint, current: Reservoir) -> f32 {
#ifdef TRANSPARENCY
#ifndef PLANTED_WINDOW_ON_STORED_TARGETS
    if current.light != NO_LIGHT {
        return target_at(sp, current.light, current.uv);
    }
#endif
#endif
    return current.p_hat;
}

// Pairwise MIS of this pixel's initial reservoir (canonical) and the history, which is a
// domain whatever its sample holds: a null sample, a target of 0 here or a light that went
// off contributes nothing, and its confidence m_prev still counts in c_total. Every term
// uses the same targets T_here = p̂·V here and T_prev = p̂·V at the previous pixel (V only
// with mis_visibility), and the target-ratio clamp is a window on p̂_here / p̂_prev
// (unshadowed, window_target_previous) applied to both samples alike: outside it the
// history's weight is 0 and the canonical keeps its share, so the weights still sum to one
// (unbiased; a rejection of the history sample alone is not). `rays` counts the shadow rays.
// `visibility_here` receives V of the history's sample here where it is traced.
fn merge_pairwise(sp: ShadingPoint, current: Reservoir, cand: TemporalCandidate, m_prev: f32, temporal_source: u32, u_current: f32, u_prev: f32, rays: ptr<function, u32>, visibility_here: ptr<function, f32>) -> Reservoir {
    let prev = cand.reservoir;
    let c_total = current.m + m_prev;
    let prev_sp = shading_point_from_surface(cand.prev_surface, frame.prev_camera_position);
    let previous = previous_lights();

    // The history's sample y_p: T_here(y_p) and its weight. T_prev(y_p) is the stored p̂.
    var target_here = cand.target_here;
    if !target_ratio_in_window(target_here, cand.target_there) {
        target_here = 0.0;
    }

    // The canonical sample y_c at the previous pixel: the previous surface and, under
    // animation, last frame's lights (a light switched on since then has p̂ 0 there, so
    // the canonical sample keeps its full weight). Current lights there (previous_lights
    // off) under-weight newly lit samples: a dark lag. Its visibility there is traced
    // against last frame's geometry (previous_geometry).
    var prev_at_current = 0.0;
    if current.light != NO_LIGHT {
        prev_at_current = target_pdf(light_contribution(prev_sp, light_point_in_frame(current.light, current.uv, previous)));
    }
    if !target_ratio_in_window(window_target_here(sp, current), prev_at_current) {
        prev_at_current = 0.0;
    }

    // The two visibilities these terms need, traced at one call site (bit 0: y_p here,
    // bit 1: y_c at the previous pixel); a target of 0 needs no ray.
    var rays_needed = 0u;
    if mis_visibility() {
        rays_needed = select(0u, 1u, target_here > 0.0) | select(0u, 2u, prev_at_current > 0.0);
    }
    while rays_needed != 0u {
        let at_previous = (rays_needed & 1u) == 0u;
        rays_needed &= rays_needed - 1u;
        var viewer = sp;
        var sample = prev;
        var in_previous_frame = false;
        var geometry = GEOMETRY_CURRENT;
        if at_previous {
            viewer = prev_sp;
            sample = current;
            in_previous_frame = previous;
            geometry = previous_geometry();
        }
        let v = sample_visibility(viewer, sample.light, sample.uv, in_previous_frame, geometry, rays);
        if at_previous {
            prev_at_current *= v;
        } else {
            target_here *= v;
            *visibility_here = v;
        }
    }
    let m_temporal = pairwise_mis_noncanonical(c_total, current.m, m_prev, prev.p_hat, target_here);
    let m_current = confidence_share(current.m, c_total)
        + pairwise_mis_canonical_term(c_total, current.m, m_prev, current.p_hat, prev_at_current);

    var r = reservoir_empty();
    reservoir_merge_mis(&r, current, current.p_hat, m_current, current.source, u_current);
    reservoir_merge_mis(&r, prev, target_here, m_temporal, temporal_source, u_prev);
    reservoir_finalize(&r, 1.0);
    r.m = c_total;
    return r;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !pixel_in_frame(id) {
        return;
    }
    let index = pixel_index(id.xy);
    let s = surfaces[index];
    let current = reservoirs_in[index];
    var d = debug[index];
    if !surface_is_valid(s) {
        reservoirs_out[index] = current;
        return;
    }
    let sp = shading_point_from_surface(s, frame.camera_position);
    var rng = rng_seed(id.xy, STREAM_TEMPORAL);

    var read = temporal_first_read(s);
    // Gradient only: temporal reuse is off, but the denoiser's temporal gradients want
    // the history's sample shaded here (docs/src/denoiser.md, "Temporal gradients"). The
    // candidate is validated and merged as usual, so its visibility is traced alike, and
    // the merge is dropped; nothing is counted as reuse.
    let merging = (params.flags & PARAM_FLAG_GRADIENT_ONLY) == 0u;
    var cand: TemporalCandidate;
    loop {
        cand = validate_previous(read.pixel, s, sp);
        if !temporal_retry(&read, rejecting_checks(cand.mask)) {
            break;
        }
        if merging {
            count_stat(STAT_FALLBACK_TRIED);
        }
        d.flags |= DEBUG_FLAG_FALLBACK_TRIED;
    }
    if merging {
        if temporal_fell_back(read, rejecting_checks(cand.mask)) {
            count_stat(STAT_FALLBACK_USED);
            d.flags |= DEBUG_FLAG_FALLBACK_USED;
        }
        count_rejections(cand.mask, STAT_TEMPORAL_REJECT);
        d.temporal_mask = cand.mask;
    }

    var r = current;
    var rays = 0u;
    var visibility_here = 1.0;
    if rejecting_checks(cand.mask) == 0u {
        let m_prev = min(cand.reservoir.m, params.di.m_cap);
        if merging {
            count_stat(STAT_TEMPORAL_ACCEPTED);
            d.flags |= DEBUG_FLAG_TEMPORAL_MERGED;
            if cand.reservoir.m > params.di.m_cap {
                d.flags |= DEBUG_FLAG_TEMPORAL_CAP;
                count_stat(STAT_TEMPORAL_CAP);
            }
        }
        let u_current = rand_f32(&rng);
        let u_prev = rand_f32(&rng);
        // A history sample that survives is one frame older.
        let temporal_source = source_with_age(SOURCE_TEMPORAL, reservoir_age(cand.reservoir) + 1u);
        if pairwise_mis() {
            r = merge_pairwise(sp, current, cand, m_prev, temporal_source, u_current, u_prev, &rays, &visibility_here);
        } else {
            r = reservoir_empty();
            reservoir_merge(&r, current, current.p_hat, current.m, current.source, u_current);
            reservoir_merge(&r, cand.reservoir, cand.target_here, m_prev, temporal_source, u_prev);
            reservoir_finalize(&r, r.m);
        }
    }
    // The gradient sample: the history's sample as last frame shaded it (p̂·V there, its
    // W) and as it shades here now, with this frame's lights and occluders. A light gone
    // leaves its target here 0.
    if (cand.mask & REJECT_SURFACE_CHECKS) == 0u && !reservoir_is_null(cand.reservoir) {
        let w = cand.reservoir.weight;
        d.gradient = vec2<f32>(cand.reservoir.p_hat * w, cand.target_here * visibility_here * w);
    }
    if !merging {
        r = current;
    }
    if r.m > params.di.m_cap {
        r.m = params.di.m_cap;
        d.flags |= DEBUG_FLAG_TEMPORAL_CAP;
    }
    if reservoir_is_corrupt(r) {
        count_stat(STAT_NONFINITE + PASS_TEMPORAL);
        r = reservoir_empty();
        r.m = 1.0;
    }
    add_stat(STAT_SHADOW_RAYS + PASS_TEMPORAL, rays);
    reservoirs_out[index] = r;
    d.source = reservoir_source(r);
    d.m_temporal = r.m;
    debug[index] = d;
}
