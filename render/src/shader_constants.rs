//! Constants both sides need (bit masks, counter indices, enum values). They are defined
//! once, here, and written into every WGSL module as a generated prelude, so the host and
//! the shaders cannot drift apart.

use crate::gpu_types;

/// Validation checks; the same bits form the temporal and spatial rejection masks
/// (restir-notes.md §2.2). Bit order is the order of the rejection-view legend.
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
/// Every temporal rejection reason (the rejection view's default reason mask; its
/// spatial part is a count of rejected neighbours, not a mask).
pub const REJECT_TEMPORAL_REASONS: u32 = (1 << REJECT_REASON_COUNT) - 1;

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

/// Which stage's candidate survived in a pixel.
pub const SOURCE_NULL: u32 = 0;
pub const SOURCE_INITIAL: u32 = 1;
pub const SOURCE_TEMPORAL: u32 = 2;
pub const SOURCE_SPATIAL: u32 = 3;
pub const SOURCE_NAMES: [&str; 4] = ["null", "initial", "temporal", "spatial"];
/// `Reservoir.source` holds the SOURCE_* in its low bits and the sample's age (frames
/// since it was first drawn) above AGE_SHIFT: no new field, so the reservoir layout and
/// its memory traffic stay what they are.
pub const SOURCE_MASK: u32 = 0xff;
pub const AGE_SHIFT: u32 = 8;
/// The largest age stored (24 bits).
pub const AGE_MAX: u32 = (1 << (32 - AGE_SHIFT)) - 1;

pub const DEBUG_FLAG_TEMPORAL_CAP: u32 = 1 << 0;
pub const DEBUG_FLAG_SPATIAL_CAP: u32 = 1 << 1;
pub const DEBUG_FLAG_FALLBACK_TRIED: u32 = 1 << 2;
pub const DEBUG_FLAG_FALLBACK_USED: u32 = 1 << 3;
pub const DEBUG_FLAG_TEMPORAL_MERGED: u32 = 1 << 4;
/// The survivor at shading is an environment direction (the source view lightens it).
pub const DEBUG_FLAG_ENVIRONMENT_SAMPLE: u32 = 1 << 5;

pub const PARAM_FLAG_PERMUTATION: u32 = 1 << 0;
pub const PARAM_FLAG_PAIRWISE: u32 = 1 << 1;
pub const PARAM_FLAG_JITTER: u32 = 1 << 2;
pub const PARAM_FLAG_INITIAL_VISIBILITY: u32 = 1 << 3;
/// Pairwise MIS evaluates the canonical sample at the previous pixel with last frame's
/// lights (`previous_lights`; only compiled in for animated scenes).
pub const PARAM_FLAG_PREVIOUS_LIGHTS: u32 = 1 << 4;

/// Passes that count non-finite values (issue "hard cases": a GPU-side guard).
pub const PASS_GBUFFER: u32 = 0;
pub const PASS_INITIAL: u32 = 1;
pub const PASS_TEMPORAL: u32 = 2;
pub const PASS_SPATIAL: u32 = 3;
pub const PASS_SHADE: u32 = 4;
pub const PASS_REFERENCE: u32 = 5;
pub const GUARDED_PASS_NAMES: [&str; 6] = [
    "gbuffer",
    "initial",
    "temporal",
    "spatial",
    "shade",
    "reference",
];

/// Indices into the per-frame atomic counter buffer (REJECT_REASON_COUNT each for the
/// temporal and spatial rejections).
pub const STAT_TEMPORAL_REJECT: u32 = 0;
pub const STAT_SPATIAL_REJECT: u32 = 40;
pub const STAT_SOURCE: u32 = 16;
pub const STAT_TEMPORAL_CAP: u32 = 20;
pub const STAT_SPATIAL_CAP: u32 = 21;
pub const STAT_FALLBACK_TRIED: u32 = 22;
pub const STAT_FALLBACK_USED: u32 = 23;
pub const STAT_NONFINITE: u32 = 24;
pub const STAT_SURFACE_PIXELS: u32 = 32;
pub const STAT_TEMPORAL_ACCEPTED: u32 = 33;
pub const STAT_BOILING_DROPPED: u32 = 34;
pub const STAT_COUNT: u32 = STAT_SPATIAL_REJECT + REJECT_REASON_COUNT as u32;

/// Random-number streams, one per purpose (`rng_seed` in rng.wgsl).
pub const STREAM_INITIAL: u32 = 0;
pub const STREAM_TEMPORAL: u32 = 1;
pub const STREAM_REFERENCE: u32 = 2;
pub const STREAM_LIGHT_TILES: u32 = 3;
pub const STREAM_SPATIAL: u32 = 4;

