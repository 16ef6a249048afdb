//! The configurations a bench compares: built-in names (`nee`, `ris`, `ris+temporal`,
//! `ris+spatial`, `restir`, `restir-pairwise`) and preset files, each a mode plus settings on
//! top of the bench's base settings.

use std::path::Path;

use anyhow::{Context, bail};
use restir_render::settings::preset;
use restir_render::{Mode, Settings};

/// The configurations run when `--configs` is not given.
pub const DEFAULT_CONFIGS: &str = "nee,ris,ris+temporal,ris+spatial,restir,restir-pairwise";

/// The built-in configurations: name, mode and the parameters that define them (applied
/// after the base settings, so `--set` cannot undo what makes a configuration itself).
const BUILTIN: &[(&str, Mode, &[&str], &str)] = &[
    (
        "nee",
        Mode::Nee,
        &[],
        "one power-sampled light sample per pixel",
    ),
    ("ris", Mode::Ris, &[], "initial RIS, no reuse"),
    (
        "ris+temporal",
        Mode::Restir,
        &["temporal=true", "spatial=false"],
        "RIS + temporal reuse",
    ),
    (
        "ris+spatial",
        Mode::Restir,
        &["temporal=false", "spatial=true"],
        "RIS + spatial reuse",
    ),
    (
        "restir",
        Mode::Restir,
        &["temporal=true", "spatial=true"],
        "RIS + temporal + spatial (1/M)",
    ),
    (
        "restir-pairwise",
        Mode::Restir,
        &["temporal=true", "spatial=true", "bias_correction=pairwise"],
        "RIS + temporal + spatial, pairwise MIS (unbiased)",
    ),
];

/// One configuration to measure.
#[derive(Clone, Debug)]
pub struct Config {
    pub name: String,
    pub mode: Mode,
    pub settings: Settings,
    /// One line for the report.
    pub description: String,
}

/// Parses `--configs`: comma-separated built-in names and preset files (`.toml`; the
/// configuration is named after the file stem and runs in `restir` mode).
pub fn parse_configs(list: &str, base: &Settings) -> anyhow::Result<Vec<Config>> {
    let mut configs: Vec<Config> = Vec::new();
    for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let config = match BUILTIN.iter().find(|(name, ..)| *name == item) {
            Some(&(name, mode, sets, description)) => {
                let mut settings = base.clone();
                settings
                    .apply_assignments(sets.iter().copied())
                    .expect("built-in configurations use valid parameters");
                Config {
                    name: name.into(),
                    mode,
                    settings,
                    description: description.into(),
                }
            }
            None if item.ends_with(".toml") || Path::new(item).is_file() => {
                preset_config(item, base)?
            }
            None => {
                let known: Vec<_> = BUILTIN.iter().map(|(n, ..)| *n).collect();
                bail!(
                    "--configs: '{item}' is neither a configuration ({}) nor a preset file",
                    known.join(", ")
                )
            }
        };
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

/// The spatial radius the bench uses at `height` when nobody chose one: the default
/// (30 px) is meant for ~1080p, where it spans similar surfaces; it shrinks with the image
/// height, but never below 10 px, under which the disk holds too few distinct pixels to
/// decorrelate neighbours (at 160×100 reuse with 30 px *hurt*: it reached across edges).
pub fn scaled_spatial_radius(height: u32) -> f32 {
    let default = Settings::default().spatial_radius;
    (default * height as f32 / 1080.0).clamp(10.0, default)
}

/// `--set` assignments every bench starts with, before the user's: jitter off, so the
/// reference shades the same rasterised surfaces and per-frame errors measure lighting alone
/// (`--set jitter=true` restores it on both sides).
pub const BASE_ASSIGNMENTS: &[&str] = &["jitter=false"];

/// Scales the spatial radius to the image height unless the preset or `--set` chose one.
pub fn scale_radius(mut settings: Settings, height: u32) -> (Settings, RadiusChoice) {
    if settings.spatial_radius == Settings::default().spatial_radius {
        settings.spatial_radius = scaled_spatial_radius(height);
        let r = settings.spatial_radius;
        (settings, RadiusChoice::Scaled(r))
    } else {
        let r = settings.spatial_radius;
        (settings, RadiusChoice::Given(r))
    }
}

/// How the spatial radius was chosen (reported with the results).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RadiusChoice {
    Scaled(f32),
    Given(f32),
}

impl std::fmt::Display for RadiusChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RadiusChoice::Scaled(r) => write!(
                f,
                "{r} px (30 px at 1080p scaled to the image height, at least 10 px)"
            ),
            RadiusChoice::Given(r) => write!(f, "{r} px (as set)"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_default_configs_parse_with_their_modes() {
        let configs = parse_configs(DEFAULT_CONFIGS, &Settings::default()).unwrap();
        let names: Vec<_> = configs.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names.join(","), DEFAULT_CONFIGS);
        assert_eq!(configs[0].mode, Mode::Nee);
        assert!(configs[2].settings.temporal && !configs[2].settings.spatial);
        assert!(!configs[3].settings.temporal && configs[3].settings.spatial);
        assert!(parse_configs("restir,nope", &Settings::default()).is_err());
        assert!(parse_configs("ris,ris", &Settings::default()).is_err());
    }

    #[test]
    fn bench_radius_scales_with_height_within_bounds() {
        assert_eq!(scaled_spatial_radius(1080), 30.0);
        assert_eq!(scaled_spatial_radius(2160), 30.0);
        assert_eq!(scaled_spatial_radius(540), 15.0);
        assert_eq!(scaled_spatial_radius(100), 10.0);
        let (s, choice) = scale_radius(Settings::default(), 100);
        assert_eq!(
            (s.spatial_radius, choice),
            (10.0, RadiusChoice::Scaled(10.0))
        );
        let given = Settings {
            spatial_radius: 5.0,
            ..Settings::default()
        };
        let (s, choice) = scale_radius(given, 100);
        assert_eq!((s.spatial_radius, choice), (5.0, RadiusChoice::Given(5.0)));
    }
}
