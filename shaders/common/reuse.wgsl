// Checks shared by temporal and spatial reuse (docs/src/temporal-reuse.md, "Validation";
// docs/src/spatial-reuse.md, "Validation").
#include "common/frame_bindings.wgsl"
#include "common/stats_bindings.wgsl"
#include "common/shading_point.wgsl"
#include "common/reservoir.wgsl"

// A reservoir read from another pixel or frame, or null (counted against `pass_id`) when
// its weights are not finite and non-negative: never propagate a corrupt one.
fn checked_reservoir(r: Reservoir, pass_id: u32) -> Reservoir {
    if reservoir_is_corrupt(r) {
        count_stat(STAT_NONFINITE + pass_id);
        return reservoir_empty();
    }
    return r;
}

fn check_enabled(bit: u32) -> bool {
    return (params.checks & bit) != 0u;
}

// Material, normal and position/depth agreement between two valid surfaces. Temporal reuse
// compares world positions (the same point should come back); spatial reuse compares view
// depths (neighbours are different points by design). Both thresholds are relative to the
// current view depth, so they follow the scene's scale.
fn surface_dissimilarity(s: Surface, other: Surface, same_point: bool) -> u32 {
    var mask = 0u;
    if check_enabled(REJECT_MATERIAL) && other.material != s.material {
        mask |= REJECT_MATERIAL;
    }
    if check_enabled(REJECT_NORMAL) && dot(oct_decode(other.normal), oct_decode(s.normal)) < params.normal_threshold {
        mask |= REJECT_NORMAL;
    }
    let distance = select(abs(other.depth - s.depth), length(other.position - s.position), same_point);
    if check_enabled(REJECT_DEPTH) && !(distance <= params.depth_threshold * s.depth) {
        mask |= REJECT_DEPTH;
    }
    return mask;
}

// One counter per set bit, at base + bit index.
fn count_rejections(mask: u32, base: u32) {
    var m = mask;
    while m != 0u {
        let bit = firstTrailingBit(m);
        count_stat(base + bit);
        m &= m - 1u;
    }
}

// Solari-style permutation: mirror the pixel inside a 4×4 block shifted by a per-frame
// offset, so neighbouring pixels do not inherit correlated histories.
// Temporal reuse of DI and GI use the same permutation.
// The previous pixel temporal reuse reads first: the reprojected one, through this frame's
// 4×4 permutation when it is on (a read that then fails validation retries the plain
// reprojection: permuted reads fail at object edges, Solari #21722). Under pairwise MIS
// only the G-buffer decides which pixel is read.
struct TemporalRead {
    reprojected: vec2<i32>,
    pixel: vec2<i32>,
    permuted: bool,
}

fn temporal_first_read(s: Surface) -> TemporalRead {
    let reprojected = vec2<i32>(floor(s.motion));
    let permuted = (params.flags & PARAM_FLAG_PERMUTATION) != 0u;
    return TemporalRead(reprojected, select(reprojected, permute_pixel(reprojected), permuted), permuted);
}

// After a try whose rejecting checks are `mask`: true when the permuted read failed, and
// the next try reads the plain reprojection. The passes loop over one call site of their
// validation (the driver compiles a copy per call: docs/src/compile-time.md):
//     var read = temporal_first_read(s);
//     loop { c = validate(read.pixel, …); if !temporal_retry(&read, mask(c)) { break; } … }
fn temporal_retry(read: ptr<function, TemporalRead>, mask: u32) -> bool {
    if !(*read).permuted || mask == 0u {
        return false;
    }
    (*read).permuted = false;
    (*read).pixel = (*read).reprojected;
    return true;
}

// Whether the history passed on the plain reprojection after the permuted read failed.
fn temporal_fell_back(read: TemporalRead, mask: u32) -> bool {
    return !read.permuted && (params.flags & PARAM_FLAG_PERMUTATION) != 0u && mask == 0u;
}

fn permute_pixel(p: vec2<i32>) -> vec2<i32> {
    let r = pcg_hash(frame.frame_index ^ frame.seed);
    let offset = vec2<i32>(i32(r & 3u), i32((r >> 2u) & 3u));
    return ((p + offset) ^ vec2<i32>(3)) - offset;
}

// A spatial neighbour's pixel offset, uniform in the disk of `radius` pixels (u uniform in
// [0, 1)²), never the pixel itself. DI and GI spatial reuse share it.
fn disk_neighbour_offset(u: vec2<f32>, radius: f32) -> vec2<i32> {
    let r = radius * sqrt(u.x);
    let angle = 2.0 * PI * u.y;
    var offset = vec2<i32>(round(r * vec2<f32>(cos(angle), sin(angle))));
    if all(offset == vec2<i32>(0)) {
        offset = vec2<i32>(1, 0);
    }
    return offset;
}

