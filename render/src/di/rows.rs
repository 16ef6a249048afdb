//! ReSTIR DI's rows of the parameter table (settings.rs): its initial candidates, temporal and
//! spatial reuse, bias correction and the MCMC mutation. The rows are tokens that
//! `settings::gather_rows!` hands to `parameter_table!`: names such as `ParamKind` and the
//! shader constants resolve there, in settings.rs. A row's name is the parameter's name
//! everywhere (`--set`, presets, tours, the WGSL `Params` field).

/// Appends these rows to the tokens it is given and hands them to `$then` with the rest of
/// the list (`settings::gather_rows!`).
macro_rules! rows {
    ($then:ident [$($rest:ident),*] $($rows:tt)*) => {
        $then! {
            [$($rest),*] $($rows)*
            Initial {
                light_candidates: u32 = 32, ParamKind::Int { min: 0, max: 256 }, "Light candidates",
                    "Light samples per pixel drawn by the light sampler and streamed \
                        through the reservoir (docs/src/ris.md, \"The streaming \
                        reservoir\"). 1 light and 0 BSDF candidates is plain NEE. When \
                        light_sampler=auto takes the light BVH, at most 4 (its equal-time \
                        best within a tenth of the frame: docs/src/light-samplers.md, \
                        \"Choosing\").";
                bsdf_candidates: u32 = 1, ParamKind::Int { min: 0, max: 16 }, "BSDF candidates",
                    "BSDF-sampled rays per pixel; those that hit an emitter join the \
                        reservoir, combined with the light candidates by the balance \
                        heuristic.";
                initial_visibility: bool = true, ParamKind::Bool, "Initial visibility",
                    "Trace the survivor's shadow ray right after initial sampling and \
                        drop it when occluded (visibility reuse: docs/src/ris.md, \
                        \"Visibility reuse\"), so reuse only spreads samples that were \
                        visible. One extra shadow ray per pixel.";
            }
            Temporal {
                temporal: bool = true, ParamKind::Bool, "Temporal reuse",
                    "Merge the reprojected previous-frame reservoir \
                        (docs/src/temporal-reuse.md). Off: the temporal pass is not \
                        dispatched.", ReuseSwitch;
                target_ratio_clamp: f32 = 10.0, ParamKind::Float { min: 1.0, max: 1e6 }, "Target-ratio clamp",
                    "1/M: reject the temporal sample when p̂(x, y_prev) / p̂(x_prev, \
                        y_prev) is outside [1/clamp, clamp]; 1 rejects any change of target. \
                        Pairwise MIS: a window on that ratio for both samples alike — \
                        outside it the history's sample gets weight 0, and where this \
                        pixel's own sample is outside it the pixel keeps the history's share \
                        — so the weights still sum to one and the clamp stays unbiased (a \
                        rejection of the history alone would not).";
                permutation: bool = true, ParamKind::Bool, "Permutation sampling",
                    "Read the previous reservoir through a per-frame 4×4 pixel \
                        permutation to decorrelate neighbours; fall back to the plain \
                        reprojected pixel when that read fails validation.";
                check_target_ratio: bool = true, ParamKind::Bool, "Check: target ratio",
                    "Apply the target-ratio clamp (off disables the test whatever the \
                        clamp; under pairwise MIS the clamp is an unbiased window, see the \
                        clamp).";
                camera_cut: f32 = 0.25, ParamKind::Float { min: 0.0, max: 100.0 }, "Camera cut distance",
                    "A camera jump longer than this fraction of the scene size in one \
                        frame is a cut: history is dropped. 0 treats every move as a cut.";
            }
            Spatial {
                spatial: bool = true, ParamKind::Bool, "Spatial reuse",
                    "Merge reservoirs of nearby pixels (docs/src/spatial-reuse.md). Off: \
                        no spatial pass is dispatched.", ReuseSwitch;
                spatial_neighbours: u32 = 5, ParamKind::Int { min: 0, max: MAX_SPATIAL_NEIGHBOURS as i64 }, "Neighbours",
                    "Neighbours tried per pixel and pass, uniformly in a disk.";
                spatial_radius: f32 = 30.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "Radius (px at 1080p)",
                    "Radius of the neighbour disk in pixels of a 1080-pixel-high image; \
                        other sizes use radius × height / 1080, at least 2 px (or the radius \
                        itself if smaller), so reuse spans the same part of the scene at any \
                        resolution or render scale.";
                spatial_passes: u32 = 1, ParamKind::Int { min: 1, max: MAX_SPATIAL_PASSES as i64 }, "Passes",
                    "Spatial passes per frame, each reading the previous pass's output.";
                boiling_filter: f32 = 0.0, ParamKind::Float { min: 0.0, max: 1000.0 }, "Boiling filter",
                    "Drop a pixel's sample when its W·p̂ exceeds this many times the \
                        neighbourhood mean (docs/src/spatial-reuse.md, \"The boiling \
                        filter\"). 0 = off. Biased: the decision looks at the sample's \
                        value, so it darkens the image while it lowers flicker (both measured \
                        in docs/src/measured/dynamic-scenes.md, \"Boiling\").";
            }
            Resampling {
                m_cap: f32 = 20.0, ParamKind::Float { min: 0.0, max: 1e6 }, "M cap",
                    "Upper bound of a reservoir's confidence M (direct light). History is \
                        merged with min(M_prev, M cap), and M is capped after every reuse \
                        pass, temporal and spatial. M counts frames' worth of samples.";
                bias_correction: BiasCorrection = BiasCorrection::Pairwise, ParamKind::Choice(BIAS_CORRECTION_NAMES), "Bias correction",
                    "pairwise (default): defensive pairwise MIS with the pixel's own \
                        reservoir as canonical (unbiased, one extra target evaluation per \
                        neighbour). one-over-m: 1/M weights with \
                        rejection (biased: darker where reused samples are occluded or \
                        outside a narrow lobe; fast).";
                mis_visibility: bool = true, ParamKind::Bool, "MIS visibility",
                    "Pairwise: the target is p̂·V (visibility included) at every pixel \
                        and in every MIS term, as unbiased reuse of visibility-tested \
                        samples requires (RTXDI's ray-traced bias correction): each reused \
                        sample is traced from here before it can be picked, this pixel's \
                        sample from each spatial neighbour and from the previous pixel \
                        (against this frame's geometry). Implies initial visibility; shading \
                        then traces no ray (the survivor is known visible). Costs 2 shadow \
                        rays per spatial neighbour and 2 per temporal merge. Off: unshadowed \
                        MIS terms: darker where neighbours are shadowed differently, and black \
                        speckles where a pixel picks a sample it cannot see (both measured in \
                        docs/src/measured/unbiased-reuse.md, \"The bias table\").";
                previous_lights: bool = true, ParamKind::Bool, "Previous-frame lights",
                    "Animated scenes, pairwise MIS: evaluate this pixel's own (canonical) \
                        sample at the previous pixel with last frame's lights — positions, \
                        emission, punctual records — as unbiasedness requires. Off: with the \
                        current lights, a common shortcut; then a light switched on stays \
                        too dark for a few frames (its new samples are weighted as if the \
                        history could have found them). Static scenes: no difference.";
                previous_geometry: bool = true, ParamKind::Bool, "Previous-frame geometry",
                    "Animated scenes, pairwise MIS with MIS visibility: trace the \
                        visibility of this pixel's own sample at the previous pixel against \
                        last frame's geometry (last frame's TLAS with ray queries, last \
                        frame's BVH boxes and triangles with the software backend), as \
                        unbiasedness requires. Off: against this frame's geometry, a common \
                        shortcut; then a moving occluder credits the previous pixel with \
                        samples it could not see and darkens (docs/src/measured/unbiased-reuse.md, \
                        \"The moving occluder against last frame's geometry\"). Static \
                        scenes: no difference.";
                mutations: u32 = 0, ParamKind::Int { min: 0, max: MAX_MUTATIONS as i64 }, "MCMC mutations",
                    "Metropolis–Hastings steps applied to each pixel's light sample after \
                        the last reuse pass, toward the pixel's own target (Sawhney et al. \
                        2024; docs/src/mcmc-mutation.md). Each step slides the point on its \
                        triangle light or proposes a fresh power-table sample; W is rescaled \
                        by T(y)/T(y'), so the image stays unbiased while neighbours and \
                        frames stop sharing one sample. Runs only where reuse is on. 0 = \
                        off. Each step costs one target evaluation, and with MIS visibility \
                        a shadow ray when the step could be accepted.";
                mutation_step: f32 = 0.1, ParamKind::Float { min: 1e-4, max: 1.0 }, "Mutation step",
                    "Largest slide of a local mutation in barycentric units of the \
                        triangle light (0.1: a tenth of the triangle). Any value is \
                        unbiased; small steps are accepted more often and move less.";
            }
        }
    };
}
pub(crate) use rows;
