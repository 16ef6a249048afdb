//! Every pipeline parameter in one table: name, stage, label, documentation, range and
//! default. The viewer's panels, `--set`, presets and `restir-viewer params` all read this
//! table, and the same name is used in WGSL (`Params` in types.wgsl) and in the UI.
//! Defaults are what the measurements favour; the book gives each one's figures in the
//! chapter of its stage, and its parameters page (docs/src/parameters.md) is generated
//! from this table.

use std::fmt;
use std::path::Path;

use crate::gpu_types::GpuParams;
use crate::shader_constants::*;

/// The stage a parameter belongs to (the viewer groups them by this).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    Initial,
    Temporal,
    Spatial,
    /// The checks that decide whether a previous or neighbouring pixel takes part, shared
    /// by temporal and spatial reuse (DI, GI and PT alike).
    Validation,
    Resampling,
    Shading,
    Tracing,
    Indirect,
    Denoise,
}

impl Stage {
    pub fn label(self) -> &'static str {
        match self {
            Stage::Initial => "Initial candidates",
            Stage::Temporal => "Temporal reuse",
            Stage::Spatial => "Spatial reuse",
            Stage::Validation => "Reuse validation",
            Stage::Resampling => "Bias correction",
            Stage::Shading => "Shading and reference",
            Stage::Tracing => "Ray tracing",
            Stage::Indirect => "Indirect",
            Stage::Denoise => "Denoiser",
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum ParamValue {
    Bool(bool),
    Int(i64),
    Float(f64),
    Choice(String),
}

impl fmt::Display for ParamValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParamValue::Bool(b) => write!(f, "{b}"),
            ParamValue::Int(i) => write!(f, "{i}"),
            ParamValue::Float(x) => write!(f, "{x}"),
            ParamValue::Choice(s) => write!(f, "{s}"),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamKind {
    Bool,
    Int { min: i64, max: i64 },
    Float { min: f64, max: f64 },
    Choice(&'static [&'static str]),
}

/// What a row does beyond setting its value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    Plain,
    /// Switches a reuse stage on (temporal or spatial reuse of a technique): the nee and
    /// ris modes turn every such row off (`Settings::without_reuse`).
    ReuseSwitch,
}

/// One row of the parameter table.
#[derive(Clone, Copy, Debug)]
pub struct ParamDef {
    pub name: &'static str,
    pub stage: Stage,
    pub label: &'static str,
    pub doc: &'static str,
    pub kind: ParamKind,
    pub role: Role,
}

impl ParamDef {
    pub fn default_value(&self) -> ParamValue {
        Settings::default()
            .get(self.name)
            .expect("every table row is a field")
    }
}

/// How reused samples are weighted (docs/src/mis-and-bias.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BiasCorrection {
    /// 1/M weights with rejection: fast, biased near geometric and lighting discontinuities.
    OneOverM,
    /// Defensive pairwise MIS with the pixel's own sample as canonical: unbiased.
    Pairwise,
}

pub const BIAS_CORRECTION_NAMES: &[&str] = &["one-over-m", "pairwise"];

/// How ReSTIR PT moves a path found at one pixel to another (docs/src/restir-pt.md, "Shift
/// mappings"; the CPU model's `path_reuse::shift::Shift`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PtShift {
    /// Keep every vertex after the primary; connect the new primary to the second.
    Reconnection,
    /// Trace again from the new primary with the path's random numbers.
    RandomReplay,
    /// Replay up to the first bounce with two rough ends far enough apart, reconnect there.
    Hybrid,
}

pub const PT_SHIFT_NAMES: &[&str] = &["reconnection", "random-replay", "hybrid"];

impl PtShift {
    /// The shader's `PT_SHIFT_*`.
    pub fn gpu(self) -> u32 {
        match self {
            PtShift::Reconnection => PT_SHIFT_RECONNECTION,
            PtShift::RandomReplay => PT_SHIFT_RANDOM_REPLAY,
            PtShift::Hybrid => PT_SHIFT_HYBRID,
        }
    }
}

/// Where DI's light candidates come from (docs/src/light-samplers.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSampler {
    /// Chosen by the scene, as the measurements say (`effects::resolve_light_sampler`).
    Auto,
    /// The power alias table over every light.
    Power,
    /// Presampled light tiles: the power distribution from a small shared working set.
    Tiles,
    /// World-space cells of lights resampled for each cell every frame (ReGIR).
    Regir,
    /// A light BVH walked stochastically by distance and orientation.
    Bvh,
}

pub const LIGHT_SAMPLER_NAMES: &[&str] = &["auto", "power", "tiles", "regir", "bvh"];

impl LightSampler {
    pub fn name(self) -> &'static str {
        match self {
            LightSampler::Auto => "auto",
            LightSampler::Power => "power",
            LightSampler::Tiles => "tiles",
            LightSampler::Regir => "regir",
            LightSampler::Bvh => "bvh",
        }
    }
}

/// Which implementation traces the renderer's rays (`tracing.rs`): every pass calls the
/// same functions of shaders/common/trace.wgsl; this picks what is compiled behind them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayBackendChoice {
    /// Ray queries on a GPU that has them, else the software BVH (also on CPU adapters,
    /// whose ray queries are slower than it: docs/bench.md "Ray queries").
    Auto,
    /// The BVH built on the CPU, traversed in WGSL (every adapter).
    Software,
    /// Hardware ray queries (wgpu `EXPERIMENTAL_RAY_QUERY`, Vulkan `VK_KHR_ray_query`).
    RayQuery,
}

pub const RAY_BACKEND_NAMES: &[&str] = &["auto", "software", "ray-query"];

/// Conversion between a typed field and the table's dynamic value.
trait Param: Sized {
    fn to_value(&self) -> ParamValue;
    fn from_value(value: &ParamValue) -> Option<Self>;
}

impl Param for bool {
    fn to_value(&self) -> ParamValue {
        ParamValue::Bool(*self)
    }
    fn from_value(value: &ParamValue) -> Option<Self> {
        match value {
            ParamValue::Bool(b) => Some(*b),
            _ => None,
        }
    }
}

