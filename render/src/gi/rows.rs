//! ReSTIR GI's rows of the parameter table (settings.rs), in the Indirect stage, each named
//! `gi_*` (the switch itself is `gi`). Tokens for `settings::gather_rows!`: names such as
//! `ParamKind` resolve in settings.rs, where the table is expanded.

/// Appends these rows to the tokens it is given and hands them to `$then` with the rest of
/// the list (`settings::gather_rows!`).
macro_rules! rows {
    ($then:ident [$($rest:ident),*] $($rows:tt)*) => {
        $then! {
            [$($rest),*] $($rows)*
            Indirect {
                gi: bool = false, ParamKind::Bool, "Indirect (ReSTIR GI)",
                    "One-bounce indirect light with reservoir reuse (Ouyang et al. 2021): \
                        one BSDF ray per pixel, its hit's outgoing direct radiance as the \
                        sample, reused over time and space through the reconnection \
                        Jacobian. The image is direct (ReSTIR DI) + indirect. Off: no GI \
                        code is compiled or run.";
                gi_temporal: bool = true, ParamKind::Bool, "GI temporal reuse",
                    "Merge the reprojected previous-frame GI reservoir, its sample \
                        reconnected to this frame's visible point.", ReuseSwitch;
                gi_spatial: bool = true, ParamKind::Bool, "GI spatial reuse",
                    "Merge GI reservoirs of nearby pixels, each sample reconnected to \
                        this pixel's visible point.", ReuseSwitch;
                gi_m_cap: f32 = 10.0, ParamKind::Float { min: 0.0, max: 1e6 }, "GI M cap",
                    "Upper bound of a GI reservoir's confidence M (as M cap for direct \
                        light, separately). 10, half the direct light's: a GI sample's \
                        cached radiance is never re-evaluated, so it outlives a lighting \
                        change for about M cap frames (recovery took ~M cap frames for \
                        direct light, docs/src/measured/dynamic-scenes.md \"Lag and \
                        ghosting\").";
                gi_light_candidates: u32 = 0, ParamKind::Int { min: 0, max: 256 }, "GI light candidates",
                    "Light candidates of the RIS at GI's secondary vertex (the direct \
                        light its sample carries). 0: DI's `light_candidates`. With the \
                        light BVH at the vertices a few of its candidates do what 32 of the \
                        table's do, for an eighth of the walks \
                        (docs/src/measured/many-lights.md, \"At every vertex\").";
                gi_spatial_neighbours: u32 = 3, ParamKind::Int { min: 0, max: MAX_SPATIAL_NEIGHBOURS as i64 }, "GI neighbours",
                    "Neighbours tried per pixel in GI spatial reuse. 3, fewer than direct \
                        light's 5: each one costs a reconnection shadow ray when GI \
                        reconnection visibility is on.";
                gi_spatial_radius: f32 = 30.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "GI radius (px at 1080p)",
                    "Radius of the GI neighbour disk in pixels of a 1080-pixel-high \
                        image, scaled with the height like the direct light's radius (at \
                        least 2 px).";
                gi_jacobian_max: f32 = 10.0, ParamKind::Float { min: 1.0, max: 1000.0 }, "GI Jacobian window",
                    "Reject a reconnected sample when its Jacobian |J| is outside [1/max, \
                        max]: a sample that the other pixel saw much larger or smaller than \
                        this one would (near geometry, grazing angles) carries a weight out \
                        of proportion, the source of GI fireflies. Symmetric, so pairwise \
                        MIS stays unbiased; 1 accepts only |J| = 1.";
                gi_spatial_visibility: bool = true, ParamKind::Bool, "GI reconnection visibility",
                    "Trace a shadow ray from this pixel's visible point to each spatial \
                        neighbour's sample point and drop the sample when occluded. Off: one \
                        ray fewer per neighbour, biased: light leaks through occluders (the \
                        CPU model's blocker test, gi/model/visibility_tests.rs, shows it).";
                gi_mis_visibility: bool = true, ParamKind::Bool, "GI MIS visibility",
                    "Pairwise, with GI reconnection visibility: also trace from each \
                        neighbour's visible point to this pixel's own sample point, so its \
                        MIS weight knows which neighbours could have found it. Off: one ray \
                        fewer per neighbour, darker behind occluders (the same test; unbiased \
                        with it on).";
                gi_bias_correction: BiasCorrection = BiasCorrection::Pairwise, ParamKind::Choice(BIAS_CORRECTION_NAMES), "GI bias correction",
                    "pairwise (default): pairwise MIS with each target expressed in this \
                        pixel's measure through the Jacobian (unbiased). one-over-m: 1/M \
                        weights with rejection (biased: darker where a neighbour cannot see \
                        or reconnect part of this pixel's hemisphere).";
            }
        }
    };
}
pub(crate) use rows;
