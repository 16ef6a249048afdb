//! Presets: TOML files with one `name = value` line per parameter, read on top of a
//! base, with the same range checks and one-line errors as `--set`.

use super::*;

/// `restir-denoised`: ReSTIR DI as the crossover map found it cheapest through the
/// denoiser (docs/src/measured/denoiser.md, "The crossover map at 384×256"): a short temporal
/// history, no spatial reuse, the denoiser on. Reuse lowers the blur the denoiser adds; a long
/// history or wide spatial reuse adds correlated noise it cannot average away.
pub const RESTIR_DENOISED: &[&str] = &["temporal=true", "spatial=false", "m_cap=4", "denoise=true"];

/// The presets known by name (`--preset NAME`, the viewer's Preset row, `--compare NAME`):
/// name, the assignments it makes on top of its base, and what it is.
pub const BUILTIN: &[(&str, &[&str], &str)] = &[(
    "restir-denoised",
    RESTIR_DENOISED,
    "ReSTIR DI tuned for the denoiser: temporal reuse with M cap 4, no spatial reuse, denoiser on",
)];

/// A built-in preset's assignments, by name.
pub fn builtin(name: &str) -> Option<&'static [&'static str]> {
    BUILTIN
        .iter()
        .find(|(n, ..)| *n == name)
        .map(|(_, a, _)| *a)
}

/// Reads a preset on top of `base`: a built-in name (`BUILTIN`) or a TOML file. Unknown
/// keys and wrong types are errors that name the file and the key; out-of-range numbers
/// are clamped with a warning.
pub fn load(path: &Path, base: &Settings) -> anyhow::Result<(Settings, Vec<String>)> {
    if let Some(assignments) = path.to_str().and_then(builtin) {
        let mut settings = base.clone();
        let warnings = settings.apply_assignments(assignments.iter().copied())?;
        return Ok((settings, warnings));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow::anyhow!("{}: cannot read preset: {e}", path.display()))?;
    parse(&text, base).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

pub fn parse(text: &str, base: &Settings) -> anyhow::Result<(Settings, Vec<String>)> {
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        anyhow::anyhow!(
            "not a valid preset ({})",
            e.message().lines().next().unwrap_or("")
        )
    })?;
    parse_table(table, base)
}

/// The parameters of an already parsed table on top of `base` (a preset file, a tour
/// step: tours are presets plus captions, app/src/tour/). Every key must be a parameter.
pub fn parse_table(table: toml::Table, base: &Settings) -> anyhow::Result<(Settings, Vec<String>)> {
    let mut settings = base.clone();
    let mut warnings = Vec::new();
    for (key, value) in table {
        let value = match value {
            toml::Value::Boolean(b) => ParamValue::Bool(b),
            toml::Value::Integer(i) => ParamValue::Int(i),
            toml::Value::Float(x) => ParamValue::Float(x),
            toml::Value::String(s) => ParamValue::Choice(s),
            other => anyhow::bail!(
                "parameter '{key}': {} is not a parameter value",
                other.type_str()
            ),
        };
        warnings.extend(settings.set(&key, value)?);
    }
    Ok((settings, warnings))
}

pub fn to_toml(settings: &Settings) -> String {
    let mut out = String::from("# ReSTIR lab preset (restir-viewer params lists every name)\n");
    for def in PARAMS {
        let value = settings.get(def.name).expect("table row");
        let text = match value {
            ParamValue::Choice(s) => format!("\"{s}\""),
            ParamValue::Float(x) => format!("{x:?}"),
            other => other.to_string(),
        };
        out.push_str(&format!("{} = {}\n", def.name, text));
    }
    out
}

pub fn save(path: &Path, settings: &Settings) -> anyhow::Result<()> {
    std::fs::write(path, to_toml(settings))
        .map_err(|e| anyhow::anyhow!("{}: cannot write preset: {e}", path.display()))
}
