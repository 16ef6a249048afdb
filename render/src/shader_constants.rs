//! Constants both sides need (bit masks, counter indices, enum values) that belong to no one
//! technique: validation, sources, counters, streams and limits, views. Each technique's own
//! are in its folder (`di/constants.rs`, `gi/constants.rs`, `pt/constants.rs`,
//! `denoise/constants.rs`). They are defined once and written into every WGSL module as a
//! generated prelude (`shader_source::wgsl_prelude`), so the host and the shaders cannot
//! drift apart.

wgsl_constants! {
    fn rejection_bits;
    /// Validation checks; the same bits form the temporal and spatial rejection masks
    /// (docs/src/temporal-reuse.md, "Validation"). Bit order is the order of the rejection-view
    /// legend.
    pub const REJECT_OFFSCREEN: u32 = 1 << 0;
    pub const REJECT_SURFACE: u32 = 1 << 1;
    pub const REJECT_MATERIAL: u32 = 1 << 2;
    pub const REJECT_NORMAL: u32 = 1 << 3;
    pub const REJECT_DEPTH: u32 = 1 << 4;
    pub const REJECT_RESERVOIR: u32 = 1 << 5;
    pub const REJECT_TARGET: u32 = 1 << 6;
    pub const REJECT_TARGET_RATIO: u32 = 1 << 7;
    /// The stored sample's light is off or gone (dynamic scenes): never reusable, so this one
    /// is not a switchable check.
    pub const REJECT_LIGHT_GONE: u32 = 1 << 8;
    pub const REJECT_REASON_COUNT: usize = 9;
    /// The first six bits (the surface checks and reservoir null) mean the same in DI's and
    /// GI's rejection masks, and are painted alike (`check_color`).
    pub const SHARED_REJECT_CHECKS: u32 = 6;
}
/// Every temporal rejection reason (the rejection view's default reason mask; its
/// spatial part is a count of rejected neighbours, not a mask).
pub const REJECT_TEMPORAL_REASONS: u32 = (1 << REJECT_REASON_COUNT) - 1;
wgsl_constants! {
    fn surface_checks;
    /// The checks that read the G-buffer only (the candidate's surface, never its sample). Under
    /// pairwise MIS only these decide whether a temporal or spatial candidate takes part
    /// (docs/src/mis-and-bias.md, "The two rules of unbiased reuse"); the others (reservoir null,
    /// target 0, target ratio, light gone) look at the sample and are counted, not acted on: the
    /// candidate stays in the MIS as a domain.
    pub const REJECT_SURFACE_CHECKS: u32 =
        REJECT_OFFSCREEN | REJECT_SURFACE | REJECT_MATERIAL | REJECT_NORMAL | REJECT_DEPTH;
}

/// Human names of the rejection bits, in bit order (stats JSON keys and UI legend).
pub const REJECT_REASON_NAMES: [&str; REJECT_REASON_COUNT] = [
    "offscreen",
    "surface_invalid",
    "material",
    "normal",
    "depth",
    "reservoir_null",
    "target_zero",
    "target_ratio",
    "light_gone",
];

