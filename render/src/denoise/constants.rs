//! The denoiser's shader constants (its fixed choices and its `Params.flags` bit): Rust
//! constants and, through `shader_source::wgsl_prelude`, WGSL `const`s of the same names
//! and values.

wgsl_constants! {
    fn denoiser;
    /// The denoiser's fixed choices (docs/src/denoiser.md). Demodulation never divides by
    /// less than this: a black surface's lighting is multiplied back by the same floor.
    pub const DENOISE_ALBEDO_FLOOR: f32 = 0.01;
    /// A reprojected history tap is this pixel's surface seen again when the normals agree
    /// to this cosine (25°, as the reuse validation's default) …
    pub const DENOISE_NORMAL_COS: f32 = 0.906;
    /// … and the points are closer than this fraction of the view depth (jitter moves the
    /// point within a pixel, ~0.003 of the depth at 480 lines; a bilinear tap is ≤ 1.5 px away).
    pub const DENOISE_POSITION_TOLERANCE: f32 = 0.05;
    /// Below this many frames of history the variance comes from the neighbourhood.
    pub const DENOISE_MIN_HISTORY: u32 = 4;
    /// The neighbourhood's radius (7 × 7, as SVGF).
    pub const DENOISE_VARIANCE_RADIUS: u32 = 3;
    /// À-trous iterations at most (taps 2^4 = 16 px apart in the last).
    pub const MAX_DENOISE_ITERATIONS: u32 = 5;
    /// The gradient's neighbourhood: (2 × taps + 1)² taps, this many pixels apart.
    pub const DENOISE_GRADIENT_TAPS: u32 = 2;
    pub const DENOISE_GRADIENT_STRIDE: u32 = 3;
    /// The temporal pass's `PassInfo` slot when last frame left a valid history (0: none).
    pub const DENOISE_HISTORY_SLOT: u32 = 1;

    /// The denoiser's temporal pass shortens the history by the temporal gradient.
    pub const PARAM_FLAG_DENOISE_GRADIENTS: u32 = 1 << 14;
}