// The G-buffer checks of a reuse candidate, one validation for the six reuse passes (DI,
// GI and PT, temporal and spatial), with the same switches (`check_*`) and the same
// rejection bits (docs/src/temporal-reuse.md, "Validation"). Whether a candidate takes part depends on these
// alone, never on its sample (the rule of unbiased reuse).
//
// First where it is: `pixel` (a reprojected previous pixel when `temporal`, else a spatial
// neighbour) fails REJECT_OFFSCREEN when it lies outside the image, or (temporal) the point
// was behind the previous camera; with that check off, the nearest pixel inside is read.
struct ReuseCandidate {
    mask: u32,   // REJECT_* bits of the failed checks
    index: u32,  // the pixel to read when `mask` is 0
}

fn reuse_candidate(pixel: vec2<i32>, s: Surface, temporal: bool) -> ReuseCandidate {
    let size = vec2<i32>(frame.size);
    var p = pixel;
    if any(p < vec2<i32>(0)) || any(p >= size) || (temporal && s.motion.x <= NO_MOTION) {
        if check_enabled(REJECT_OFFSCREEN) {
            return ReuseCandidate(REJECT_OFFSCREEN, 0u);
        }
        p = clamp(p, vec2<i32>(0), size - 1);
    }
    return ReuseCandidate(0u, pixel_index(vec2<u32>(p)));
}

// Then what it saw (`other`, read by the caller from its pass's buffer: WGSL passes no
// storage pointers): REJECT_SURFACE when it saw no surface or (temporal) the history was
// invalidated, else the material, normal and position/depth checks. The one meant
// difference: GI and PT `need_surface` (their samples are reconnected or shifted from the
// candidate's visible point, so without one there is nothing to reuse whatever
// check_surface says); DI's light samples need none.
fn candidate_surface_checks(s: Surface, other: Surface, temporal: bool, need_surface: bool) -> u32 {
    let valid = surface_is_valid(other) && (!temporal || frame.history_valid != 0u);
    if !valid {
        return select(0u, REJECT_SURFACE, check_enabled(REJECT_SURFACE) || need_surface);
    }
    return surface_dissimilarity(s, other, temporal);
}

fn pairwise_mis() -> bool {
    return (params.flags & PARAM_FLAG_PAIRWISE) != 0u;
}

// The failed checks that drop a temporal or spatial candidate. Under 1/M: every enabled check.
// Under pairwise MIS: the G-buffer checks only (REJECT_SURFACE_CHECKS). Whether a candidate takes
// part may not depend on its sample (docs/src/mis-and-bias.md, "The two rules of unbiased reuse";
// the ReSTIR course notes' rule): the canonical sample's weight assumes the candidate's domain is
// there, so dropping it for a null sample, a target of 0 here or a light gone made the image too
// bright by the canonical share it lost (+4.5 % at M cap 100, +41 % after a switch-off). Such a
// candidate stays in the MIS and contributes what its target says: nothing.
fn rejecting_checks(mask: u32) -> u32 {
#ifndef PLANTED_SAMPLE_REJECTION
    if pairwise_mis() {
        return mask & REJECT_SURFACE_CHECKS;
    }
#endif
    return mask;
}

// Visibility in every pairwise MIS term (`mis_visibility`): the target is p̂·V at every
// pixel, so a sample is reused only where it is visible and each domain's weight knows
// which samples that domain can produce. Without shadows V is 1 everywhere.
fn mis_visibility() -> bool {
#ifdef SHADOWS
    return (params.flags & PARAM_FLAG_MIS_VISIBILITY) != 0u;
#else
    return false;
#endif
}

// Whether t_here / t_there lies in [1/clamp, clamp] (the target-ratio clamp; true when it
// is off). A zero on either side is outside: the two targets do not agree at all.
fn target_ratio_in_window(t_here: f32, t_there: f32) -> bool {
    let k = params.di.target_ratio_clamp;
    if k <= 0.0 {
        return true;
    }
    if !(t_here > 0.0 && t_there > 0.0) {
        return false;
    }
    return t_here <= k * t_there && t_here * k >= t_there;
}

// One shadow ray from sp to a stored light sample: this frame's light, or (`previous`, for
// animated scenes) the light as it was last frame, traced against `geometry`'s frame (the
// previous pixel's canonical term uses last frame's: previous_geometry). `rays` counts
// what was traced. The target factor V (light_visibility): 0 or 1, or between through glass.
fn sample_visibility(sp: ShadingPoint, light: u32, uv: vec2<f32>, previous: bool, geometry: u32, rays: ptr<function, u32>) -> f32 {
    let lp = light_point_in_frame(light, uv, previous);
    *rays += 1u;
    return light_visibility_in(sp, lp, light_contribution(sp, lp), geometry);
}
