//! ReSTIR PT's shader constants (shift mappings, the path reservoir's packed word, shift
//! failures, the inspector's path probe): Rust constants and, through
//! `shader_source::wgsl_prelude`, WGSL `const`s of the same names and values.

use crate::shader_constants::MAX_BOUNCES;

wgsl_constants! {
    fn shifts_and_failures;
    /// ReSTIR PT's shift mappings (`Params.pt_shift`, settings `pt_shift`).
    pub const PT_SHIFT_RECONNECTION: u32 = 0;
    pub const PT_SHIFT_RANDOM_REPLAY: u32 = 1;
    pub const PT_SHIFT_HYBRID: u32 = 2;
    /// A path reservoir's `packed` word (shaders/pt/reservoir.wgsl): source | n << 4 | end << 8 |
    /// k << 9 | lobes << 13. The end technique of x_n → z:
    pub const PT_END_NEE: u32 = 0;
    pub const PT_END_BSDF: u32 = 1;
    /// k for a path that is replayed whole (no reconnection).
    pub const PT_RC_NONE: u32 = 15;
    pub const PT_LOBE_DIFFUSE: u32 = 0;
    pub const PT_LOBE_SPECULAR: u32 = 1;
    /// Why a path could not be moved to another pixel (pt_shift in shaders/pt/path.wgsl; the CPU
    /// model's `pt::model::shift::Failure`). `PT_FAIL_NONE`: it moved and carries light there.
    pub const PT_FAIL_NONE: u32 = 0;
    /// The replayed prefix left the path (missed, met another lobe's zero, left the scene).
    pub const PT_FAIL_REPLAY: u32 = 1;
    /// The reconnection is undefined (too near or far, grazing, the other side of its surface).
    pub const PT_FAIL_UNDEFINED: u32 = 2;
    /// The reconnection segment is blocked.
    pub const PT_FAIL_OCCLUDED: u32 = 3;
    /// Hybrid: the shifted path would reconnect at another bounce (not a bijection there).
    pub const PT_FAIL_ELSEWHERE: u32 = 4;
    /// Moved, but its integrand is zero at the new pixel (below the surface, outside the lobe).
    pub const PT_FAIL_ZERO: u32 = 5;
    pub const PT_FAIL_REASON_COUNT: usize = 6;
}
pub const PT_FAIL_NAMES: [&str; PT_FAIL_REASON_COUNT] = [
    "moved",
    "replay left the path",
    "reconnection undefined",
    "reconnection occluded",
    "reconnects elsewhere (hybrid)",
    "zero where moved",
];

wgsl_constants! {
    fn probe;
    /// `PtPixelDebug.temporal_failure` when no temporal shift was tried (no history, or the
    /// previous surface failed the G-buffer checks).
    pub const PT_FAIL_NOT_TRIED: u32 = 0xff;
    /// The PT stages the pixel inspector's path probe keeps (pt initial, temporal, spatial),
    /// and the vertices one stage's path can have: x_1 … x_n and the light point z.
    pub const PT_PROBE_STAGES: u32 = 3;
    pub const PT_PROBE_VERTICES: u32 = MAX_BOUNCES + 1;
    /// `PtProbeVertex.flags` bits.
    pub const PT_VERTEX_RECONNECTION: u32 = 1;
    pub const PT_VERTEX_LIGHT: u32 = 2;
    /// The light end is a direction (the environment), not a point.
    pub const PT_VERTEX_DIRECTION: u32 = 4;
}
