//! Every pipeline parameter in one table: name, stage, label, documentation, range and
//! default. The viewer's panels, `--set`, presets and `restir-viewer params` all read this
//! table, and the same name is used in WGSL (`m_cap` is `params.di.m_cap`,
//! `gi_m_cap` is `params.gi.m_cap`) and in the UI. The rows live with their technique
//! (`di/rows.rs`, `gi/rows.rs`, …; `settings/shared_rows.rs` for the rest) and this file
//! gathers them (`gather_rows!`).
//! Defaults are what the measurements favour; the book gives each one's figures in the
//! chapter of its stage, and its parameters page (docs/src/parameters.md) is generated
//! from this table.

use std::fmt;
use std::path::Path;

use crate::denoise::constants::*;
use crate::denoise::rows::rows as denoise_rows;
use crate::di::rows::rows as di_rows;
use crate::gi::rows::rows as gi_rows;
use crate::pt::constants::*;
use crate::pt::rows::rows as pt_rows;
use crate::shader_constants::*;
use shared_rows::rows as shared_rows;

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
    /// whose ray queries are slower than it: docs/src/measured/compile-and-load.md "Ray queries").
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

/// The rows sorted by stage (the order of `Stage`'s variants), keeping each stage's rows in
/// the order given: a stable insertion sort, run by the compiler.
const fn in_stage_order<const N: usize>(mut rows: [ParamDef; N]) -> [ParamDef; N] {
    let mut i = 1;
    while i < N {
        let mut j = i;
        while j > 0 && (rows[j - 1].stage as u8) > (rows[j].stage as u8) {
            let moved = rows[j - 1];
            rows[j - 1] = rows[j];
            rows[j] = moved;
            j -= 1;
        }
        i += 1;
    }
    rows
}

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

        /// The parameter table, in display order: by stage, and within a stage in the
        /// order `gather_rows!` lists the techniques.
        pub static PARAMS: &[ParamDef] = &in_stage_order([
            $( $( ParamDef {
                name: stringify!($field),
                stage: Stage::$stage,
                label: $label,
                doc: $doc,
                kind: $kind,
                role: row_role!($($role)?),
            }, )* )*
        ]);

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

/// Hands every technique's rows to `parameter_table!`: each `rows!` macro appends its
/// stages to the tokens it is given and calls back with the rest of the list. The registry
/// lists techniques; their rows live in their folders (docs/src/source-layout.md).
macro_rules! gather_rows {
    ([] $($rows:tt)*) => {
        parameter_table! { $($rows)* }
    };
    ([$next:ident $(, $rest:ident)*] $($rows:tt)*) => {
        $next! { gather_rows [$($rest),*] $($rows)* }
    };
}

gather_rows!([di_rows, shared_rows, gi_rows, pt_rows, denoise_rows]);

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

    /// The light samples each reference vertex draws: `reference_light_samples`, within
    /// MAX_REFERENCE_LIGHT_SAMPLES and, over a path, within REFERENCE_PATH_LIGHT_SAMPLES
    /// (lavapipe's loop bound on one invocation's rays), at least 1.
    pub fn reference_light_samples_in_use(&self) -> u32 {
        let per_path = REFERENCE_PATH_LIGHT_SAMPLES / self.reference_bounces();
        self.reference_light_samples
            .min(MAX_REFERENCE_LIGHT_SAMPLES)
            .min(per_path)
            .max(1)
    }
}

/// The OR of the bits whose switch is on (a `Params.flags` or checks word).
pub(crate) fn flag_bits(switches: &[(bool, u32)]) -> u32 {
    switches
        .iter()
        .filter(|(on, _)| *on)
        .fold(0, |acc, (_, bit)| acc | bit)
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

/// The rows no one technique owns: light samplers, validation, shading, tracing.
mod shared_rows;

/// The `Params` uniform from the settings: the shared fields and each technique's part.
mod gpu;

/// Pixel-unit parameters follow the image height (defined at 1080p).
pub mod pixel_units;

#[cfg(test)]
mod tests;
