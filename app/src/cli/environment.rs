//! `--env FILE|builtin:sky`, `--env-strength S` and `--env-rotation DEG`, shared by
//! `view`, `render` and `bench`: the environment is loaded once (its distribution built
//! once) and attached to the scene before the upload.

use std::sync::Arc;

use anyhow::bail;
use clap::Args;
use restir_render::{Environment, Scene, load_environment};

#[derive(Args, Debug, Clone, Default)]
pub struct EnvArgs {
    /// Light the scene with an environment: an equirectangular .hdr or .exr (+Y up, top row
    /// = zenith, image centre toward +X; docs/src/environment.md, "Convention") or
    /// `builtin:sky`.
    #[arg(long, value_name = "FILE|builtin:sky")]
    pub env: Option<String>,
    /// Multiplies the environment's radiance (default 1).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub env_strength: Option<f32>,
    /// Turns the environment about +Y by this many degrees (default 0).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub env_rotation: Option<f32>,
}

impl EnvArgs {
    /// The environment the flags name, or `None` without `--env`. One-line errors name
    /// the file (or the flag) and the problem.
    pub fn load(&self) -> anyhow::Result<Option<Arc<Environment>>> {
        let Some(spec) = &self.env else {
            if self.env_strength.is_some() || self.env_rotation.is_some() {
                bail!("--env-strength and --env-rotation need --env");
            }
            return Ok(None);
        };
        let env = load_environment(spec)?
            .with_strength_and_rotation(
                self.env_strength.unwrap_or(1.0),
                self.env_rotation.unwrap_or(0.0),
            )
            .map_err(|e| anyhow::anyhow!(e))?;
        Ok(Some(Arc::new(env)))
    }

    /// Loads the environment and attaches it to `scene`.
    pub fn apply(&self, scene: &mut Scene) -> anyhow::Result<()> {
        scene.environment = self.load()?;
        Ok(())
    }
}
