//! The denoiser's rows of the parameter table (settings.rs), each named `denoise_*` (the
//! switch itself is `denoise`). Tokens for `settings::gather_rows!`: names such as
//! `ParamKind` resolve in settings.rs, where the table is expanded.

/// Appends these rows to the tokens it is given and hands them to `$then` with the rest of
/// the list (`settings::gather_rows!`).
macro_rules! rows {
    ($then:ident [$($rest:ident),*] $($rows:tt)*) => {
        $then! {
            [$($rest),*] $($rows)*
            Denoise {
                denoise: bool = false, ParamKind::Bool, "Denoiser (SVGF)",
                    "A spatiotemporal variance-guided filter after shading (Schied et al. \
                        2017; docs/src/denoiser.md): the frame's light (direct + indirect, \
                        one signal) is divided by the surface colour, accumulated over time \
                        through the motion vectors, and blurred by à-trous passes that stop \
                        at depth, normal and luminance edges scaled by the estimated \
                        variance, then multiplied back. Every figure (error, flicker, \
                        boiling, lag) is then measured on the denoised image. Off: no \
                        denoiser code is compiled or run.";
                denoise_gradients: bool = true, ParamKind::Bool, "Temporal gradients",
                    "A-SVGF (Schied et al. 2018): DI's temporal pass shades last frame's \
                        sample at this frame's surface with this frame's lights and \
                        occluders; where the neighbourhood's shading changed by a share λ of \
                        its value, this frame weighs α + (1 − α) λ in the history blend, so \
                        a light switched off or a moving shadow is followed within a frame \
                        or two instead of ~1/α. With DI temporal reuse off the temporal pass \
                        runs for the gradients alone (its cost is counted). Off: plain SVGF.";
                denoise_iterations: u32 = 3, ParamKind::Int { min: 1, max: MAX_DENOISE_ITERATIONS as i64 }, "À-trous iterations",
                    "À-trous passes, taps 1, 2, 4, … pixels apart: 3 reach 2 × (1 + 2 + \
                        4) = 14 px each way. The best depth depends on the scene and the \
                        image size (a larger image wants more): docs/src/measured/denoiser.md, \
                        \"Choosing the depth per scene\", measures it per scene, and \
                        `denoise_auto_depth` chooses it.";
                denoise_auto_depth: bool = false, ParamKind::Bool, "Depth by a held-out frame",
                    "Chooses the à-trous depth per scene (docs/src/denoiser.md, \"Choosing \
                        the depth\"): once the history has been valid for 6 frames, it is \
                        filtered on the CPU at every depth (the denoiser's model) and compared \
                        with the next frame's raw light, whose noise is its own, so the depth \
                        closest to it is the depth closest to the truth; later frames filter \
                        at that depth (the Stats panel and --stats show it) until the settings \
                        change. With temporal reuse the next frame shares samples with the \
                        history and shallow depths look better than they are. Off: \
                        denoise_iterations.";
                denoise_alpha: f32 = 0.2, ParamKind::Float { min: 0.01, max: 1.0 }, "History blend α",
                    "Smallest weight of this frame in the temporal blend (1/length while \
                        the history is shorter than 1/α): 0.2 keeps ~5 frames; lower is \
                        smoother and lags more; 1 turns temporal accumulation off.";
                denoise_moments_alpha: f32 = 0.2, ParamKind::Float { min: 0.01, max: 1.0 }, "Moments blend α",
                    "The same for the luminance moments the variance is estimated from.";
                denoise_history_cap: u32 = 32, ParamKind::Int { min: 1, max: 255 }, "History cap (frames)",
                    "Longest history a pixel counts (the history-length view's top); with \
                        α it sets how long 1/length keeps decreasing.";
                denoise_phi_luminance: f32 = 4.0, ParamKind::Float { min: 0.01, max: 1000.0 }, "φ luminance",
                    "Luminance edge-stopping: a neighbour's weight falls as e^(−|Δl| / (φ \
                        σ)), σ the standard deviation of the luminance difference (both \
                        pixels' variances). Larger blurs more.";
                denoise_phi_normal: f32 = 128.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "φ normal",
                    "Normal edge-stopping exponent: weight max(0, n·n')^φ (128: 6° halves \
                        it). Larger keeps creases sharper.";
                denoise_phi_depth: f32 = 1.0, ParamKind::Float { min: 0.01, max: 1000.0 }, "φ depth",
                    "Depth edge-stopping: weight e^(−d / (φ · depth · pixel angle · taps \
                        apart)), d the neighbour's distance from this pixel's tangent plane; \
                        zero on one plane however steep. Larger blurs across silhouettes.";
            }
        }
    };
}
pub(crate) use rows;
