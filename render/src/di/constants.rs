//! ReSTIR DI's shader constants (the reservoir's packed word, the debug record's flags, its
//! `Params.flags` bits): Rust constants and, through `shader_source::wgsl_prelude`, WGSL
//! `const`s of the same names and values.

wgsl_constants! {
    fn packing_and_flags;
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
    pub const PARAM_FLAG_INITIAL_VISIBILITY: u32 = 1 << 3;
    /// Pairwise MIS evaluates the canonical sample at the previous pixel with last frame's
    /// lights (`previous_lights`; only compiled in for animated scenes).
    pub const PARAM_FLAG_PREVIOUS_LIGHTS: u32 = 1 << 10;
    /// Pairwise MIS with visibility in the target (`mis_visibility`): every pairwise term is
    /// p̂·V, so reuse traces the shadow rays the MIS weights need and shading traces none.
    pub const PARAM_FLAG_MIS_VISIBILITY: u32 = 1 << 11;
    /// Pairwise MIS traces the canonical sample's visibility at the previous pixel against last
    /// frame's geometry (`previous_geometry`; only compiled in for animated scenes).
    pub const PARAM_FLAG_PREVIOUS_GEOMETRY: u32 = 1 << 12;
    /// The temporal pass runs for the denoiser's gradients only (temporal reuse off): it
    /// shades the history's sample here and drops the merge (docs/src/denoiser.md).
    pub const PARAM_FLAG_GRADIENT_ONLY: u32 = 1 << 13;
}
