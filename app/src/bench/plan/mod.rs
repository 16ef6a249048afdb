//! What to run: `bench`'s command line (`args.rs`) checked and turned into a `Plan`: the
//! image size, the camera path, the settings every configuration starts from, the
//! configurations themselves (`configs.rs`, built-ins in `builtin.rs`, a cost curve's points
//! from `knob.rs`), the equal-time budget's rule (`budget.rs`) and a sweep split into jobs
//! (`jobs.rs`). Nothing here renders.

pub mod args;
pub mod budget;
mod builtin;
pub mod camera_path;
pub mod configs;
pub mod jobs;
pub mod knob;

use anyhow::bail;
use restir_render::Settings;
use restir_render::effects::EffectSet;

use crate::cli::setup::parse_size;
use args::BenchArgs;
use camera_path::CameraPath;
use configs::{BASE_ASSIGNMENTS, Config, parse_configs};

/// A bench's arguments, checked.
pub struct Plan {
    pub size: (u32, u32),
    pub camera: CameraPath,
    /// The settings every configuration starts from: `BASE_ASSIGNMENTS`, then `--set`.
    pub base: Settings,
    /// The spatial radius as set (px at 1080p) and as used at this height (px).
    pub radius: (f32, f32),
    /// In `--configs` order; with `--knob`, each once per knob value.
    pub configs: Vec<Config>,
    /// `--effects` when forced.
    pub effects: Option<EffectSet>,
    /// Measured frames per configuration and seed (`--frames`; 1 in equal-time mode, where
    /// the budget decides).
    pub measured: u32,
}

impl Plan {
    /// Checks the arguments in the order a user reads them and fails on the first wrong one.
    pub fn of(args: &BenchArgs) -> anyhow::Result<Plan> {
        let size = parse_size(&args.size)?;
        let camera = CameraPath::parse(&args.camera)?;
        if let Some(t) = args.budget_ms {
            check_budget(t, camera, args.warmup)?;
        }
        if args.frames == Some(0) {
            bail!("--frames must be at least 1");
        }
        if args.seeds == 0 {
            bail!("--seeds must be at least 1");
        }
        let base = args.pipeline.settings(BASE_ASSIGNMENTS)?;
        let radius = (base.spatial_radius, base.effective_spatial_radius(size.1));
        let config_list = match &args.knob {
            Some(knob) => knob::expand_knob(&args.configs, knob)?,
            None => args.configs.clone(),
        };
        if let Some(t) = args.target_rmse
            && !(t.is_finite() && t > 0.0)
        {
            bail!("--target-rmse {t}: expected a positive error");
        }
        let configs = parse_configs(&config_list, &base)?;
        let effects = args.pipeline.effects()?;
        Ok(Plan {
            size,
            camera,
            base,
            radius,
            configs,
            effects,
            measured: args.frames.unwrap_or(1),
        })
    }
}

/// Equal-time mode compares running averages of one still image, from the first frame on.
fn check_budget(ms: f64, camera: CameraPath, warmup: u32) -> anyhow::Result<()> {
    if !(ms.is_finite() && ms > 0.0) {
        bail!("--budget-ms {ms}: expected a positive number of milliseconds");
    }
    if camera != CameraPath::Static {
        bail!("--budget-ms compares running averages, which need --camera static");
    }
    if warmup > 0 {
        bail!("--warmup and --budget-ms do not mix: warm-up frames would be free time");
    }
    Ok(())
}
