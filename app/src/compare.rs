//! Split-screen comparison, the way people compare renderers: configuration A (what is
//! being tuned) left of a divider, configuration B right of it, both rendered every frame
//! from the same camera, each with its own renderer and history. `render --compare B` and
//! the viewer's Compare section share what is here: what B can be, and the split itself.

use std::path::Path;

use anyhow::Context;
use restir_render::settings::preset;
use restir_render::{Mode, Settings};

/// Configuration B.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareTarget {
    /// What the user typed, shown on the image and in the stats (`ris`, `fast.toml`).
    pub label: String,
    pub mode: Mode,
    pub settings: Settings,
}

impl CompareTarget {
    /// `reference`, `nee`, `ris` or `restir` (A's settings in that mode), optionally with
    /// `+denoise` or `+raw` (the denoiser on or off: `restir+raw` beside a denoised A is
    /// raw | denoised; `ris+denoise` beside it is two configurations, both denoised), or a
    /// preset, built in (`restir-denoised`) or a file (defaults plus the preset, `restir`
    /// mode: the preset *is* the configuration).
    pub fn parse(spec: &str, a_settings: &Settings) -> anyhow::Result<CompareTarget> {
        let spec = spec.trim();
        let (mode_name, denoise) = match spec.split_once('+') {
            Some((mode, "denoise")) => (mode, Some(true)),
            Some((mode, "raw")) => (mode, Some(false)),
            _ => (spec, None),
        };
        if let Some(mode) = Mode::from_name(mode_name) {
            let mut settings = a_settings.clone();
            if let Some(on) = denoise {
                settings.denoise = on;
            }
            return Ok(CompareTarget {
                label: spec.to_string(),
                mode,
                settings,
            });
        }
        if let Some(assignments) = preset::builtin(spec) {
            let mut settings = Settings::default();
            settings.apply_assignments(assignments.iter().copied())?;
            return Ok(CompareTarget {
                label: spec.to_string(),
                mode: Mode::Restir,
                settings,
            });
        }
        let path = Path::new(spec);
        if spec.ends_with(".toml") || path.is_file() {
            let (settings, warnings) = preset::load(path, &Settings::default())?;
            for w in warnings {
                log::warn!("{spec}: {w}");
            }
            let label = path
                .file_name()
                .and_then(|n| n.to_str())
                .with_context(|| format!("--compare '{spec}': no usable file name"))?
                .to_string();
            return Ok(CompareTarget {
                label,
                mode: Mode::Restir,
                settings,
            });
        }
        anyhow::bail!(
            "--compare '{spec}': expected reference, nee, ris or restir (each optionally \
             +denoise or +raw), restir-denoised or a preset .toml file"
        )
    }
}

/// The first column that shows B, for a divider at `fraction` (0 = all B, 1 = all A).
pub fn divider_column(width: u32, fraction: f32) -> u32 {
    (fraction.clamp(0.0, 1.0) * width as f32).round() as u32
}

/// One image of `width` columns: A's pixels left of `divider`, B's from it on. Works for
/// any pixel type (RGBA8 of the display, linear RGBA of an EXR).
pub fn split_columns<T: Copy>(a: &[T], b: &[T], width: u32, divider: u32) -> Vec<T> {
    assert_eq!(a.len(), b.len(), "both sides have the same size");
    let width = width.max(1) as usize;
    let divider = (divider as usize).min(width);
    a.chunks(width)
        .zip(b.chunks(width))
        .flat_map(|(row_a, row_b)| row_a[..divider].iter().chain(&row_b[divider..]))
        .copied()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn split_takes_columns_left_of_the_divider_from_a() {
        // 3 × 2 images of distinct values.
        let a = [1, 2, 3, 4, 5, 6];
        let b = [10, 20, 30, 40, 50, 60];
        assert_eq!(split_columns(&a, &b, 3, 1), vec![1, 20, 30, 4, 50, 60]);
        assert_eq!(split_columns(&a, &b, 3, 0), b.to_vec());
        assert_eq!(split_columns(&a, &b, 3, 3), a.to_vec());
        assert_eq!(split_columns(&a, &b, 3, 9), a.to_vec());
        assert_eq!(divider_column(225, 0.5), 113);
        assert_eq!(divider_column(10, -1.0), 0);
    }

    #[test]
    fn compare_targets_are_modes_or_presets() {
        let a = Settings {
            m_cap: 7.0,
            ..Settings::default()
        };
        let ris = CompareTarget::parse("ris", &a).unwrap();
        assert_eq!((ris.mode, ris.settings.m_cap), (Mode::Ris, 7.0));
        let dir = std::env::temp_dir().join(format!("restir-compare-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("short-history.toml");
        std::fs::write(&file, "m_cap = 3\n").unwrap();
        let p = CompareTarget::parse(file.to_str().unwrap(), &a).unwrap();
        assert_eq!(
            (p.label.as_str(), p.mode, p.settings.m_cap),
            ("short-history.toml", Mode::Restir, 3.0)
        );
        let raw = CompareTarget::parse(
            "restir+raw",
            &Settings {
                denoise: true,
                ..a.clone()
            },
        );
        let raw = raw.unwrap();
        assert_eq!(
            (raw.mode, raw.settings.denoise, raw.settings.m_cap),
            (Mode::Restir, false, 7.0)
        );
        let ris = CompareTarget::parse("ris+denoise", &a).unwrap();
        assert!(ris.mode == Mode::Ris && ris.settings.denoise && ris.label == "ris+denoise");
        assert!(CompareTarget::parse("ris+loud", &a).is_err());
        let e = CompareTarget::parse("magic", &a).unwrap_err().to_string();
        assert!(e.contains("'magic'"), "{e}");
        assert!(CompareTarget::parse("missing.toml", &a).is_err());
    }
}
