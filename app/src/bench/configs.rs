//! The configurations a bench compares: built-in names (`nee`, `ris`, `ris+temporal`,
//! `ris+spatial`, `restir`, `restir-pairwise`, `path-2b`, `restir+gi`, `restir+pt`, ...) and
//! preset files, each a mode plus settings on top of the bench's base settings. A
//! configuration is scored against the reference of its own `max_bounces` (references.rs).

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
        &[
            "temporal=true",
            "spatial=true",
            "bias_correction=one-over-m",
        ],
        "RIS + temporal + spatial, 1/M weights (biased; the default before pairwise)",
    ),
    (
        "restir-pairwise",
        Mode::Restir,
        &["temporal=true", "spatial=true", "bias_correction=pairwise"],
        "RIS + temporal + spatial, pairwise MIS (unbiased; the default)",
    ),
    (
        "path-2b",
        Mode::Reference,
        &["reference_spp=1", "max_bounces=2"],
        "one-sample brute-force path tracing, 2 bounces (the reference estimator at 1 spp, per frame; scored against a 2-bounce reference)",
    ),
    (
        "restir+gi",
        Mode::Restir,
        &["gi=true", "gi_bias_correction=one-over-m", "max_bounces=2"],
        "restir (DI) + ReSTIR GI with 1/M weights (biased); scored against a 2-bounce reference",
    ),
    (
        "restir+gi-pairwise",
        Mode::Restir,
        &["gi=true", "gi_bias_correction=pairwise", "max_bounces=2"],
        "restir (DI) + ReSTIR GI with pairwise MIS (the GI default); scored against a 2-bounce reference",
    ),
    (
        "path-3b",
        Mode::Reference,
        &["reference_spp=1", "max_bounces=3"],
        "one-sample brute-force path tracing, 3 bounces; scored against a 3-bounce reference",
    ),
    (
        "restir+pt",
        Mode::Restir,
        &["pt=true", "pt_shift=hybrid", "max_bounces=2"],
        "restir (DI) + ReSTIR PT, hybrid shift, paths of 2 bounces (GI's path space); scored against a 2-bounce reference",
    ),
    (
        "restir+pt-reconnection",
        Mode::Restir,
        &["pt=true", "pt_shift=reconnection", "max_bounces=2"],
        "restir (DI) + ReSTIR PT, reconnection shift, 2 bounces",
    ),
    (
        "restir+pt-replay",
        Mode::Restir,
        &["pt=true", "pt_shift=random-replay", "max_bounces=2"],
        "restir (DI) + ReSTIR PT, random-replay shift, 2 bounces",
    ),
    (
        "restir+pt-3b",
        Mode::Restir,
        &["pt=true", "pt_shift=hybrid", "max_bounces=3"],
        "restir (DI) + ReSTIR PT, hybrid shift, paths of up to 3 bounces; scored against a 3-bounce reference",
    ),
    (
        "restir+pt-spatial-only",
        Mode::Restir,
        &[
            "pt=true",
            "pt_shift=hybrid",
            "max_bounces=2",
            "pt_temporal=false",
        ],
        "restir (DI) + ReSTIR PT, hybrid shift, 2 bounces, spatial path reuse only (what temporal reuse adds)",
    ),
    (
        "restir+pt-clamped",
        Mode::Restir,
        &[
            "pt=true",
            "pt_shift=hybrid",
            "max_bounces=2",
            "pt_jacobian_clamp=2",
        ],
        "restir (DI) + ReSTIR PT, hybrid shift, 2 bounces, |J| clamped into [1/2, 2] (biased)",
    ),
    (
        "restir-denoised",
        Mode::Restir,
        preset::RESTIR_DENOISED,
        "the restir-denoised preset: temporal reuse at M cap 4, no spatial reuse, denoised (SVGF)",
    ),
    (
        "tiles-on",
        Mode::Restir,
        &["light_sampler=tiles"],
        "restir defaults with light tiles (the tiles sweep)",
    ),
    (
        "tiles-off",
        Mode::Restir,
        &["light_sampler=power"],
        "restir defaults with the power table (the tiles sweep)",
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

/// `--knob NAME=V1,V2,...`: each configuration of `list` once per value, as
/// `CONFIG[NAME=V]`, or `CONFIG[its own;NAME=V]` where it has parameters already (a
/// configuration name `--configs` parses back, so the points run as jobs too).
pub fn expand_knob(list: &str, knob: &str) -> anyhow::Result<String> {
    let (name, values) = knob
        .split_once('=')
        .filter(|(n, v)| !n.trim().is_empty() && !v.trim().is_empty())
        .with_context(|| format!("--knob '{knob}': expected NAME=V1,V2,..."))?;
    let values: Vec<&str> = values
        .split(',')
        .map(str::trim)
        .filter(|v| !v.is_empty())
        .collect();
    if values.len() < 2 {
        bail!("--knob '{knob}': a cost curve needs two values at least");
    }
    let items: Vec<String> = list
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .flat_map(|c| {
            values.iter().map(move |v| match c.strip_suffix(']') {
                Some(own) => format!("{own};{}={v}]", name.trim()),
                None => format!("{c}[{}={v}]", name.trim()),
            })
        })
        .collect();
    Ok(items.join(","))
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
        // Any configuration can be denoised, with or without a backend after it.
        let denoised = parse_configs(
            "ris+denoise,restir-pairwise+denoise:software,ris+temporal+denoise",
            &Settings::default(),
        )
        .unwrap();
        assert!(denoised.iter().all(|c| c.settings.denoise));
        assert_eq!(denoised[0].mode, Mode::Ris);
        assert_eq!(denoised[1].name, "restir-pairwise+denoise:software");
        assert!(denoised[2].settings.temporal && !denoised[2].settings.spatial);
        assert!(!configs.iter().any(|c| c.settings.denoise));
        // Parameters in brackets come last and name the configuration.
        let tuned = parse_configs(
            "ris[light_candidates=8],restir-pairwise+denoise@bvh[m_cap=4;denoise_iterations=2]",
            &Settings::default(),
        )
        .unwrap();
        assert_eq!(tuned[0].name, "ris[light_candidates=8]");
        assert_eq!(tuned[0].settings.light_candidates, 8);
        assert!(tuned[1].settings.denoise && tuned[1].settings.m_cap == 4.0);
        assert_eq!(
            tuned[1].settings.light_sampler,
            restir_render::settings::LightSampler::Bvh
        );
        for bad in ["ris[light_candidates=8", "ris[nope=1]", "ris[m_cap=x]"] {
            let e = format!(
                "{:#}",
                parse_configs(bad, &Settings::default()).unwrap_err()
            );
            assert!(e.contains("--configs"), "{bad}: {e}");
        }
        assert_eq!(
            expand_knob("ris,restir", "light_candidates=2,8").unwrap(),
            "ris[light_candidates=2],ris[light_candidates=8],restir[light_candidates=2],restir[light_candidates=8]"
        );
        assert_eq!(
            expand_knob("restir[m_cap=4]", "light_candidates=2,8").unwrap(),
            "restir[m_cap=4;light_candidates=2],restir[m_cap=4;light_candidates=8]"
        );
        assert!(expand_knob("ris", "light_candidates=2").is_err());
        assert!(expand_knob("ris", "=2,3").is_err());
        assert!(parse_configs("+denoise", &Settings::default()).is_err());
        assert!(parse_configs("ris,ris", &Settings::default()).is_err());
        // `restir` keeps the 1/M weights its published figures were measured with;
        // `restir-pairwise` is the default estimator (docs/src/mis-and-bias.md, "The cost
        // and the choice").
        use restir_render::settings::BiasCorrection;
        assert_eq!(
            configs[4].settings.bias_correction,
            BiasCorrection::OneOverM
        );
        assert_eq!(
            configs[5].settings.bias_correction,
            BiasCorrection::Pairwise
        );
    }

    #[test]
    fn a_sampler_suffix_picks_the_light_sampler() {
        use restir_render::settings::LightSampler;
        let configs = parse_configs(
            "ris@bvh,restir-pairwise@regir:software,ris+denoise@tiles,ris",
            &Settings::default(),
        )
        .unwrap();
        assert_eq!(configs[0].mode, Mode::Ris);
        assert_eq!(configs[0].settings.light_sampler, LightSampler::Bvh);
        assert_eq!(configs[1].settings.light_sampler, LightSampler::Regir);
        assert_eq!(configs[1].name, "restir-pairwise@regir:software");
        assert!(configs[2].settings.denoise);
        assert_eq!(configs[2].settings.light_sampler, LightSampler::Tiles);
        assert_eq!(configs[3].settings.light_sampler, LightSampler::Auto);
        assert!(parse_configs("ris@octree", &Settings::default()).is_err());
    }

    #[test]
    fn a_backend_suffix_picks_the_tracing_backend() {
        use restir_render::settings::RayBackendChoice;
        let configs = parse_configs(
            "nee:ray-query,restir-pairwise:software,nee",
            &Settings::default(),
        )
        .unwrap();
        assert_eq!(configs[0].name, "nee:ray-query");
        assert_eq!(configs[0].mode, Mode::Nee);
        assert_eq!(configs[0].settings.ray_backend, RayBackendChoice::RayQuery);
        assert_eq!(configs[1].settings.ray_backend, RayBackendChoice::Software);
        assert_eq!(configs[2].settings.ray_backend, RayBackendChoice::Auto);
        assert!(parse_configs("nee:warp-drive", &Settings::default()).is_err());
    }

    #[test]
    fn path_2b_is_the_one_sample_two_bounce_reference_estimator() {
        let base = Settings::default();
        let configs = parse_configs("ris,path-2b", &base).unwrap();
        let path = &configs[1];
        assert_eq!(path.mode, Mode::Reference);
        assert_eq!(
            (path.settings.reference_spp, path.settings.max_bounces),
            (1, 2)
        );
        // Everything else is the base: jitter off with the bench's base assignments.
        let jitter_off = {
            let mut b = base.clone();
            b.apply_assignments(BASE_ASSIGNMENTS.iter().copied())
                .unwrap();
            b
        };
        let path = &parse_configs("path-2b", &jitter_off).unwrap()[0];
        assert!(!path.settings.jitter);
        // `ris` stays direct-only, so it gets the 1-bounce reference.
        assert_eq!(configs[0].settings.max_bounces, 1);
    }

    #[test]
    fn gi_configurations_run_gi_and_are_scored_against_two_bounces() {
        use restir_render::settings::BiasCorrection;
        let configs = parse_configs("restir+gi,restir+gi-pairwise", &Settings::default()).unwrap();
        for c in &configs {
            assert_eq!(c.mode, Mode::Restir);
            assert!(c.settings.gi && c.settings.gi_temporal && c.settings.gi_spatial);
            assert_eq!(c.settings.max_bounces, 2);
        }
        assert_eq!(
            configs[0].settings.gi_bias_correction,
            BiasCorrection::OneOverM
        );
        assert_eq!(
            configs[1].settings.gi_bias_correction,
            BiasCorrection::Pairwise
        );
    }
}