/// The reference renders its samples per pixel in dispatches of at most this many.
/// lavapipe (Mesa 22) bounds the total loop iterations of one shader invocation (one
/// counter shared by all loops, 65535): a single invocation tracing a few hundred BVH rays
/// silently stops early. Small chunks keep every invocation far below that bound.
pub const REFERENCE_SAMPLES_PER_DISPATCH: u32 = 8;

/// Light tiles (notes §6; RTXDI): every frame LIGHT_TILE_COUNT tiles of LIGHT_TILE_SIZE
/// power-sampled lights are drawn once; each LIGHT_TILE_PIXELS² block of pixels draws its
/// initial candidates from one tile, so candidate reads hit a small, shared working set
/// whatever the number of lights.
pub const LIGHT_TILE_COUNT: u32 = 128;
pub const LIGHT_TILE_SIZE: u32 = 1024;
pub const LIGHT_TILE_PIXELS: u32 = 16;

/// Upper bound of `spatial_neighbours` (the shader keeps accepted ones in an array).
pub const MAX_SPATIAL_NEIGHBOURS: u32 = 32;
/// Spatial passes a frame runs at most (the `spatial_passes` range).
pub const MAX_SPATIAL_PASSES: u32 = 8;

/// Motion of a point that was behind the previous camera (always off-screen).
pub const NO_MOTION: f32 = -1e9;

pub const VIEW_FINAL: u32 = 0;
pub const VIEW_SOURCE: u32 = 1;
pub const VIEW_M: u32 = 2;
pub const VIEW_REJECTION: u32 = 3;
pub const VIEW_WEIGHT: u32 = 4;
pub const VIEW_NORMALS: u32 = 5;
pub const VIEW_ALBEDO: u32 = 6;
pub const VIEW_DEPTH: u32 = 7;
pub const VIEW_MOTION: u32 = 8;
pub const VIEW_ERROR: u32 = 9;
pub const VIEW_DIFFERENCE: u32 = 10;
pub const VIEW_AGE: u32 = 11;

pub const TONEMAP_ACES: u32 = 0;
pub const TONEMAP_REINHARD: u32 = 1;
pub const TONEMAP_CLAMP: u32 = 2;