wgsl_constants! {
    fn sources;
    /// Which stage's candidate survived in a pixel.
    pub const SOURCE_NULL: u32 = 0;
    pub const SOURCE_INITIAL: u32 = 1;
    pub const SOURCE_TEMPORAL: u32 = 2;
    pub const SOURCE_SPATIAL: u32 = 3;
}
pub const SOURCE_NAMES: [&str; 4] = ["null", "initial", "temporal", "spatial"];
wgsl_constants! {
    fn proposers;
    /// Which strategy proposed a pixel's initial survivor (the `proposer` view;
    /// docs/src/light-samplers.md): a BSDF ray, or the light sampler — its power table (also
    /// ReGIR outside its grid and the BVH's lights without a position), a tile, a ReGIR slot
    /// or the BVH walk.
    pub const PROPOSER_NONE: u32 = 0;
    pub const PROPOSER_BSDF: u32 = 1;
    pub const PROPOSER_POWER: u32 = 2;
    pub const PROPOSER_TILE: u32 = 3;
    pub const PROPOSER_REGIR: u32 = 4;
    pub const PROPOSER_BVH: u32 = 5;
}
pub const PROPOSER_NAMES: [&str; 6] = [
    "none",
    "BSDF ray",
    "power table",
    "light tile",
    "ReGIR slot",
    "light BVH",
];
wgsl_constants! {
    fn shared_flags_and_passes;
    /// `Params.flags` bits every technique's shading reads; each technique's own bits are
    /// in its folder (`di::constants`, `gi::constants`, `denoise::constants`).
    pub const PARAM_FLAG_JITTER: u32 = 1 << 2;

    /// Passes that count non-finite values (a GPU-side guard; docs/src/ris.md, "Conventions").
    pub const PASS_GBUFFER: u32 = 0;
    pub const PASS_INITIAL: u32 = 1;
    pub const PASS_TEMPORAL: u32 = 2;
    pub const PASS_SPATIAL: u32 = 3;
    pub const PASS_SHADE: u32 = 4;
    pub const PASS_REFERENCE: u32 = 5;
    /// The MCMC mutation of DI's samples (di/mutation.wgsl; docs/src/mcmc-mutation.md).
    pub const PASS_MUTATION: u32 = 6;
}
pub const GUARDED_PASS_NAMES: [&str; 7] = [
    "gbuffer",
    "initial",
    "temporal",
    "spatial",
    "shade",
    "reference",
    "mutation",
];

