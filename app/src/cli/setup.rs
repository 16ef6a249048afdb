//! Turning command-line settings into a renderer: scene, size, parameters, preset.

use std::path::PathBuf;

use anyhow::{Context, bail};
use clap::Args;
use restir_render::Settings;
use restir_render::effects::EffectSet;
use restir_render::settings::preset;

/// The pipeline options `render` and `bench` share (`#[command(flatten)]`).
#[derive(Args, Debug)]
pub struct PipelineArgs {
    /// Seed of every random stream.
    #[arg(long, default_value_t = 0)]
    pub seed: u32,
    /// Override a pipeline parameter, `name=value` (see `params`); repeatable.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// A preset applied before `--set`: a TOML file (`name = value` per line) or a built-in
    /// name (`restir-denoised`).
    #[arg(long)]
    pub preset: Option<PathBuf>,
    /// Effect set to compile: auto (from the scene), all (general pipeline) or a list.
    #[arg(long, default_value = "auto")]
    pub effects: String,
}

impl PipelineArgs {
    /// Defaults, then `first` (assignments a command starts from), the preset and `--set`.
    pub fn settings(&self, first: &[&str]) -> anyhow::Result<Settings> {
        let assignments: Vec<String> = first
            .iter()
            .map(|s| s.to_string())
            .chain(self.set.iter().cloned())
            .collect();
        settings_from(self.preset.as_ref(), &assignments)
    }

    pub fn effects(&self) -> anyhow::Result<Option<EffectSet>> {
        parse_effects(&self.effects)
    }
}

/// Parses `WxH`.
pub fn parse_size(text: &str) -> anyhow::Result<(u32, u32)> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .with_context(|| format!("--size '{text}': expected WxH, e.g. 640x360"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .with_context(|| format!("--size '{text}': '{s}' is not a whole number"))
    };
    let (w, h) = (parse(w)?, parse(h)?);
    if w == 0
        || h == 0
        || w > restir_render::renderer::MAX_SIZE
        || h > restir_render::renderer::MAX_SIZE
    {
        bail!(
            "--size '{text}': each side must be 1..={}",
            restir_render::renderer::MAX_SIZE
        );
    }
    Ok((w, h))
}

/// Default settings, then the preset, then each `--set` in order (warnings are logged).
pub fn settings_from(
    preset_file: Option<&PathBuf>,
    assignments: &[String],
) -> anyhow::Result<Settings> {
    let mut settings = Settings::default();
    if let Some(path) = preset_file {
        let (s, warnings) = preset::load(path, &settings)?;
        for w in warnings {
            eprintln!("warning: {}: {w}", path.display());
        }
        settings = s;
    }
    for w in settings
        .apply_assignments(assignments.iter().map(String::as_str))
        .map_err(|e| anyhow::anyhow!("--set {e}"))?
    {
        eprintln!("warning: --set {w}");
    }
    Ok(settings)
}

/// `--effects auto|all|LIST`.
pub fn parse_effects(text: &str) -> anyhow::Result<Option<EffectSet>> {
    if text == "auto" {
        return Ok(None);
    }
    EffectSet::parse_list(text)
        .map(Some)
        .map_err(|e| anyhow::anyhow!("--effects: {e}"))
}

/// `--time T --fps F` of `render` and `bench`: frame i shows scene time T + i/F.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct TimeArgs {
    /// Scene time of the first frame, in seconds (animated scenes) [default: 0].
    #[arg(long)]
    pub time: Option<f32>,
    /// Scene time advances 1/F seconds per frame; 0 freezes time (a reference of one
    /// moment is accumulated that way) [default: 30].
    #[arg(long)]
    pub fps: Option<f32>,
}

impl TimeArgs {
    pub fn timeline(&self) -> anyhow::Result<restir_render::timeline::Timeline> {
        self.timeline_or(0.0, 30.0)
    }

    /// The timeline with these defaults for what the flags leave out (a tour step's).
    pub fn timeline_or(
        &self,
        start: f32,
        fps: f32,
    ) -> anyhow::Result<restir_render::timeline::Timeline> {
        restir_render::timeline::Timeline::new(self.time.unwrap_or(start), self.fps.unwrap_or(fps))
            .map_err(anyhow::Error::msg)
    }
}
