//! The rows of the parameter table (settings.rs) that belong to no one technique: the light
//! samplers (which serve DI, GI, PT and the reference alike), the reuse validation DI, GI
//! and PT share, shading and the reference, and the ray backend. Tokens for
//! `gather_rows!`: names such as `ParamKind` resolve in settings.rs, where the table is
//! expanded.

/// Appends these rows to the tokens it is given and hands them to `$then` with the rest of
/// the list (`settings::gather_rows!`).
macro_rules! rows {
    ($then:ident [$($rest:ident),*] $($rows:tt)*) => {
        $then! {
            [$($rest),*] $($rows)*
            Initial {
                light_sampler: LightSampler = LightSampler::Auto, ParamKind::Choice(LIGHT_SAMPLER_NAMES), "Light sampler",
                    "Where the light candidates come from (docs/src/light-samplers.md). \
                        power: the alias table over all lights. tiles: 128 tiles of 1024 \
                        lights presampled by power once per frame, one per 16×16 pixel block \
                        — the same distribution from a small shared working set. regir: \
                        world-space cells around the camera whose slots are refilled every \
                        frame by RIS toward each cell's lights; a pixel reads a jittered \
                        cell. bvh: a light BVH walked by distance and orientation, each \
                        candidate's PDF exact. auto: by the scene, as the measurements say \
                        (docs/src/measured/many-lights.md, \"Light samplers at scale\").";
                regir_grid: u32 = 16, ParamKind::Int { min: 1, max: MAX_REGIR_GRID as i64 }, "ReGIR cells per side",
                    "The ReGIR grid is this many cells along each axis, centred on the \
                        camera and snapped to whole cells (docs/src/light-samplers.md, \
                        \"ReGIR\"). Outside it, candidates come from the power table.";
                regir_cell_size: f32 = 0.02, ParamKind::Float { min: 1e-4, max: 1.0 }, "ReGIR cell size",
                    "A cell's side as a fraction of the scene's diagonal.";
                regir_slots: u32 = 32, ParamKind::Int { min: 1, max: MAX_REGIR_SLOTS as i64 }, "ReGIR lights per cell",
                    "Slots per cell, each refilled every frame by RIS; a candidate reads \
                        one slot at random. Cells × slots is capped at 2^18: past it, fewer \
                        slots.";
                regir_build_samples: u32 = 4, ParamKind::Int { min: 1, max: 64 }, "ReGIR build samples",
                    "Power-sampled lights each slot resamples from, toward the cell's \
                        target (power over squared distance, zero where the cell lies wholly \
                        behind a one-sided emitter).";
                regir_build_from_bvh: bool = false, ParamKind::Bool, "ReGIR fed by the light BVH",
                    "Draw each slot's build samples from the light BVH walked at the \
                        cell's centre instead of the power table (a hybrid: \
                        docs/src/light-samplers.md, \"ReGIR fed by the tree\"), so cells \
                        find their near lights among a million. Unbiased either way; costs \
                        the tree's build and a walk per build sample.";
                regir_jitter: f32 = 1.0, ParamKind::Float { min: 0.0, max: 4.0 }, "ReGIR jitter",
                    "How far (in cells) a pixel's lookup point is jittered before its \
                        cell is found: 0 reads the pixel's own cell (visible cell edges), 1 \
                        blends neighbours. Any value is unbiased: each cell's target covers \
                        the pixels that may read it.";
                environment_share: f32 = 0.0, ParamKind::Float { min: 0.0, max: 0.99 }, "Environment share",
                    "Probability that a light sample is an environment direction. 0: by \
                        estimated power (π R² ∫L dω against the lights' power; \
                        docs/src/environment.md, \"Split with the other lights\"). Any value \
                        is unbiased; it only moves noise between sky and lights (an enclosed \
                        room under a bright sky wants less). Without an environment it does \
                        nothing.";
                bvh_at_vertices: bool = true, ParamKind::Bool, "Light BVH at path vertices",
                    "With the light BVH as the sampler: GI's and PT's path vertices and \
                        transparent layers draw their light samples from the tree too, each \
                        weighed against BSDF sampling with the tree's PDF at that vertex \
                        (docs/src/light-samplers.md, \"At every vertex\"). Off: the power \
                        table there. Either is unbiased; the tree sends a vertex's samples \
                        to the lights near it.";
                light_bvh_gpu_refit: bool = true, ParamKind::Bool, "Light BVH refit on the GPU",
                    "When lights move or change power, refit the light BVH in a compute \
                        pass (one dispatch per tree level above the changed lights) instead \
                        of on the CPU (docs/src/light-samplers.md, \"Moving lights\"). The \
                        same tree either way, within float rounding of the cone bounds.";
            }
            Validation {
                normal_threshold: f32 = 0.906, ParamKind::Float { min: 0.0, max: 1.0 }, "Normal threshold",
                    "Reject a previous or neighbouring surface when the cosine between \
                        its normal and this one is below this (0.906 = 25°).";
                depth_threshold: f32 = 0.1, ParamKind::Float { min: 0.0, max: 1.0 }, "Depth threshold",
                    "Reject when the world-position distance (temporal) or depth \
                        difference (spatial) exceeds this fraction of the view depth.";
                check_offscreen: bool = true, ParamKind::Bool, "Check: off-screen",
                    "Reject a reprojection (or neighbour) outside the image. Off: the \
                        coordinate is clamped to the border.";
                check_surface: bool = true, ParamKind::Bool, "Check: surface valid",
                    "Reject when the previous (or neighbouring) pixel saw no surface, or \
                        the history was invalidated (resize, scene change, camera cut).";
                check_material: bool = true, ParamKind::Bool, "Check: material id",
                    "Reject when the material id differs.";
                check_normal: bool = true, ParamKind::Bool, "Check: normal",
                    "Reject when the normals disagree by more than the normal threshold.";
                check_depth: bool = true, ParamKind::Bool, "Check: position / depth",
                    "Reject when positions (temporal) or depths (spatial) differ by more \
                        than the depth threshold.";
                check_reservoir: bool = true, ParamKind::Bool, "Check: reservoir null",
                    "1/M: reject a previous or neighbouring reservoir that holds no \
                        sample. Pairwise MIS: counted, not rejected (a null sample is a \
                        sample of its domain: it contributes nothing, its M counts).";
                check_target: bool = true, ParamKind::Bool, "Check: target > 0",
                    "1/M: reject a temporal or spatial sample whose target re-evaluated \
                        here is zero. Pairwise MIS: counted, not rejected (it contributes \
                        nothing, its domain's M counts; rejecting it made the image \
                        brighter).";
            }
            Shading {
                jitter: bool = true, ParamKind::Bool, "Sub-pixel jitter",
                    "Jitter the G-buffer inside the pixel every frame, so accumulated \
                        frames converge to the pixel-area average (antialiased). Off: every \
                        pass, the reference included, sees the pixel centre, so comparisons \
                        measure lighting error alone.";
                reference_light_bvh: bool = false, ParamKind::Bool, "Reference: light BVH",
                    "The reference samples lights with the light BVH at every vertex \
                        instead of the power table. Off (default): the power table whatever \
                        the light sampler, so the reference stays independent of the \
                        estimators it checks; the two references agree \
                        (render/tests/vertex_light_sampler.rs) and the tree's converges \
                        faster where lights are many and local (docs/src/light-samplers.md, \
                        \"At every vertex\").";
                reference_spp: u32 = 4, ParamKind::Int { min: 1, max: 4096 }, "Reference spp",
                    "Samples per pixel per frame of the reference renderer.";
                reference_light_samples: u32 = 1,
                    ParamKind::Int { min: 1, max: MAX_REFERENCE_LIGHT_SAMPLES as i64 },
                    "Reference light samples",
                    "Light samples (each with its shadow ray) at every vertex of a reference \
                        path, weighed with its one BSDF sample by the multi-sample balance \
                        heuristic (docs/src/frame.md, \"The reference\"). Unbiased at any \
                        count; more spends a sample's camera ray and path on more of the \
                        light, which is where a scene of many small lights is noisy. At \
                        most 16 per path (count × bounces; lavapipe's loop bound): 8 at 2 \
                        bounces. 1: the reference as it always was, to the bit.";
                max_bounces: u32 = 1, ParamKind::Int { min: 1, max: MAX_BOUNCES as i64 }, "Max bounces",
                    "Path vertices the reference shades. 1: emission seen directly + \
                        direct light at the first hit (what nee, ris and restir estimate). \
                        N: the path continues along the BSDF-sampled ray, with direct light \
                        (light sampling + BSDF sampling, balance heuristic) at each of its \
                        first N hits, so 2 adds one bounce of indirect light. Every bounce \
                        costs two more rays per sample.";
            }
            Tracing {
                ray_backend: RayBackendChoice = RayBackendChoice::Auto, ParamKind::Choice(RAY_BACKEND_NAMES), "Ray backend",
                    "What traces every ray (shadow rays, BSDF rays, camera and path \
                        rays): software, the BVH built on the CPU and walked in WGSL (any \
                        adapter); ray-query, the driver's acceleration structures through \
                        ray queries (VK_KHR_ray_query: NVIDIA, AMD, Intel GPUs, and Mesa \
                        25's lavapipe on the CPU); auto, ray queries on a GPU that has them, \
                        software on a CPU adapter (lavapipe's ray queries run on the CPU too \
                        and trace fewer rays per second than the BVH there, measured in \
                        docs/src/measured/compile-and-load.md \"Ray queries\"). Both give the \
                        same image (ties between equally near hits \
                        may resolve differently); the Stats panel names the one running.";
            }
        }
    };
}
pub(crate) use rows;