wgsl_constants! {
    fn counters;
    /// Indices into the per-frame atomic counter buffer, each block right after the one
    /// before it (nothing is numbered by hand): DI's temporal rejections by reason, the
    /// survivors' sources, the M caps and permutation fallbacks, non-finite values per DI
    /// pass, surface pixels, merged temporal candidates, boiling drops, DI's spatial
    /// rejections by reason.
    pub const STAT_TEMPORAL_REJECT: u32 = 0;
    pub const STAT_SOURCE: u32 = STAT_TEMPORAL_REJECT + REJECT_REASON_COUNT as u32;
    pub const STAT_TEMPORAL_CAP: u32 = STAT_SOURCE + SOURCE_NAMES.len() as u32;
    pub const STAT_SPATIAL_CAP: u32 = STAT_TEMPORAL_CAP + 1;
    pub const STAT_FALLBACK_TRIED: u32 = STAT_SPATIAL_CAP + 1;
    pub const STAT_FALLBACK_USED: u32 = STAT_FALLBACK_TRIED + 1;
    pub const STAT_NONFINITE: u32 = STAT_FALLBACK_USED + 1;
    pub const STAT_SURFACE_PIXELS: u32 = STAT_NONFINITE + GUARDED_PASS_NAMES.len() as u32;
    pub const STAT_TEMPORAL_ACCEPTED: u32 = STAT_SURFACE_PIXELS + 1;
    pub const STAT_BOILING_DROPPED: u32 = STAT_TEMPORAL_ACCEPTED + 1;
    pub const STAT_SPATIAL_REJECT: u32 = STAT_BOILING_DROPPED + 1;
    /// The indirect technique's counters follow DI's (ReSTIR GI's or PT's, whichever ran: they
    /// never run together): non-finite values per indirect pass, then the temporal and spatial
    /// rejections (GI_REJECT_REASON_COUNT each: DI's reasons, then GI's reconnection ones),
    /// then merged temporal candidates and the fallback counters, then the frames each
    /// technique shaded (STAT_INDIRECT_FRAMES + INDIRECT_GI / INDIRECT_PT), which tell
    /// `--stats` which ran.
    pub const STAT_INDIRECT_NONFINITE: u32 = STAT_SPATIAL_REJECT + REJECT_REASON_COUNT as u32;
    pub const STAT_INDIRECT_TEMPORAL_REJECT: u32 = STAT_INDIRECT_NONFINITE + INDIRECT_GUARDED_PASS_NAMES.len() as u32;
    pub const STAT_INDIRECT_SPATIAL_REJECT: u32 = STAT_INDIRECT_TEMPORAL_REJECT + GI_REJECT_REASON_COUNT as u32;
    pub const STAT_INDIRECT_TEMPORAL_ACCEPTED: u32 = STAT_INDIRECT_SPATIAL_REJECT + GI_REJECT_REASON_COUNT as u32;
    /// Temporal reuse's retries of the plain reprojection after a failed permuted read, and
    /// the retries that passed (as DI's STAT_FALLBACK_*).
    pub const STAT_INDIRECT_FALLBACK_TRIED: u32 = STAT_INDIRECT_TEMPORAL_ACCEPTED + 1;
    pub const STAT_INDIRECT_FALLBACK_USED: u32 = STAT_INDIRECT_FALLBACK_TRIED + 1;
    pub const STAT_INDIRECT_FRAMES: u32 = STAT_INDIRECT_FALLBACK_USED + 1;
    /// Shadow rays traced by each DI pass, at STAT_SHADOW_RAYS + PASS_* (GUARDED_PASS_NAMES
    /// order; the reference's rays are not counted), summed over pixels.
    pub const STAT_SHADOW_RAYS: u32 = STAT_INDIRECT_FRAMES + INDIRECT_NAMES.len() as u32;
    /// DI's light candidates, and those with a non-zero unshadowed
    /// contribution (p̂ > 0): the light sampler's useful-candidate share
    /// (docs/src/light-samplers.md).
    pub const STAT_LIGHT_CANDIDATES: u32 = STAT_SHADOW_RAYS + GUARDED_PASS_NAMES.len() as u32;
    pub const STAT_USEFUL_CANDIDATES: u32 = STAT_LIGHT_CANDIDATES + 1;
    /// MCMC mutation steps tried and accepted (their ratio is the acceptance rate the
    /// mutation step is tuned by; docs/src/mcmc-mutation.md).
    pub const STAT_MUTATIONS_TRIED: u32 = STAT_USEFUL_CANDIDATES + 1;
    pub const STAT_MUTATIONS_ACCEPTED: u32 = STAT_MUTATIONS_TRIED + 1;
    pub const STAT_COUNT: u32 = STAT_MUTATIONS_ACCEPTED + 1;

    /// The indirect passes that count non-finite values (at STAT_INDIRECT_NONFINITE + id),
    /// named in `--stats` after the technique that ran ("gi initial", "pt initial", ...).
    pub const INDIRECT_PASS_INITIAL: u32 = 0;
    pub const INDIRECT_PASS_TEMPORAL: u32 = 1;
    pub const INDIRECT_PASS_SPATIAL: u32 = 2;
    pub const INDIRECT_PASS_SHADE: u32 = 3;
}
pub const INDIRECT_GUARDED_PASS_NAMES: [&str; 4] = ["initial", "temporal", "spatial", "shade"];
wgsl_constants! {
    fn indirect_techniques;
    /// The indirect techniques (STAT_INDIRECT_FRAMES + id), by their settings' names.
    pub const INDIRECT_GI: u32 = 0;
    pub const INDIRECT_PT: u32 = 1;
}
pub const INDIRECT_NAMES: [&str; 2] = ["gi", "pt"];