impl Param for u32 {
    fn to_value(&self) -> ParamValue {
        ParamValue::Int(*self as i64)
    }
    fn from_value(value: &ParamValue) -> Option<Self> {
        match value {
            ParamValue::Int(i) => u32::try_from(*i).ok(),
            _ => None,
        }
    }
}

impl Param for f32 {
    fn to_value(&self) -> ParamValue {
        // Through the shortest decimal form, so 0.906 shows as 0.906, not 0.906000018.
        ParamValue::Float(self.to_string().parse().unwrap_or(*self as f64))
    }
    fn from_value(value: &ParamValue) -> Option<Self> {
        match value {
            ParamValue::Float(x) => Some(*x as f32),
            ParamValue::Int(i) => Some(*i as f32),
            _ => None,
        }
    }
}

/// A choice parameter: an enum whose variants pair one-to-one with a names table.
macro_rules! choice_param {
    ($ty:ident, $names:ident, [$($variant:ident),*]) => {
        impl Param for $ty {
            fn to_value(&self) -> ParamValue {
                let index = [$($ty::$variant),*]
                    .iter()
                    .position(|v| v == self)
                    .expect("every variant is listed");
                ParamValue::Choice($names[index].to_string())
            }
            fn from_value(value: &ParamValue) -> Option<Self> {
                let ParamValue::Choice(s) = value else {
                    return None;
                };
                let index = $names.iter().position(|n| n == s)?;
                [$($ty::$variant),*].get(index).copied()
            }
        }
    };
}

choice_param!(BiasCorrection, BIAS_CORRECTION_NAMES, [OneOverM, Pairwise]);
choice_param!(
    LightSampler,
    LIGHT_SAMPLER_NAMES,
    [Auto, Power, Tiles, Regir, Bvh]
);
choice_param!(
    PtShift,
    PT_SHIFT_NAMES,
    [Reconnection, RandomReplay, Hybrid]
);
choice_param!(
    RayBackendChoice,
    RAY_BACKEND_NAMES,
    [Auto, Software, RayQuery]
);

/// A row's role: `Plain` unless the row names one after its documentation.
macro_rules! row_role {
    () => {
        Role::Plain
    };
    ($role:ident) => {
        Role::$role
    };
}

