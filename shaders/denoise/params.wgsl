// The denoiser's fields of the Params uniform (`params.denoise`; the twin of
// render/src/denoise/params.rs; docs/src/denoiser.md): setting `denoise_x` is field `x`.
struct DenoiseParams {
    alpha: f32,                   // smallest weight of this frame in the history blend
    moments_alpha: f32,
    phi_luminance: f32,
    phi_normal: f32,
    phi_depth: f32,
    history_cap: f32,             // frames
    _pad0: u32,
    _pad1: u32,
}