wgsl_constants! {
    fn streams_and_limits;
    /// Random-number streams, one per purpose (`rng_seed` in rng.wgsl).
    pub const STREAM_INITIAL: u32 = 0;
    pub const STREAM_TEMPORAL: u32 = 1;
    pub const STREAM_REFERENCE: u32 = 2;
    /// Light presampling: the tiles or the ReGIR cells (never both in one frame).
    pub const STREAM_LIGHT_TILES: u32 = 3;
    pub const STREAM_SPATIAL: u32 = 4;
    // Spatial passes use STREAM_SPATIAL + pass index (4..4 + MAX_SPATIAL_PASSES).
    pub const STREAM_INDIRECT_INITIAL: u32 = 12;
    pub const STREAM_INDIRECT_TEMPORAL: u32 = 13;
    pub const STREAM_INDIRECT_SPATIAL: u32 = 14;
    /// The G-buffer's choice at each transparent layer (solid or pass, transparency.wgsl).
    pub const STREAM_TRANSPARENCY: u32 = 15;
    /// The most transparent layers a ray passes before the next one counts as opaque: every
    /// ray type (camera, path, shadow) stops at the same count, so all modes agree on the
    /// model, and a ray through a stack of glass still terminates.
    pub const MAX_TRANSPARENT_LAYERS: u32 = 8;
    /// `rng_seed` mixes frame_index × STREAM_COUNT + stream: a stream ≥ STREAM_COUNT would
    /// replay another stream of a later frame (GI once drew DI's next-frame numbers).
    pub const STREAM_COUNT: u32 = 16;
    /// The MCMC mutation's numbers: the initial stream's seed rehashed with this salt, a
    /// chain of its own without renumbering the streams (which would change every image).
    pub const MUTATION_STREAM_SALT: u32 = 0x6d757461;

    /// `bench-rays` (ray_bench.wgsl): rays per surface pixel and dispatch, and the two kinds
    /// (the dispatch's `PassInfo` slot). 16 rays keep one dispatch far above its fixed cost on
    /// a GPU and well inside Mesa 22's loop-iteration cap (REFERENCE_SAMPLES_PER_DISPATCH).
    pub const RAY_BENCH_RAYS_PER_PIXEL: u32 = 16;
    pub const RAY_BENCH_SHADOW: u32 = 0;
    pub const RAY_BENCH_CLOSEST: u32 = 1;

    /// The reference renders its samples per pixel in dispatches of at most this many.
    /// lavapipe (Mesa 22) bounds the total loop iterations of one shader invocation (one
    /// counter shared by all loops, 65535): a single invocation tracing a few hundred BVH rays
    /// silently stops early. Small chunks keep every invocation far below that bound.
    pub const REFERENCE_SAMPLES_PER_DISPATCH: u32 = 8;

    /// The most path vertices the reference shades (the `max_bounces` range). Each bounce adds a
    /// shadow ray and a BSDF ray per sample: at 8 bounces and REFERENCE_SAMPLES_PER_DISPATCH
    /// samples an invocation traces 136 rays, still within lavapipe's loop bound on the
    /// built-in scenes.
    pub const MAX_BOUNCES: u32 = 8;

    /// Light samples per reference vertex at most (`reference_light_samples`), and per path
    /// at most (samples × bounces): with REFERENCE_SAMPLES_PER_DISPATCH samples an
    /// invocation then traces at most 8 × (16 + 8) = 192 rays, near the 136 of 8 bounces
    /// with one light sample that lavapipe's loop bound is known to allow.
    pub const MAX_REFERENCE_LIGHT_SAMPLES: u32 = 16;
    pub const REFERENCE_PATH_LIGHT_SAMPLES: u32 = 16;

    /// Light tiles (docs/src/ris.md, "Light tiles"; RTXDI): every frame LIGHT_TILE_COUNT tiles of
    /// LIGHT_TILE_SIZE power-sampled lights are drawn once; each LIGHT_TILE_PIXELS² block of pixels
    /// draws its initial candidates from one tile, so candidate reads hit a small, shared working
    /// set whatever the number of lights.
    pub const LIGHT_TILE_COUNT: u32 = 128;
    pub const LIGHT_TILE_SIZE: u32 = 1024;
    pub const LIGHT_TILE_PIXELS: u32 = 16;

    /// ReGIR (docs/src/light-samplers.md, "ReGIR"): the grid's cells per side and slots per
    /// cell at most, and cells × slots at most (the fill pass's dispatch, 4 MiB of slots).
    pub const MAX_REGIR_GRID: u32 = 32;
    pub const MAX_REGIR_SLOTS: u32 = 1024;
    pub const MAX_REGIR_SLOTS_TOTAL: u32 = 262144;

    /// The light BVH (docs/src/light-samplers.md, "The light BVH"): a node's `child_or_light`
    /// with this bit set is a leaf holding that light; a light whose trail has depth
    /// LIGHT_BVH_NOT_IN_TREE has no leaf (no power or no position: PDF 0).
    pub const LIGHT_BVH_LEAF: u32 = 0x80000000;
    pub const LIGHT_BVH_NOT_IN_TREE: u32 = 0xffffffff;
    /// The refit on the GPU (lights/light_bvh_refit.wgsl): invocations per workgroup, and how many
    /// levels (dispatches) a refit may have, each with its slot of the levels uniform.
    pub const LIGHT_BVH_REFIT_WORKGROUP: u32 = 64;
    pub const MAX_LIGHT_BVH_LEVELS: u32 = 72;

    /// Upper bound of `spatial_neighbours` (the shader keeps accepted ones in an array).
    pub const MAX_SPATIAL_NEIGHBOURS: u32 = 32;
    /// Upper bound of `mutations` (MCMC steps per pixel and frame).
    pub const MAX_MUTATIONS: u32 = 16;
}
/// Spatial passes a frame runs at most (the `spatial_passes` range).
pub const MAX_SPATIAL_PASSES: u32 = 8;

