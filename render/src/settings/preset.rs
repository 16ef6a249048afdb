//! Presets: TOML files with one `name = value` line per parameter, read on top of a
//! base, with the same range checks and one-line errors as `--set`.

use super::*;

/// Reads a preset on top of `base`. Unknown keys and wrong types are errors that name
/// the file and the key; out-of-range numbers are clamped with a warning.
pub fn load(path: &Path, base: &Settings) -> anyhow::Result<(Settings, Vec<String>)> {
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
