//! The configurations a bench compares: built-in names (`nee`, `ris`, `ris+temporal`,
//! `ris+spatial`, `restir`, `restir-pairwise`, `path-2b`, `restir+gi`, `restir+pt`, ...) and
//! preset files, each a mode plus settings on top of the bench's base settings. A
//! configuration is scored against the reference of its own `max_bounces` (run/reference_sets.rs).

use std::path::Path;

use anyhow::{Context, bail};
use restir_render::settings::preset;
use restir_render::{Mode, Settings};

use super::builtin::BUILTIN;

/// The configurations run when `--configs` is not given.
pub const DEFAULT_CONFIGS: &str = "nee,ris,ris+temporal,ris+spatial,restir,restir-pairwise";

/// One configuration to measure.
#[derive(Clone, Debug)]
pub struct Config {
    pub name: String,
    pub mode: Mode,
    pub settings: Settings,
    /// One line for the report.
    pub description: String,
}

/// A built-in name with a tracing backend after a colon (`nee:ray-query`): the
/// configuration traced by that backend (`ray_backend`), whatever `--set` says.
fn split_backend(item: &str) -> (&str, Option<&str>) {
    match item.rsplit_once(':') {
        Some((name, backend))
            if restir_render::settings::RAY_BACKEND_NAMES.contains(&backend)
                && BUILTIN
                    .iter()
                    .any(|(n, ..)| *n == split_denoise(split_sampler(name).0).0) =>
        {
            (name, Some(backend))
        }
        _ => (item, None),
    }
}

/// `ris@bvh`: the configuration `ris` with DI's light candidates from that light sampler
/// (`light_sampler`; docs/src/light-samplers.md), whatever `--set` says.
fn split_sampler(name: &str) -> (&str, Option<&str>) {
    match name.rsplit_once('@') {
        Some((base, sampler))
            if restir_render::settings::LIGHT_SAMPLER_NAMES.contains(&sampler) =>
        {
            (base, Some(sampler))
        }
        _ => (name, None),
    }
}

/// The suffix that runs a configuration through the denoiser (docs/src/denoiser.md).
pub const DENOISE_SUFFIX: &str = "+denoise";

/// `restir+denoise`: the configuration `restir`, denoised; every figure the bench computes
/// is then the denoised image's, the denoiser's passes counted in its frame time.
fn split_denoise(name: &str) -> (&str, bool) {
    match name.strip_suffix(DENOISE_SUFFIX) {
        Some(base) if !base.is_empty() => (base, true),
        _ => (name, false),
    }
}

/// `ris[light_candidates=8;m_cap=4]`: the configuration `ris` with these parameters set
/// last (over its own and `--set`'s): one point of a cost curve (`--knob`), or one
/// estimator's own denoiser settings. Returns the name without them and the assignments.
fn split_overrides(item: &str) -> anyhow::Result<(&str, Vec<&str>)> {
    let Some(open) = item.find('[') else {
        return Ok((item, Vec::new()));
    };
    let inner = item[open + 1..].strip_suffix(']').with_context(|| {
        format!("--configs: '{item}': parameters go in brackets at the end, NAME[key=value;...]")
    })?;
    let sets: Vec<&str> = inner
        .split(';')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect();
    Ok((&item[..open], sets))
}

/// Parses `--configs`: comma-separated built-in names (each optionally `+denoise`, then
/// `@power`, `@tiles`, `@regir`, `@bvh` or `@auto`, then `:software`, `:ray-query` or
/// `:auto`, then `[key=value;...]`) and preset files (`.toml`; the configuration is named
/// after the file stem and runs in `restir` mode).
pub fn parse_configs(list: &str, base: &Settings) -> anyhow::Result<Vec<Config>> {
    let mut configs: Vec<Config> = Vec::new();
    for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let full = item;
        let (item, overrides) = split_overrides(item)?;
        let (named, backend) = split_backend(item);
        let (named, sampler) = split_sampler(named);
        let (builtin, denoise) = split_denoise(named);
        let mut config = match BUILTIN.iter().find(|(name, ..)| *name == builtin) {
            Some(&(_, mode, sets, description)) => {
                let mut settings = base.clone();
                settings
                    .apply_assignments(sets.iter().copied())
                    .expect("built-in configurations use valid parameters");
                let mut description = description.to_string();
                if let Some(b) = backend {
                    settings
                        .set_from_str("ray_backend", b)
                        .expect("a listed backend name");
                    description.push_str(&format!(", rays traced by {b}"));
                }
                if let Some(s) = sampler {
                    settings
                        .set_from_str("light_sampler", s)
                        .expect("a listed sampler name");
                    description.push_str(&format!(", light candidates from the {s} sampler"));
                }
                Config {
                    name: item.into(),
                    mode,
                    settings,
                    description,
                }
            }
            None if builtin.ends_with(".toml") || Path::new(builtin).is_file() => {
                preset_config(builtin, base)?
            }
            None => {
                let known: Vec<_> = BUILTIN.iter().map(|(n, ..)| *n).collect();
                bail!(
                    "--configs: '{item}' is neither a configuration ({}, each optionally \
                     {DENOISE_SUFFIX}, @SAMPLER and :BACKEND) nor a preset file",
                    known.join(", ")
                )
            }
        };
        if denoise {
            config.settings.denoise = true;
            if !config.name.contains(DENOISE_SUFFIX) {
                config.name.push_str(DENOISE_SUFFIX); // a preset, named after its file
            }
            config.description.push_str(", denoised (SVGF)");
        }
        if !overrides.is_empty() {
            config
                .settings
                .apply_assignments(overrides.iter().copied())
                .with_context(|| format!("--configs: '{full}'"))?;
            config.name = full.to_string();
            config
                .description
                .push_str(&format!(", with {}", overrides.join(", ")));
        }
        if configs.iter().any(|c| c.name == config.name) {
            bail!("--configs: '{}' is listed twice", config.name);
        }
        configs.push(config);
    }
    if configs.is_empty() {
        bail!("--configs: no configuration given");
    }
    Ok(configs)
}

fn preset_config(path: &str, base: &Settings) -> anyhow::Result<Config> {
    let (settings, warnings) = preset::load(Path::new(path), base)?;
    for w in warnings {
        eprintln!("warning: {path}: {w}");
    }
    let name = Path::new(path)
        .file_stem()
        .and_then(|s| s.to_str())
        .with_context(|| format!("--configs: '{path}' has no usable file name"))?
        .to_string();
    Ok(Config {
        name,
        mode: Mode::Restir,
        settings,
        description: format!("preset {path}"),
    })
}

/// `--set` assignments every bench starts with, before the user's: jitter off, so the
/// reference shades the same rasterised surfaces and per-frame errors measure lighting alone
/// (`--set jitter=true` restores it on both sides).
pub const BASE_ASSIGNMENTS: &[&str] = &["jitter=false"];

#[cfg(test)]
#[path = "configs_tests.rs"]
mod tests;