/// The WGSL prelude: every constant above as a `const` declaration.
pub fn wgsl_prelude() -> String {
    let u32s: &[(&str, u32)] = &[
        ("NO_LIGHT", gpu_types::NO_LIGHT),
        ("NO_TEXTURE", gpu_types::NO_TEXTURE),
        ("MATERIAL_DOUBLE_SIDED", gpu_types::MATERIAL_DOUBLE_SIDED),
        ("MATERIAL_ALPHA_MASK", gpu_types::MATERIAL_ALPHA_MASK),
        ("LIGHT_KIND_TRIANGLE", gpu_types::LIGHT_KIND_TRIANGLE),
        ("LIGHT_KIND_PUNCTUAL", gpu_types::LIGHT_KIND_PUNCTUAL),
        ("LIGHT_KIND_ENVIRONMENT", gpu_types::LIGHT_KIND_ENVIRONMENT),
        ("LIGHT_KIND_SHIFT", gpu_types::LIGHT_KIND_SHIFT),
        ("LIGHT_PRIM_MASK", gpu_types::LIGHT_PRIM_MASK),
        ("PUNCTUAL_POINT", gpu_types::PUNCTUAL_POINT),
        ("PUNCTUAL_SPOT", gpu_types::PUNCTUAL_SPOT),
        ("PUNCTUAL_DIRECTIONAL", gpu_types::PUNCTUAL_DIRECTIONAL),
        ("REJECT_OFFSCREEN", REJECT_OFFSCREEN),
        ("REJECT_SURFACE", REJECT_SURFACE),
        ("REJECT_MATERIAL", REJECT_MATERIAL),
        ("REJECT_NORMAL", REJECT_NORMAL),
        ("REJECT_DEPTH", REJECT_DEPTH),
        ("REJECT_RESERVOIR", REJECT_RESERVOIR),
        ("REJECT_TARGET", REJECT_TARGET),
        ("REJECT_TARGET_RATIO", REJECT_TARGET_RATIO),
        ("REJECT_LIGHT_GONE", REJECT_LIGHT_GONE),
        ("REJECT_REASON_COUNT", REJECT_REASON_COUNT as u32),
        ("SOURCE_NULL", SOURCE_NULL),
        ("SOURCE_INITIAL", SOURCE_INITIAL),
        ("SOURCE_TEMPORAL", SOURCE_TEMPORAL),
        ("SOURCE_SPATIAL", SOURCE_SPATIAL),
        ("SOURCE_MASK", SOURCE_MASK),
        ("AGE_SHIFT", AGE_SHIFT),
        ("AGE_MAX", AGE_MAX),
        ("DEBUG_FLAG_TEMPORAL_CAP", DEBUG_FLAG_TEMPORAL_CAP),
        ("DEBUG_FLAG_SPATIAL_CAP", DEBUG_FLAG_SPATIAL_CAP),
        ("DEBUG_FLAG_FALLBACK_TRIED", DEBUG_FLAG_FALLBACK_TRIED),
        ("DEBUG_FLAG_FALLBACK_USED", DEBUG_FLAG_FALLBACK_USED),
        ("DEBUG_FLAG_TEMPORAL_MERGED", DEBUG_FLAG_TEMPORAL_MERGED),
        (
            "DEBUG_FLAG_ENVIRONMENT_SAMPLE",
            DEBUG_FLAG_ENVIRONMENT_SAMPLE,
        ),
        ("PARAM_FLAG_PERMUTATION", PARAM_FLAG_PERMUTATION),
        ("PARAM_FLAG_PAIRWISE", PARAM_FLAG_PAIRWISE),
        ("PARAM_FLAG_JITTER", PARAM_FLAG_JITTER),
        (
            "PARAM_FLAG_INITIAL_VISIBILITY",
            PARAM_FLAG_INITIAL_VISIBILITY,
        ),
        ("PARAM_FLAG_PREVIOUS_LIGHTS", PARAM_FLAG_PREVIOUS_LIGHTS),
        ("PASS_GBUFFER", PASS_GBUFFER),
        ("PASS_INITIAL", PASS_INITIAL),
        ("PASS_TEMPORAL", PASS_TEMPORAL),
        ("PASS_SPATIAL", PASS_SPATIAL),
        ("PASS_SHADE", PASS_SHADE),
        ("PASS_REFERENCE", PASS_REFERENCE),
        ("STAT_TEMPORAL_REJECT", STAT_TEMPORAL_REJECT),
        ("STAT_SPATIAL_REJECT", STAT_SPATIAL_REJECT),
        ("STAT_SOURCE", STAT_SOURCE),
        ("STAT_TEMPORAL_CAP", STAT_TEMPORAL_CAP),
        ("STAT_SPATIAL_CAP", STAT_SPATIAL_CAP),
        ("STAT_FALLBACK_TRIED", STAT_FALLBACK_TRIED),
        ("STAT_FALLBACK_USED", STAT_FALLBACK_USED),
        ("STAT_NONFINITE", STAT_NONFINITE),
        ("STAT_SURFACE_PIXELS", STAT_SURFACE_PIXELS),
        ("STAT_TEMPORAL_ACCEPTED", STAT_TEMPORAL_ACCEPTED),
        ("STAT_BOILING_DROPPED", STAT_BOILING_DROPPED),
        ("STAT_COUNT", STAT_COUNT),
        ("STREAM_INITIAL", STREAM_INITIAL),
        ("STREAM_TEMPORAL", STREAM_TEMPORAL),
        ("STREAM_REFERENCE", STREAM_REFERENCE),
        ("STREAM_LIGHT_TILES", STREAM_LIGHT_TILES),
        ("LIGHT_TILE_COUNT", LIGHT_TILE_COUNT),
        ("LIGHT_TILE_SIZE", LIGHT_TILE_SIZE),
        ("LIGHT_TILE_PIXELS", LIGHT_TILE_PIXELS),
        ("STREAM_SPATIAL", STREAM_SPATIAL),
        ("MAX_SPATIAL_NEIGHBOURS", MAX_SPATIAL_NEIGHBOURS),
        (
            "REFERENCE_SAMPLES_PER_DISPATCH",
            REFERENCE_SAMPLES_PER_DISPATCH,
        ),
        ("VIEW_FINAL", VIEW_FINAL),
        ("VIEW_SOURCE", VIEW_SOURCE),
        ("VIEW_M", VIEW_M),
        ("VIEW_REJECTION", VIEW_REJECTION),
        ("VIEW_WEIGHT", VIEW_WEIGHT),
        ("VIEW_NORMALS", VIEW_NORMALS),
        ("VIEW_ALBEDO", VIEW_ALBEDO),
        ("VIEW_DEPTH", VIEW_DEPTH),
        ("VIEW_MOTION", VIEW_MOTION),
        ("VIEW_ERROR", VIEW_ERROR),
        ("VIEW_DIFFERENCE", VIEW_DIFFERENCE),
        ("VIEW_AGE", VIEW_AGE),
        ("TONEMAP_ACES", TONEMAP_ACES),
        ("TONEMAP_REINHARD", TONEMAP_REINHARD),
        ("TONEMAP_CLAMP", TONEMAP_CLAMP),
    ];
    let mut out = String::from("// Generated from render/src/shader_constants.rs: edit there.\n");
    for (name, value) in u32s {
        out.push_str(&format!("const {name}: u32 = {value}u;\n"));
    }
    out.push_str(&format!("const NO_MOTION: f32 = {NO_MOTION:e};\n"));
    out
}