macro_rules! parameter_table {
    ($( $stage:ident { $( $field:ident : $ty:ty = $default:expr, $kind:expr, $label:literal, $doc:literal $(, $role:ident)?; )* } )*) => {
        /// Every pipeline parameter (see the module docs).
        #[derive(Clone, Debug, PartialEq)]
        pub struct Settings { $( $( #[doc = $doc] pub $field: $ty, )* )* }

        impl Default for Settings {
            fn default() -> Self {
                Self { $( $( $field: $default, )* )* }
            }
        }

        /// The parameter table, in display order.
        pub static PARAMS: &[ParamDef] = &[
            $( $( ParamDef { name: stringify!($field), stage: Stage::$stage, label: $label, doc: $doc, kind: $kind, role: row_role!($($role)?) }, )* )*
        ];

        impl Settings {
            /// The current value of a parameter by name.
            pub fn get(&self, name: &str) -> Option<ParamValue> {
                match name {
                    $( $( stringify!($field) => Some(self.$field.to_value()), )* )*
                    _ => None,
                }
            }

            /// Stores an already range-checked value; false on a type mismatch.
            fn store(&mut self, name: &str, value: &ParamValue) -> bool {
                match name {
                    $( $( stringify!($field) => match <$ty as Param>::from_value(value) {
                        Some(v) => { self.$field = v; true }
                        None => false,
                    }, )* )*
                    _ => false,
                }
            }
        }
    };
}

parameter_table! {
    Initial {
        light_candidates: u32 = 32, ParamKind::Int { min: 0, max: 256 }, "Light candidates",
            "Light samples per pixel drawn by the light sampler and streamed through the reservoir (docs/src/ris.md, \"The streaming reservoir\"). 1 light and 0 BSDF candidates is plain NEE. When light_sampler=auto takes the light BVH, at most 4 (its equal-time best within a tenth of the frame: docs/src/light-samplers.md, \"Choosing\").";
        bsdf_candidates: u32 = 1, ParamKind::Int { min: 0, max: 16 }, "BSDF candidates",
            "BSDF-sampled rays per pixel; those that hit an emitter join the reservoir, combined with the light candidates by the balance heuristic.";
        light_sampler: LightSampler = LightSampler::Auto, ParamKind::Choice(LIGHT_SAMPLER_NAMES), "Light sampler",
            "Where the light candidates come from (docs/src/light-samplers.md). power: the alias table over all lights. tiles: 128 tiles of 1024 lights presampled by power once per frame, one per 16×16 pixel block — the same distribution from a small shared working set. regir: world-space cells around the camera whose slots are refilled every frame by RIS toward each cell's lights; a pixel reads a jittered cell. bvh: a light BVH walked by distance and orientation, each candidate's PDF exact. auto: by the scene, as the measurements say (docs/bench.md, \"Light samplers at scale\").";
        regir_grid: u32 = 16, ParamKind::Int { min: 1, max: MAX_REGIR_GRID as i64 }, "ReGIR cells per side",
            "The ReGIR grid is this many cells along each axis, centred on the camera and snapped to whole cells (docs/src/light-samplers.md, \"ReGIR\"). Outside it, candidates come from the power table.";
        regir_cell_size: f32 = 0.02, ParamKind::Float { min: 1e-4, max: 1.0 }, "ReGIR cell size",
            "A cell's side as a fraction of the scene's diagonal.";
        regir_slots: u32 = 32, ParamKind::Int { min: 1, max: MAX_REGIR_SLOTS as i64 }, "ReGIR lights per cell",
            "Slots per cell, each refilled every frame by RIS; a candidate reads one slot at random. Cells × slots is capped at 2^18: past it, fewer slots.";
        regir_build_samples: u32 = 4, ParamKind::Int { min: 1, max: 64 }, "ReGIR build samples",
            "Power-sampled lights each slot resamples from, toward the cell's target (power over squared distance, zero where the cell lies wholly behind a one-sided emitter).";
        regir_build_from_bvh: bool = false, ParamKind::Bool, "ReGIR fed by the light BVH",
            "Draw each slot's build samples from the light BVH walked at the cell's centre instead of the power table (a hybrid: docs/src/light-samplers.md, \"ReGIR fed by the tree\"), so cells find their near lights among a million. Unbiased either way; costs the tree's build and a walk per build sample.";
        regir_jitter: f32 = 1.0, ParamKind::Float { min: 0.0, max: 4.0 }, "ReGIR jitter",
            "How far (in cells) a pixel's lookup point is jittered before its cell is found: 0 reads the pixel's own cell (visible cell edges), 1 blends neighbours. Any value is unbiased: each cell's target covers the pixels that may read it.";
        environment_share: f32 = 0.0, ParamKind::Float { min: 0.0, max: 0.99 }, "Environment share",
            "Probability that a light sample is an environment direction. 0: by estimated power (π R² ∫L dω against the lights' power; docs/src/environment.md, \"Split with the other lights\"). Any value is unbiased; it only moves noise between sky and lights (an enclosed room under a bright sky wants less). Without an environment it does nothing.";
        bvh_at_vertices: bool = true, ParamKind::Bool, "Light BVH at path vertices",
            "With the light BVH as the sampler: GI's and PT's path vertices and transparent layers draw their light samples from the tree too, each weighed against BSDF sampling with the tree's PDF at that vertex (docs/src/light-samplers.md, \"At every vertex\"). Off: the power table there. Either is unbiased; the tree sends a vertex's samples to the lights near it.";
        light_bvh_gpu_refit: bool = true, ParamKind::Bool, "Light BVH refit on the GPU",
            "When lights move or change power, refit the light BVH in a compute pass (one dispatch per tree level above the changed lights) instead of on the CPU (docs/src/light-samplers.md, \"Moving lights\"). The same tree either way, within float rounding of the cone bounds.";
        initial_visibility: bool = true, ParamKind::Bool, "Initial visibility",
            "Trace the survivor's shadow ray right after initial sampling and drop it when occluded (visibility reuse: docs/src/ris.md, \"Visibility reuse\"), so reuse only spreads samples that were visible. One extra shadow ray per pixel.";
    }
    Temporal {
        temporal: bool = true, ParamKind::Bool, "Temporal reuse",
            "Merge the reprojected previous-frame reservoir (docs/src/temporal-reuse.md). Off: the temporal pass is not dispatched.", ReuseSwitch;
        target_ratio_clamp: f32 = 10.0, ParamKind::Float { min: 1.0, max: 1e6 }, "Target-ratio clamp",
            "1/M: reject the temporal sample when p̂(x, y_prev) / p̂(x_prev, y_prev) is outside [1/clamp, clamp]; 1 rejects any change of target. Pairwise MIS: a window on that ratio for both samples alike — outside it the history's sample gets weight 0, and where this pixel's own sample is outside it the pixel keeps the history's share — so the weights still sum to one and the clamp stays unbiased (a rejection of the history alone would not).";
        permutation: bool = true, ParamKind::Bool, "Permutation sampling",
            "Read the previous reservoir through a per-frame 4×4 pixel permutation to decorrelate neighbours; fall back to the plain reprojected pixel when that read fails validation.";
        check_target_ratio: bool = true, ParamKind::Bool, "Check: target ratio",
            "Apply the target-ratio clamp (off disables the test whatever the clamp; under pairwise MIS the clamp is an unbiased window, see the clamp).";
        camera_cut: f32 = 0.25, ParamKind::Float { min: 0.0, max: 100.0 }, "Camera cut distance",
            "A camera jump longer than this fraction of the scene size in one frame is a cut: history is dropped. 0 treats every move as a cut.";
    }
    Spatial {
        spatial: bool = true, ParamKind::Bool, "Spatial reuse",
            "Merge reservoirs of nearby pixels (docs/src/spatial-reuse.md). Off: no spatial pass is dispatched.", ReuseSwitch;
        spatial_neighbours: u32 = 5, ParamKind::Int { min: 0, max: MAX_SPATIAL_NEIGHBOURS as i64 }, "Neighbours",
            "Neighbours tried per pixel and pass, uniformly in a disk.";
        spatial_radius: f32 = 30.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "Radius (px at 1080p)",
            "Radius of the neighbour disk in pixels of a 1080-pixel-high image; other sizes use radius × height / 1080, at least 2 px (or the radius itself if smaller), so reuse spans the same part of the scene at any resolution or render scale.";
        spatial_passes: u32 = 1, ParamKind::Int { min: 1, max: MAX_SPATIAL_PASSES as i64 }, "Passes",
            "Spatial passes per frame, each reading the previous pass's output.";
        boiling_filter: f32 = 0.0, ParamKind::Float { min: 0.0, max: 1000.0 }, "Boiling filter",
            "Drop a pixel's sample when its W·p̂ exceeds this many times the neighbourhood mean (docs/src/spatial-reuse.md, \"The boiling filter\"). 0 = off. Biased: the decision looks at the sample's value, so it darkens (2: −3.5 % on a frozen blinking-lights at M cap 100, −5 % on the concourse) while it lowers flicker (docs/bench.md, \"Boiling\").";
    }
    Validation {
        normal_threshold: f32 = 0.906, ParamKind::Float { min: 0.0, max: 1.0 }, "Normal threshold",
            "Reject a previous or neighbouring surface when the cosine between its normal and this one is below this (0.906 = 25°).";
        depth_threshold: f32 = 0.1, ParamKind::Float { min: 0.0, max: 1.0 }, "Depth threshold",
            "Reject when the world-position distance (temporal) or depth difference (spatial) exceeds this fraction of the view depth.";
        check_offscreen: bool = true, ParamKind::Bool, "Check: off-screen",
            "Reject a reprojection (or neighbour) outside the image. Off: the coordinate is clamped to the border.";
        check_surface: bool = true, ParamKind::Bool, "Check: surface valid",
            "Reject when the previous (or neighbouring) pixel saw no surface, or the history was invalidated (resize, scene change, camera cut).";
        check_material: bool = true, ParamKind::Bool, "Check: material id",
            "Reject when the material id differs.";
        check_normal: bool = true, ParamKind::Bool, "Check: normal",
            "Reject when the normals disagree by more than the normal threshold.";
        check_depth: bool = true, ParamKind::Bool, "Check: position / depth",
            "Reject when positions (temporal) or depths (spatial) differ by more than the depth threshold.";
        check_reservoir: bool = true, ParamKind::Bool, "Check: reservoir null",
            "1/M: reject a previous or neighbouring reservoir that holds no sample. Pairwise MIS: counted, not rejected (a null sample is a sample of its domain: it contributes nothing, its M counts).";
        check_target: bool = true, ParamKind::Bool, "Check: target > 0",
            "1/M: reject a temporal or spatial sample whose target re-evaluated here is zero. Pairwise MIS: counted, not rejected (it contributes nothing, its domain's M counts; rejecting it made the image brighter).";
    }
    Resampling {
        m_cap: f32 = 20.0, ParamKind::Float { min: 0.0, max: 1e6 }, "M cap",
            "Upper bound of a reservoir's confidence M (direct light). History is merged with min(M_prev, M cap), and M is capped after every reuse pass, temporal and spatial. M counts frames' worth of samples.";
        bias_correction: BiasCorrection = BiasCorrection::Pairwise, ParamKind::Choice(BIAS_CORRECTION_NAMES), "Bias correction",
            "pairwise (default): defensive pairwise MIS with the pixel's own reservoir as canonical (unbiased, one extra target evaluation per neighbour, ~3 % of the frame). one-over-m: 1/M weights with rejection (biased: darker where reused samples are occluded or outside a narrow lobe; fast).";
        mis_visibility: bool = true, ParamKind::Bool, "MIS visibility",
            "Pairwise: the target is p̂·V (visibility included) at every pixel and in every MIS term, as unbiased reuse of visibility-tested samples requires (RTXDI's ray-traced bias correction): each reused sample is traced from here before it can be picked, this pixel's sample from each spatial neighbour and from the previous pixel (against this frame's geometry). Implies initial visibility; shading then traces no ray (the survivor is known visible). Costs 2 shadow rays per spatial neighbour and 2 per temporal merge. Off: unshadowed MIS terms: darker where neighbours are shadowed differently (sun-lit Cornell box −5 %) and black speckles where a pixel picks a sample it cannot see.";
        previous_lights: bool = true, ParamKind::Bool, "Previous-frame lights",
            "Animated scenes, pairwise MIS: evaluate this pixel's own (canonical) sample at the previous pixel with last frame's lights — positions, emission, punctual records — as unbiasedness requires. Off: with the current lights, a common shortcut; then a light switched on stays too dark for a few frames (its new samples are weighted as if the history could have found them). Static scenes: no difference.";
        previous_geometry: bool = true, ParamKind::Bool, "Previous-frame geometry",
            "Animated scenes, pairwise MIS with MIS visibility: trace the visibility of this pixel's own sample at the previous pixel against last frame's geometry (last frame's TLAS with ray queries, last frame's BVH boxes and triangles with the software backend), as unbiasedness requires. Off: against this frame's geometry, a common shortcut; then a moving occluder credits the previous pixel with samples it could not see (builtin:dynamic:moving-occluder 2 % dark). Static scenes: no difference.";
        mutations: u32 = 0, ParamKind::Int { min: 0, max: MAX_MUTATIONS as i64 }, "MCMC mutations",
            "Metropolis–Hastings steps applied to each pixel's light sample after the last reuse pass, toward the pixel's own target (Sawhney et al. 2024; docs/src/mcmc-mutation.md). Each step slides the point on its triangle light or proposes a fresh power-table sample; W is rescaled by T(y)/T(y'), so the image stays unbiased while neighbours and frames stop sharing one sample. Runs only where reuse is on. 0 = off. Each step costs one target evaluation, and with MIS visibility a shadow ray when the step could be accepted.";
        mutation_step: f32 = 0.1, ParamKind::Float { min: 1e-4, max: 1.0 }, "Mutation step",
            "Largest slide of a local mutation in barycentric units of the triangle light (0.1: a tenth of the triangle). Any value is unbiased; small steps are accepted more often and move less.";
    }
    Shading {
        jitter: bool = true, ParamKind::Bool, "Sub-pixel jitter",
            "Jitter the G-buffer inside the pixel every frame, so accumulated frames converge to the pixel-area average (antialiased). Off: every pass, the reference included, sees the pixel centre, so comparisons measure lighting error alone.";
        reference_light_bvh: bool = false, ParamKind::Bool, "Reference: light BVH",
            "The reference samples lights with the light BVH at every vertex instead of the power table. Off (default): the power table whatever the light sampler, so the reference stays independent of the estimators it checks; the two references agree (render/tests/vertex_light_sampler.rs) and the tree's converges faster where lights are many and local (docs/src/light-samplers.md, \"At every vertex\").";
        reference_spp: u32 = 4, ParamKind::Int { min: 1, max: 4096 }, "Reference spp",
            "Samples per pixel per frame of the reference renderer.";
        max_bounces: u32 = 1, ParamKind::Int { min: 1, max: MAX_BOUNCES as i64 }, "Max bounces",
            "Path vertices the reference shades. 1: emission seen directly + direct light at the first hit (what nee, ris and restir estimate). N: the path continues along the BSDF-sampled ray, with direct light (light sampling + BSDF sampling, balance heuristic) at each of its first N hits, so 2 adds one bounce of indirect light. Every bounce costs two more rays per sample.";
    }
    Tracing {
        ray_backend: RayBackendChoice = RayBackendChoice::Auto, ParamKind::Choice(RAY_BACKEND_NAMES), "Ray backend",
            "What traces every ray (shadow rays, BSDF rays, camera and path rays): software, the BVH built on the CPU and walked in WGSL (any adapter); ray-query, the driver's acceleration structures through ray queries (VK_KHR_ray_query: NVIDIA, AMD, Intel GPUs, and Mesa 25's lavapipe on the CPU); auto, ray queries on a GPU that has them, software on a CPU adapter (lavapipe's ray queries run on the CPU too and measured 0.3–0.7× the BVH's rays per second, docs/bench.md \"Ray queries\"). Both give the same image (ties between equally near hits may resolve differently); the Stats panel names the one running.";
    }
    Indirect {
        gi: bool = false, ParamKind::Bool, "Indirect (ReSTIR GI)",
            "One-bounce indirect light with reservoir reuse (Ouyang et al. 2021): one BSDF ray per pixel, its hit's outgoing direct radiance as the sample, reused over time and space through the reconnection Jacobian. The image is direct (ReSTIR DI) + indirect. Off: no GI code is compiled or run.";
        gi_temporal: bool = true, ParamKind::Bool, "GI temporal reuse",
            "Merge the reprojected previous-frame GI reservoir, its sample reconnected to this frame's visible point.", ReuseSwitch;
        gi_spatial: bool = true, ParamKind::Bool, "GI spatial reuse",
            "Merge GI reservoirs of nearby pixels, each sample reconnected to this pixel's visible point.", ReuseSwitch;
        gi_m_cap: f32 = 10.0, ParamKind::Float { min: 0.0, max: 1e6 }, "GI M cap",
            "Upper bound of a GI reservoir's confidence M (as M cap for direct light, separately). 10, half the direct light's: a GI sample's cached radiance is never re-evaluated, so it outlives a lighting change for about M cap frames (recovery took ~M cap frames for direct light, docs/bench.md \"Lag and ghosting\").";
        gi_light_candidates: u32 = 0, ParamKind::Int { min: 0, max: 256 }, "GI light candidates",
            "Light candidates of the RIS at GI's secondary vertex (the direct light its sample carries). 0: DI's `light_candidates`. With the light BVH at the vertices a few of its candidates do what 32 of the table's do, for an eighth of the walks (docs/bench.md, \"At every vertex\").";
        gi_spatial_neighbours: u32 = 3, ParamKind::Int { min: 0, max: MAX_SPATIAL_NEIGHBOURS as i64 }, "GI neighbours",
            "Neighbours tried per pixel in GI spatial reuse. 3, fewer than direct light's 5: each one costs a reconnection shadow ray when GI reconnection visibility is on.";
        gi_spatial_radius: f32 = 30.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "GI radius (px at 1080p)",
            "Radius of the GI neighbour disk in pixels of a 1080-pixel-high image, scaled with the height like the direct light's radius (at least 2 px).";
        gi_jacobian_max: f32 = 10.0, ParamKind::Float { min: 1.0, max: 1000.0 }, "GI Jacobian window",
            "Reject a reconnected sample when its Jacobian |J| is outside [1/max, max]: a sample that the other pixel saw much larger or smaller than this one would (near geometry, grazing angles) carries a weight out of proportion, the source of GI fireflies. Symmetric, so pairwise MIS stays unbiased; 1 accepts only |J| = 1.";
        gi_spatial_visibility: bool = true, ParamKind::Bool, "GI reconnection visibility",
            "Trace a shadow ray from this pixel's visible point to each spatial neighbour's sample point and drop the sample when occluded. Off: one ray fewer per neighbour, biased: light leaks through occluders (+9 % behind a blocker hiding 40 % of the light in the CPU test scene, gi/model/visibility_tests.rs).";
        gi_mis_visibility: bool = true, ParamKind::Bool, "GI MIS visibility",
            "Pairwise, with GI reconnection visibility: also trace from each neighbour's visible point to this pixel's own sample point, so its MIS weight knows which neighbours could have found it. Off: one ray fewer per neighbour, darker behind occluders (−5 % in the same test; unbiased with it on).";
        gi_bias_correction: BiasCorrection = BiasCorrection::Pairwise, ParamKind::Choice(BIAS_CORRECTION_NAMES), "GI bias correction",
            "pairwise (default): pairwise MIS with each target expressed in this pixel's measure through the Jacobian (unbiased). one-over-m: 1/M weights with rejection (biased: darker where a neighbour cannot see or reconnect part of this pixel's hemisphere).";
        pt: bool = false, ParamKind::Bool, "Indirect (ReSTIR PT)",
            "Multi-bounce indirect light with path reuse (GRIS / ReSTIR PT, Lin et al. 2022): each pixel traces one path of up to max_bounces (at least 2) bounces with next-event estimation and MIS at every vertex past the first; its sub-paths are the candidates of one path reservoir, reused over time and space through a shift mapping (pt_shift) under pairwise MIS. The image is direct (ReSTIR DI) + indirect; replaces ReSTIR GI while on. Off: no PT code is compiled or run.";
        pt_shift: PtShift = PtShift::Hybrid, ParamKind::Choice(PT_SHIFT_NAMES), "PT shift mapping",
            "How a neighbour's path is moved to this pixel. reconnection: keep its vertices from the second on and connect to it (fails where the first bounce is glossy: the new angle misses the lobe). random-replay: trace again with its random numbers (fails when the replayed path leaves it; exact in glossy chains). hybrid (default): replay up to the first bounce whose two ends are rough (pt_rough_threshold) and far enough apart (pt_min_distance), reconnect there. All three unbiased under pairwise MIS: a path that cannot be moved is a zero in its domain, never dropped.";
        pt_temporal: bool = true, ParamKind::Bool, "PT temporal reuse",
            "Merge the reprojected previous-frame path reservoir, its path shifted from last frame's visible point to this one (and this pixel's path shifted back there for the pairwise weights). The previous side is evaluated in this frame's scene: exact for static scenes; under animation a moving occluder is seen where it is now, not where it was (named biased, as DI's previous_geometry=false).", ReuseSwitch;
        pt_m_cap: f32 = 10.0, ParamKind::Float { min: 0.0, max: 1e6 }, "PT M cap",
            "Upper bound of a path reservoir's confidence M. 10, as GI's: a reconnected path's radiance beyond its reconnection vertex is cached, not re-evaluated, so it outlives a lighting change for about M cap frames.";
        pt_spatial: bool = true, ParamKind::Bool, "PT spatial reuse",
            "Merge the path reservoirs of nearby pixels, each path shifted to this pixel (and this pixel's path shifted to each of them for the pairwise weights).", ReuseSwitch;
        pt_spatial_neighbours: u32 = 3, ParamKind::Int { min: 0, max: MAX_SPATIAL_NEIGHBOURS as i64 }, "PT neighbours",
            "Neighbours tried per pixel in PT spatial reuse; each costs two shifts (a replayed prefix is up to max_bounces − 1 rays, a reconnection one visibility ray).";
        pt_spatial_radius: f32 = 30.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "PT radius (px at 1080p)",
            "Radius of the PT neighbour disk in pixels of a 1080-pixel-high image, scaled with the height (at least 2 px).";
        pt_rough_threshold: f32 = 0.3, ParamKind::Float { min: 0.0, max: 1.0 }, "PT roughness threshold",
            "Hybrid shift: a vertex is rough enough to reconnect at when its material roughness is at least this, or it has no specular lobe. 0: every vertex (hybrid = reconnection at the first far-enough pair); 1: only purely rough ones.";
        pt_min_distance: f32 = 0.02, ParamKind::Float { min: 0.0, max: 1.0 }, "PT reconnection distance",
            "Hybrid shift: the two ends of the reconnected segment must be at least this far apart, as a fraction of the scene's size (the diagonal of its bounding box, not world units: 0.02 is 2 % of it). A near reconnection has a Jacobian far from 1.";
        pt_jacobian_clamp: f32 = 0.0, ParamKind::Float { min: 0.0, max: 1000.0 }, "PT Jacobian clamp (biased)",
            "Biased, off by default (0): clamp every shift's |J| into [1/c, c] (c ≥ 1). Bounds the fireflies of near or grazing reconnections at the price of a wrong change of measure: the image is no longer the integral (docs/bench.md measures how far off).";
    }
    Denoise {
        denoise: bool = false, ParamKind::Bool, "Denoiser (SVGF)",
            "A spatiotemporal variance-guided filter after shading (Schied et al. 2017; docs/src/denoiser.md): the frame's light (direct + indirect, one signal) is divided by the surface colour, accumulated over time through the motion vectors, and blurred by à-trous passes that stop at depth, normal and luminance edges scaled by the estimated variance, then multiplied back. Every figure (error, flicker, boiling, lag) is then measured on the denoised image. Off: no denoiser code is compiled or run.";
        denoise_gradients: bool = true, ParamKind::Bool, "Temporal gradients",
            "A-SVGF (Schied et al. 2018): DI's temporal pass shades last frame's sample at this frame's surface with this frame's lights and occluders; where the neighbourhood's shading changed by a share λ of its value, this frame weighs α + (1 − α) λ in the history blend, so a light switched off or a moving shadow is followed within a frame or two instead of ~1/α. With DI temporal reuse off the temporal pass runs for the gradients alone (its cost is counted). Off: plain SVGF.";
        denoise_iterations: u32 = 3, ParamKind::Int { min: 1, max: MAX_DENOISE_ITERATIONS as i64 }, "À-trous iterations",
            "À-trous passes, taps 1, 2, 4, … pixels apart: 3 reach 2 × (1 + 2 + 4) = 14 px each way. Measured on builtin:concourse at 96×64 (docs/bench.md, \"Through a denoiser\"): 3 gave the lowest per-frame error (ris + denoiser: 0.0184 luma RMSE; 4: 0.0197; 5: 0.0207) and each iteration costs ~6 % of a restir frame; a larger image wants more.";
        denoise_alpha: f32 = 0.2, ParamKind::Float { min: 0.01, max: 1.0 }, "History blend α",
            "Smallest weight of this frame in the temporal blend (1/length while the history is shorter than 1/α): 0.2 keeps ~5 frames; lower is smoother and lags more; 1 turns temporal accumulation off.";
        denoise_moments_alpha: f32 = 0.2, ParamKind::Float { min: 0.01, max: 1.0 }, "Moments blend α",
            "The same for the luminance moments the variance is estimated from.";
        denoise_history_cap: u32 = 32, ParamKind::Int { min: 1, max: 255 }, "History cap (frames)",
            "Longest history a pixel counts (the history-length view's top); with α it sets how long 1/length keeps decreasing.";
        denoise_phi_luminance: f32 = 4.0, ParamKind::Float { min: 0.01, max: 1000.0 }, "φ luminance",
            "Luminance edge-stopping: a neighbour's weight falls as e^(−|Δl| / (φ σ)), σ the standard deviation of the luminance difference (both pixels' variances). Larger blurs more.";
        denoise_phi_normal: f32 = 128.0, ParamKind::Float { min: 1.0, max: 1024.0 }, "φ normal",
            "Normal edge-stopping exponent: weight max(0, n·n')^φ (128: 6° halves it). Larger keeps creases sharper.";
        denoise_phi_depth: f32 = 1.0, ParamKind::Float { min: 0.01, max: 1000.0 }, "φ depth",
            "Depth edge-stopping: weight e^(−d / (φ · depth · pixel angle · taps apart)), d the neighbour's distance from this pixel's tangent plane; zero on one plane however steep. Larger blurs across silhouettes.";
    }
}

/// A problem with a parameter name or value (one line, names the parameter).
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingsError {
    #[error("unknown parameter '{0}' (see `restir-viewer params`)")]
    Unknown(String),
    #[error("parameter '{name}': {problem}")]
    BadValue { name: String, problem: String },
}

impl Settings {
    pub fn def(name: &str) -> Option<&'static ParamDef> {
        PARAMS.iter().find(|p| p.name == name)
    }

    /// These settings as the reference renders with them: its own light sampler, the power
    /// table or (`reference_light_bvh`) the light BVH at every vertex, never the realtime
    /// modes' choice, so that it stays an independent check of them.
    pub fn for_reference(&self) -> Settings {
        let mut s = self.clone();
        s.light_sampler = if self.reference_light_bvh {
            LightSampler::Bvh
        } else {
            LightSampler::Power
        };
        s.bvh_at_vertices = true;
        s
    }

    /// These settings with every reuse stage off, as the nee and ris modes run them: each
    /// row marked `ReuseSwitch` (DI, GI and PT temporal and spatial reuse) set to false.
    pub fn without_reuse(&self) -> Settings {
        let mut s = self.clone();
        for def in PARAMS.iter().filter(|p| p.role == Role::ReuseSwitch) {
            let stored = s.store(def.name, &ParamValue::Bool(false));
            debug_assert!(stored, "{} is a reuse switch but not a bool", def.name);
        }
        s
    }

    /// Sets a parameter. Out-of-range numbers are clamped and a warning is returned;
    /// wrong types and non-finite numbers are errors.
    pub fn set(&mut self, name: &str, value: ParamValue) -> Result<Option<String>, SettingsError> {
        let def = Settings::def(name).ok_or_else(|| SettingsError::Unknown(name.to_string()))?;
        let bad = |problem: String| SettingsError::BadValue {
            name: name.to_string(),
            problem,
        };
        let (value, warning) = match (def.kind, value) {
            (ParamKind::Bool, v @ ParamValue::Bool(_)) => (v, None),
            (ParamKind::Int { min, max }, ParamValue::Int(i)) => {
                let c = i.clamp(min, max);
                (
                    ParamValue::Int(c),
                    (c != i).then(|| format!("{name}: {i} is outside {min}..={max}, using {c}")),
                )
            }
            (ParamKind::Int { min, max }, ParamValue::Float(x))
                if x.fract() == 0.0 && x.is_finite() =>
            {
                let i = x as i64;
                let c = i.clamp(min, max);
                (
                    ParamValue::Int(c),
                    (c != i).then(|| format!("{name}: {i} is outside {min}..={max}, using {c}")),
                )
            }
            (ParamKind::Float { min, max }, v @ (ParamValue::Float(_) | ParamValue::Int(_))) => {
                let x = match v {
                    ParamValue::Int(i) => i as f64,
                    ParamValue::Float(x) => x,
                    _ => unreachable!("matched above"),
                };
                if !x.is_finite() {
                    return Err(bad(format!("{x} is not a finite number")));
                }
                let c = x.clamp(min, max);
                (
                    ParamValue::Float(c),
                    (c != x).then(|| format!("{name}: {x} is outside {min}..={max}, using {c}")),
                )
            }
            (ParamKind::Choice(options), ParamValue::Choice(s)) => {
                if !options.contains(&s.as_str()) {
                    return Err(bad(format!("'{s}' is not one of {}", options.join(", "))));
                }
                (ParamValue::Choice(s), None)
            }
            (kind, v) => return Err(bad(format!("{v} is not {}", kind_description(kind)))),
        };
        if !self.store(name, &value) {
            return Err(bad(format!("{value} has the wrong type")));
        }
        // The caller says it (one line: `warning: --set ...`, the preset's file, the tour).
        Ok(warning)
    }

    /// Parses `value` as text for the parameter's kind (`--set key=value`).
    pub fn set_from_str(
        &mut self,
        name: &str,
        text: &str,
    ) -> Result<Option<String>, SettingsError> {
        let def = Settings::def(name).ok_or_else(|| SettingsError::Unknown(name.to_string()))?;
        let bad = |problem: String| SettingsError::BadValue {
            name: name.to_string(),
            problem,
        };
        let t = text.trim();
        let value = match def.kind {
            ParamKind::Bool => match t.to_ascii_lowercase().as_str() {
                "true" | "on" | "1" | "yes" => ParamValue::Bool(true),
                "false" | "off" | "0" | "no" => ParamValue::Bool(false),
                _ => return Err(bad(format!("'{t}' is not a boolean (true/false)"))),
            },
            ParamKind::Int { .. } => match t.parse::<i64>() {
                Ok(i) => ParamValue::Int(i),
                Err(_) => match t.parse::<f64>() {
                    Ok(x) if x.is_finite() => {
                        ParamValue::Int(x.round().clamp(i64::MIN as f64, i64::MAX as f64) as i64)
                    }
                    _ => return Err(bad(format!("'{t}' is not an integer"))),
                },
            },
            ParamKind::Float { .. } => match t.parse::<f64>() {
                Ok(x) => ParamValue::Float(x),
                Err(_) => return Err(bad(format!("'{t}' is not a number"))),
            },
            ParamKind::Choice(_) => ParamValue::Choice(t.to_string()),
        };
        self.set(name, value)
    }

    /// Applies `key=value` pairs in order; returns the warnings.
    pub fn apply_assignments<'a>(
        &mut self,
        assignments: impl IntoIterator<Item = &'a str>,
    ) -> Result<Vec<String>, SettingsError> {
        let mut warnings = Vec::new();
        for a in assignments {
            let (key, value) = a.split_once('=').ok_or_else(|| SettingsError::BadValue {
                name: a.to_string(),
                problem: "expected key=value".to_string(),
            })?;
            warnings.extend(self.set_from_str(key.trim(), value)?);
        }
        Ok(warnings)
    }

    /// The uniform block the shaders read, for an image `height` pixels high (pixel-unit
    /// parameters follow the height, see `pixel_units`).
    pub fn gpu_params(&self, height: u32) -> GpuParams {
        let checks = [
            (self.check_offscreen, REJECT_OFFSCREEN),
            (self.check_surface, REJECT_SURFACE),
            (self.check_material, REJECT_MATERIAL),
            (self.check_normal, REJECT_NORMAL),
            (self.check_depth, REJECT_DEPTH),
            (self.check_reservoir, REJECT_RESERVOIR),
            (self.check_target, REJECT_TARGET),
            (self.check_target_ratio, REJECT_TARGET_RATIO),
        ]
        .iter()
        .filter(|(on, _)| *on)
        .fold(0, |acc, (_, bit)| acc | bit);
        let mut flags = 0;
        if self.permutation {
            flags |= PARAM_FLAG_PERMUTATION;
        }
        if self.bias_correction == BiasCorrection::Pairwise {
            flags |= PARAM_FLAG_PAIRWISE;
        }
        if self.jitter {
            flags |= PARAM_FLAG_JITTER;
        }
        if self.visibility_in_target() {
            flags |= PARAM_FLAG_MIS_VISIBILITY;
        }
        if self.traces_initial_visibility() {
            flags |= PARAM_FLAG_INITIAL_VISIBILITY;
        }
        flags |= self.gi_flags();
        if self.previous_lights {
            flags |= PARAM_FLAG_PREVIOUS_LIGHTS;
        }
        if self.previous_geometry {
            flags |= PARAM_FLAG_PREVIOUS_GEOMETRY;
        }
        if self.denoise_gradients_on() {
            flags |= PARAM_FLAG_DENOISE_GRADIENTS;
            if !self.temporal {
                flags |= PARAM_FLAG_GRADIENT_ONLY;
            }
        }
        GpuParams {
            light_candidates: self.light_candidates,
            bsdf_candidates: self.bsdf_candidates,
            m_cap: self.m_cap,
            normal_threshold: self.normal_threshold,
            depth_threshold: self.depth_threshold,
            target_ratio_clamp: if self.check_target_ratio {
                self.target_ratio_clamp
            } else {
                0.0
            },
            checks,
            flags,
            spatial_neighbours: self.spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS),
            spatial_radius: self.effective_spatial_radius(height),
            // One frame renders at most PASS_INFO_SLOTS chunks of samples; the shader divides
            // by this count, so it must be the count actually rendered (4096 used to render
            // 2048 and halve the image).
            reference_spp: self.reference_spp.clamp(
                1,
                REFERENCE_SAMPLES_PER_DISPATCH * crate::gpu_types::PASS_INFO_SLOTS,
            ),
            boiling_filter: self.boiling_filter,
            gi_m_cap: self.gi_m_cap,
            gi_spatial_neighbours: self.gi_spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS),
            gi_spatial_radius: self.effective_gi_spatial_radius(height),
            gi_jacobian_max: self.gi_jacobian_max.max(1.0),
            max_bounces: self.reference_bounces(),
            pt_shift: self.pt_shift.gpu(),
            pt_rough_threshold: self.pt_rough_threshold,
            pt_min_distance: self.pt_min_distance,
            pt_spatial_neighbours: self.pt_spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS),
            pt_spatial_radius: self.effective_pt_spatial_radius(height),
            pt_m_cap: self.pt_m_cap,
            pt_jacobian_clamp: if self.pt_jacobian_clamp > 0.0 {
                self.pt_jacobian_clamp.max(1.0)
            } else {
                0.0
            },
            denoise_alpha: self.denoise_alpha,
            denoise_moments_alpha: self.denoise_moments_alpha,
            denoise_phi_luminance: self.denoise_phi_luminance,
            denoise_phi_normal: self.denoise_phi_normal,
            denoise_phi_depth: self.denoise_phi_depth,
            denoise_history_cap: self.denoise_history_cap as f32,
            regir_grid: self.regir_grid.clamp(1, MAX_REGIR_GRID),
            regir_slots: self.regir_slots_in_use(),
            regir_cell_size: self.regir_cell_size,
            regir_build_samples: self.regir_build_samples.max(1),
            regir_jitter: self.regir_jitter,
            mutations: self.mutations.min(MAX_MUTATIONS),
            mutation_step: self.mutation_step,
            gi_light_candidates: if self.gi_light_candidates == 0 {
                self.light_candidates
            } else {
                self.gi_light_candidates
            },
        }
    }

    /// ReGIR's slots per cell as used: the setting, lowered until cells × slots fits
    /// `MAX_REGIR_SLOTS_TOTAL` (the fill pass's dispatch and the buffer's size).
    pub fn regir_slots_in_use(&self) -> u32 {
        let cells = self.regir_grid.clamp(1, MAX_REGIR_GRID).pow(3);
        self.regir_slots
            .clamp(1, MAX_REGIR_SLOTS)
            .min((MAX_REGIR_SLOTS_TOTAL / cells).max(1))
    }

    /// Whether the denoiser runs with temporal gradients (which need DI's temporal pass,
    /// for its gradient samples alone where temporal reuse is off).
    pub fn denoise_gradients_on(&self) -> bool {
        self.denoise && self.denoise_gradients
    }

    /// Whether the pairwise target includes visibility (`mis_visibility`; 1/M has no MIS
    /// terms to put it in).
    pub fn visibility_in_target(&self) -> bool {
        self.mis_visibility && self.bias_correction == BiasCorrection::Pairwise
    }

    /// Whether the initial pass traces its survivor's shadow ray: `initial_visibility`, or
    /// visibility in the target, which needs the canonical sample's own V whatever
    /// `initial_visibility` says.
    pub fn traces_initial_visibility(&self) -> bool {
        self.initial_visibility || self.visibility_in_target()
    }

    /// The Indirect stage's `PARAM_FLAG_GI_*` bits of `GpuParams::flags`.
    /// The bounces the reference traces: `max_bounces`, and at least 2 while ReSTIR GI or PT
    /// is on (GI adds one indirect bounce, so its image is compared with a 2-bounce
    /// reference; PT's paths have up to this many).
    pub fn reference_bounces(&self) -> u32 {
        let wanted = if self.gi || self.pt {
            self.max_bounces.max(2)
        } else {
            self.max_bounces
        };
        wanted.clamp(1, MAX_BOUNCES)
    }

    fn gi_flags(&self) -> u32 {
        [
            (self.gi, PARAM_FLAG_GI),
            (self.gi_temporal, PARAM_FLAG_GI_TEMPORAL),
            (self.gi_spatial, PARAM_FLAG_GI_SPATIAL),
            (self.gi_spatial_visibility, PARAM_FLAG_GI_SPATIAL_VISIBILITY),
            (self.gi_mis_visibility, PARAM_FLAG_GI_MIS_VISIBILITY),
            (
                self.gi_bias_correction == BiasCorrection::Pairwise,
                PARAM_FLAG_GI_PAIRWISE,
            ),
        ]
        .iter()
        .filter(|(on, _)| *on)
        .fold(0, |acc, (_, bit)| acc | bit)
    }
}

fn kind_description(kind: ParamKind) -> String {
    match kind {
        ParamKind::Bool => "a boolean".into(),
        ParamKind::Int { min, max } => format!("an integer in {min}..={max}"),
        ParamKind::Float { min, max } => format!("a number in {min}..={max}"),
        ParamKind::Choice(options) => format!("one of {}", options.join(", ")),
    }
}

/// Presets: TOML files with one `name = value` line per parameter.
pub mod preset;

/// Pixel-unit parameters follow the image height (defined at 1080p).
pub mod pixel_units;

#[cfg(test)]
mod tests;
