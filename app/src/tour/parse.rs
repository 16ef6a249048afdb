//! Reading a tour file. A step is a preset (its parameter keys go through the preset
//! parser, `restir_render::settings::preset::parse_table`, so presets and tours share one
//! parser) plus the step keys below. Every error is one line naming the step and the
//! problem (the caller adds the file).

use std::path::Path;

use anyhow::{Context, anyhow, bail};
use glam::{Quat, Vec3};
use restir_render::scene::builtin::{DEFAULT_SCENE, is_builtin_name};
use restir_render::settings::preset;
use restir_render::{Camera, DebugView, Mode, Settings};
use toml::{Table, Value};

use super::{LiveNumber, StepTime, Tour, TourStep};
use crate::compare::CompareTarget;

/// The keys of a step that are not pipeline parameters.
const STEP_KEYS: [&str; 14] = [
    "title",
    "caption",
    "scene",
    "env",
    "time",
    "clip",
    "fps",
    "paused",
    "camera",
    "mode",
    "compare",
    "debug_view",
    "exposure",
    "show",
];

pub fn parse(text: &str, path: &Path) -> anyhow::Result<Tour> {
    let mut table: Table = text.parse().map_err(|e: toml::de::Error| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].lines().count().max(1));
        let at = line.map(|l| format!(" at line {l}")).unwrap_or_default();
        anyhow!(
            "not a valid tour{at} ({})",
            e.message().lines().next().unwrap_or("")
        )
    })?;
    let title = match table.remove("title") {
        None => path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("tour")
            .to_string(),
        Some(Value::String(s)) => s,
        Some(other) => bail!("title: expected a string, not {}", other.type_str()),
    };
    let steps = match table.remove("step") {
        Some(Value::Array(steps)) => steps,
        Some(other) => bail!(
            "'step' must be an array of tables ([[step]]), not {}",
            other.type_str()
        ),
        None => Vec::new(),
    };
    if let Some(key) = table.keys().next() {
        bail!("unknown key '{key}' (a tour has 'title' and [[step]] tables)");
    }
    if steps.is_empty() {
        bail!("the tour has no steps (add [[step]] tables)");
    }
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut scene = DEFAULT_SCENE.to_string();
    let mut out = Vec::with_capacity(steps.len());
    for (i, value) in steps.into_iter().enumerate() {
        let Value::Table(t) = value else {
            bail!("step {}: expected a table, not {}", i + 1, value.type_str());
        };
        let name = t
            .get("title")
            .and_then(Value::as_str)
            .map(|s| format!(" (\"{s}\")"))
            .unwrap_or_default();
        let step =
            parse_step(t, folder, &scene).map_err(|e| anyhow!("step {}{name}: {e:#}", i + 1))?;
        scene = step.scene.clone();
        out.push(step);
    }
    Ok(Tour {
        path: path.to_path_buf(),
        title,
        steps: out,
    })
}