wgsl_constants! {
    fn motion_and_view_limits;
    /// Motion of a point that was behind the previous camera (always off-screen).
    pub const NO_MOTION: f32 = -1e9;

    /// Frames per batch mean of the bias view's noise estimate (moments.wgsl): long enough to
    /// hold most of the frame-to-frame correlation at the default M cap of 20, short enough
    /// that a few hundred frames give a usable spread.
    pub const BIAS_BATCH: u32 = 16;
    /// The bias view paints a pixel when |mean − reference| exceeds this many standard errors
    /// (two-sided false alarm 0.3 % for Gaussian noise).
    pub const BIAS_SIGNIFICANCE: f32 = 3.0;
    /// … and by more than this fraction of the reference: smaller differences are white in its
    /// palette anyway, and the reference's noise, known only as an image-wide RMSE, is larger
    /// than that in its brightest pixels.
    pub const BIAS_NEGLIGIBLE: f32 = 0.01;
    /// Widening of each light-BVH node's normals cone (radians), so that the octahedral
    /// encoding of its axis (≈ 1e-4 rad of error) never makes the bound exclude a direction
    /// it holds (the records of light_sampler.rs and lights/light_bvh_refit.wgsl alike).
    pub const LIGHT_BVH_CONE_SLACK: f32 = 1e-3;
    /// Normals' cones whose axes are this close to opposite (radians) are joined about a
    /// fixed perpendicular (light_bvh.rs, `DirectionCone::union`).
    pub const LIGHT_BVH_NEARLY_OPPOSITE: f32 = 1e-3;
        /// Frames in the temporal window of the boiling and survivor-change views (the
    /// `temporal window` pass): long enough that the relative standard deviation of a steady
    /// pixel is estimated to ±18 % (1/√(2·15)), short enough that a switched light leaves it
    /// within half a second at 30 fps.
    pub const TEMPORAL_WINDOW_FRAMES: u32 = 16;
    /// The boiling view's palette runs from 0 to this relative standard deviation (σ/mean of
    /// a pixel's luminance over the window); stronger flicker saturates at yellow.
    pub const BOILING_VIEW_MAX: f32 = 1.5;
}
/// A pixel *boils* when its σ/mean over the window exceeds this (the palette's middle,
/// teal): a 16-frame window of a steadily noisy ReSTIR pixel rarely gets there, a pixel
/// whose survivor comes and goes does (render/tests/temporal_window.rs).
pub const BOILING_THRESHOLD: f32 = 0.75;

