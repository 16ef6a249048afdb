//! ReSTIR GI's shader constants (the reservoir's packed word, the reconnection's
//! thresholds, its `Params.flags` bits): Rust constants and, through
//! `shader_source::wgsl_prelude`, WGSL `const`s of the same names and values.

wgsl_constants! {
    fn packing_and_flags;
    /// `GiReservoir.packed`: SOURCE_* in bits 0..4, the GI rejection mask of the stage that
    /// wrote it in bits 4..16, the sample's age in frames in bits 16..32 (saturating).
    pub const GI_SOURCE_MASK: u32 = 0xf;
    pub const GI_FLAGS_SHIFT: u32 = 4;
    pub const GI_FLAGS_MASK: u32 = 0xfff;
    pub const GI_AGE_SHIFT: u32 = 16;
    pub const GI_AGE_MAX: u32 = 0xffff;
    /// Thresholds of the reconnection Jacobian (gi/model/jacobian.rs), the same on both sides.
    /// Shortest reconnection (world units, squared) with a usable direction. Positions are f32:
    /// at a scene scale of ~100 one ulp is ~7.6e-6, so below ~1e-5 the direction from x_s to the
    /// receiver is rounding noise, and the Jacobian's `1/d²` runs away.
    pub const RECONNECTION_MIN_DISTANCE_SQ: f32 = 1e-10;
    /// Longest reconnection (squared; 1e10 units, far beyond any scene). With the two bounds and
    /// `RECONNECTION_MIN_COS` every quotient below stays finite: J ≤ 1e6 · 1e20 / 1e-10 = 1e36 < f32::MAX,
    /// which matters on the GPU, where WGSL leaves an overflowing division indeterminate.
    pub const RECONNECTION_MAX_DISTANCE_SQ: f32 = 1e20;
    /// Smallest |cos φ| at the sample point (from either receiver): below it the patch has no
    /// solid angle to speak of (J = 0 or ∞ up to rounding), and no window in the settings'
    /// range (j_max ≤ 1000) could accept the result anyway.
    pub const RECONNECTION_MIN_COS: f32 = 1e-6;
    /// `Params.flags` bits of the Indirect stage.
    pub const PARAM_FLAG_GI: u32 = 1 << 4;
    pub const PARAM_FLAG_GI_TEMPORAL: u32 = 1 << 5;
    pub const PARAM_FLAG_GI_SPATIAL: u32 = 1 << 6;
    pub const PARAM_FLAG_GI_SPATIAL_VISIBILITY: u32 = 1 << 7;
    pub const PARAM_FLAG_GI_PAIRWISE: u32 = 1 << 8;
    pub const PARAM_FLAG_GI_MIS_VISIBILITY: u32 = 1 << 9;
}