fn parse_step(mut t: Table, folder: &Path, previous_scene: &str) -> anyhow::Result<TourStep> {
    let mut own = Table::new();
    for key in STEP_KEYS {
        if let Some(v) = t.remove(key) {
            own.insert(key.to_string(), v);
        }
    }
    // What is left are parameters, read like a preset on top of the defaults.
    let (settings, _clamped) = preset::parse_table(t, &Settings::default())?;
    let text = |key: &str| -> anyhow::Result<Option<String>> {
        match own.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(v) => bail!("{key}: expected a string, not {}", v.type_str()),
        }
    };
    let number = |key: &str| -> anyhow::Result<Option<f32>> {
        match own.get(key) {
            None => Ok(None),
            Some(v) => as_f32(v)
                .filter(|x| x.is_finite())
                .map(Some)
                .with_context(|| format!("{key}: expected a number, not {v}")),
        }
    };
    let scene = match text("scene")? {
        Some(s) => resolve_scene(&s, folder)?,
        None => previous_scene.to_string(),
    };
    let env = text("env")?
        .map(|e| resolve_environment(&e, folder))
        .transpose()?;
    let mode = match text("mode")? {
        None => Mode::Restir,
        Some(m) => Mode::from_name(&m)
            .with_context(|| format!("mode '{m}': expected reference, nee, ris or restir"))?,
    };
    let debug_view = match text("debug_view")? {
        None => DebugView::Final,
        Some(v) => DebugView::from_name(&v).with_context(|| {
            let names: Vec<_> = DebugView::ALL.iter().map(|v| v.name()).collect();
            format!("debug_view '{v}': expected one of {}", names.join(", "))
        })?,
    };
    let fps = number("fps")?;
    if fps.is_some_and(|f| f <= 0.0) {
        bail!("fps: expected a positive rate");
    }
    let paused = match own.get("paused") {
        None => false,
        Some(Value::Boolean(b)) => *b,
        Some(v) => bail!("paused: expected true or false, not {v}"),
    };
    let compare = own
        .get("compare")
        .map(|v| parse_compare(v, folder, &settings))
        .transpose()?;
    Ok(TourStep {
        title: text("title")?.unwrap_or_else(|| "(untitled)".to_string()),
        caption: paragraphs(&text("caption")?.unwrap_or_default()),
        scene,
        env,
        time: StepTime {
            start: number("time")?,
            clip: text("clip")?,
            fps,
            paused,
        },
        camera: own.get("camera").map(parse_camera).transpose()?,
        mode,
        settings,
        compare,
        debug_view,
        exposure: number("exposure")?,
        show: own
            .get("show")
            .map(parse_show)
            .transpose()?
            .unwrap_or_default(),
    })
}

/// A caption as written in a TOML multi-line string, re-flowed: the lines of a paragraph
/// joined by spaces (the panel wraps them at its width), blank lines kept as breaks.
fn paragraphs(text: &str) -> String {
    text.trim()
        .split("\n\n")
        .map(|p| p.split_whitespace().collect::<Vec<_>>().join(" "))
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("\n\n")
}

fn as_f32(v: &Value) -> Option<f32> {
    match v {
        Value::Float(x) => Some(*x as f32),
        Value::Integer(i) => Some(*i as f32),
        _ => None,
    }
}

/// `builtin:NAME` (checked against the built-in list) or a glTF path, relative to the
/// tour's folder, that must exist.
fn resolve_scene(spec: &str, folder: &Path) -> anyhow::Result<String> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        if !is_builtin_name(name) {
            bail!("unknown scene '{spec}' (restir-viewer scenes lists the built-in ones)");
        }
        return Ok(spec.to_string());
    }
    file_in_folder("scene", spec, folder)
}

/// `builtin:sky` or an .hdr/.exr file relative to the tour's folder.
fn resolve_environment(spec: &str, folder: &Path) -> anyhow::Result<String> {
    if spec.starts_with("builtin:") {
        if spec != "builtin:sky" {
            bail!("env '{spec}': the built-in environment is builtin:sky");
        }
        return Ok(spec.to_string());
    }
    file_in_folder("env", spec, folder)
}

/// `spec` relative to the tour's folder, which must be a file (`key` names the field).
fn file_in_folder(key: &str, spec: &str, folder: &Path) -> anyhow::Result<String> {
    let path = folder.join(spec);
    if !path.is_file() {
        bail!("{key} '{spec}': no such file ({})", path.display());
    }
    Ok(path.display().to_string())
}