wgsl_constants! {
    fn tonemappers_and_gi_rejections;
    pub const TONEMAP_ACES: u32 = 0;
    pub const TONEMAP_REINHARD: u32 = 1;
    pub const TONEMAP_CLAMP: u32 = 2;

    /// ReSTIR GI validation (docs/src/restir-gi.md, "Rules the shaders follow"): the GI rejection
    /// mask's bits 0..5 are the DI checks with the same bits and meaning (`REJECT_OFFSCREEN` ..
    /// `REJECT_RESERVOIR`, so a `surface_dissimilarity` mask is used as it is); these three are
    /// GI's own. The reconnection shift is undefined: the sample point is (nearly) on the receiver,
    /// seen at a grazing angle, or the receiver is behind the sample's surface (gi/model/jacobian.rs).
    pub const GI_REJECT_RECONNECTION: u32 = 1 << 6;
    /// The reconnection Jacobian is outside [1/gi_jacobian_max, gi_jacobian_max].
    pub const GI_REJECT_JACOBIAN: u32 = 1 << 7;
    /// The reconnection segment from the receiver to the sample point is occluded.
    pub const GI_REJECT_OCCLUDED: u32 = 1 << 8;
    pub const GI_REJECT_REASON_COUNT: usize = 9;
}
/// Human names of the GI rejection bits, in bit order (the first six are DI's).
pub const GI_REJECT_REASON_NAMES: [&str; GI_REJECT_REASON_COUNT] = [
    REJECT_REASON_NAMES[0],
    REJECT_REASON_NAMES[1],
    REJECT_REASON_NAMES[2],
    REJECT_REASON_NAMES[3],
    REJECT_REASON_NAMES[4],
    REJECT_REASON_NAMES[5],
    "reconnection",
    "jacobian",
    "occluded",
];
wgsl_constants! {
    fn inspector;
    /// `GpuFrame.inspect_pixel` when no pixel is inspected.
    pub const NO_INSPECT_PIXEL: u32 = 0xffff_ffff;
}

#[cfg(test)]
mod stream_tests {
    use super::*;

    #[test]
    fn every_random_stream_is_distinct_and_below_the_stride() {
        let mut streams = vec![
            STREAM_INITIAL,
            STREAM_TEMPORAL,
            STREAM_REFERENCE,
            STREAM_LIGHT_TILES,
            STREAM_INDIRECT_INITIAL,
            STREAM_INDIRECT_TEMPORAL,
            STREAM_INDIRECT_SPATIAL,
            STREAM_TRANSPARENCY,
        ];
        streams.extend((0..MAX_SPATIAL_PASSES).map(|p| STREAM_SPATIAL + p));
        let count = streams.len();
        streams.sort();
        streams.dedup();
        assert_eq!(streams.len(), count, "two purposes share a stream");
        assert!(streams.iter().all(|&s| s < STREAM_COUNT));
    }

    /// The counter blocks follow one another without gaps or overlaps, and STAT_COUNT holds
    /// them all: (start, size) of each, in buffer order.
    #[test]
    fn the_counter_blocks_tile_the_buffer() {
        let reasons = REJECT_REASON_COUNT as u32;
        let gi_reasons = GI_REJECT_REASON_COUNT as u32;
        let blocks = [
            (STAT_TEMPORAL_REJECT, reasons),
            (STAT_SOURCE, SOURCE_NAMES.len() as u32),
            (STAT_TEMPORAL_CAP, 1),
            (STAT_SPATIAL_CAP, 1),
            (STAT_FALLBACK_TRIED, 1),
            (STAT_FALLBACK_USED, 1),
            (STAT_NONFINITE, GUARDED_PASS_NAMES.len() as u32),
            (STAT_SURFACE_PIXELS, 1),
            (STAT_TEMPORAL_ACCEPTED, 1),
            (STAT_BOILING_DROPPED, 1),
            (STAT_SPATIAL_REJECT, reasons),
            (
                STAT_INDIRECT_NONFINITE,
                INDIRECT_GUARDED_PASS_NAMES.len() as u32,
            ),
            (STAT_INDIRECT_TEMPORAL_REJECT, gi_reasons),
            (STAT_INDIRECT_SPATIAL_REJECT, gi_reasons),
            (STAT_INDIRECT_TEMPORAL_ACCEPTED, 1),
            (STAT_INDIRECT_FALLBACK_TRIED, 1),
            (STAT_INDIRECT_FALLBACK_USED, 1),
            (STAT_INDIRECT_FRAMES, INDIRECT_NAMES.len() as u32),
            (STAT_SHADOW_RAYS, GUARDED_PASS_NAMES.len() as u32),
            (STAT_LIGHT_CANDIDATES, 1),
            (STAT_USEFUL_CANDIDATES, 1),
            (STAT_MUTATIONS_TRIED, 1),
            (STAT_MUTATIONS_ACCEPTED, 1),
        ];
        let mut next = 0;
        for (start, size) in blocks {
            assert_eq!(
                start, next,
                "a counter block starts at {start}, expected {next}"
            );
            next += size;
        }
        assert_eq!(next, STAT_COUNT);
    }
}