/// `camera = { position = [x, y, z], rotation = [x, y, z, w] | look_at = [x, y, z],
/// yfov_degrees = F }`: what the viewer's Camera section copies.
fn parse_camera(v: &Value) -> anyhow::Result<Camera> {
    let Value::Table(t) = v else {
        bail!("camera: expected a table, not {}", v.type_str());
    };
    for key in t.keys() {
        if !["position", "rotation", "look_at", "yfov_degrees"].contains(&key.as_str()) {
            bail!("camera: unknown key '{key}' (position, rotation or look_at, yfov_degrees)");
        }
    }
    let numbers = |key: &str, n: usize| -> anyhow::Result<Option<Vec<f32>>> {
        let Some(v) = t.get(key) else {
            return Ok(None);
        };
        let list: Option<Vec<f32>> = v.as_array().and_then(|a| a.iter().map(as_f32).collect());
        match list {
            Some(l) if l.len() == n && l.iter().all(|x| x.is_finite()) => Ok(Some(l)),
            _ => bail!("camera.{key}: expected {n} numbers, not {v}"),
        }
    };
    let position = numbers("position", 3)?.context("camera: 'position' is missing")?;
    let position = Vec3::from_slice(&position);
    let yfov = match t.get("yfov_degrees") {
        None => 45.0,
        Some(v) => as_f32(v)
            .filter(|d| (1.0..=179.0).contains(d))
            .with_context(|| format!("camera.yfov_degrees: expected 1..=179, not {v}"))?,
    }
    .to_radians();
    match (numbers("rotation", 4)?, numbers("look_at", 3)?) {
        (Some(q), None) => {
            let q = Quat::from_xyzw(q[0], q[1], q[2], q[3]);
            if q.length() < 1e-6 {
                bail!("camera.rotation: a zero quaternion");
            }
            Ok(Camera {
                position,
                rotation: q.normalize(),
                yfov,
            })
        }
        (None, Some(target)) => {
            let target = Vec3::from_slice(&target);
            if (target - position).length() < 1e-9 {
                bail!("camera.look_at: the camera's own position");
            }
            Ok(Camera::look_at(position, target, yfov))
        }
        (Some(_), Some(_)) => bail!("camera: give rotation or look_at, not both"),
        (None, None) => bail!("camera: give rotation or look_at"),
    }
}

/// B: a mode (this step's settings in that mode), a preset file (relative to the tour;
/// defaults plus the preset, as `--compare`), or an inline preset `{ label = "...", mode
/// = "...", name = value, ... }`: this step's settings with those values changed ("the
/// same, but ...").
fn parse_compare(v: &Value, folder: &Path, a: &Settings) -> anyhow::Result<CompareTarget> {
    match v {
        Value::String(s) if Mode::from_name(s).is_some() => CompareTarget::parse(s, a),
        Value::String(s) => CompareTarget::parse(&folder.join(s).display().to_string(), a)
            .map_err(|e| anyhow!("compare: {e:#}")),
        Value::Table(t) => {
            let mut t = t.clone();
            let label = match t.remove("label") {
                None => "B".to_string(),
                Some(Value::String(s)) => s,
                Some(v) => bail!("compare.label: expected a string, not {}", v.type_str()),
            };
            let mode = match t.remove("mode") {
                None => Mode::Restir,
                Some(Value::String(m)) => Mode::from_name(&m).with_context(|| {
                    format!("compare.mode '{m}': expected reference, nee, ris or restir")
                })?,
                Some(v) => bail!("compare.mode: expected a string, not {}", v.type_str()),
            };
            let (settings, _) = preset::parse_table(t, a).map_err(|e| anyhow!("compare: {e:#}"))?;
            Ok(CompareTarget {
                label,
                mode,
                settings,
            })
        }
        other => bail!(
            "compare: expected a mode, a preset file or a table, not {}",
            other.type_str()
        ),
    }
}

fn parse_show(v: &Value) -> anyhow::Result<Vec<LiveNumber>> {
    let names: Vec<&str> = LiveNumber::ALL.iter().map(|n| n.name()).collect();
    let Some(list) = v.as_array() else {
        bail!("show: expected a list such as [\"rmse\", \"bias\"], not {v}");
    };
    list.iter()
        .map(|item| {
            let s = item.as_str().unwrap_or_default();
            LiveNumber::ALL
                .into_iter()
                .find(|n| n.name() == s)
                .with_context(|| format!("show: '{item}' is not one of {}", names.join(", ")))
        })
        .collect()
}
