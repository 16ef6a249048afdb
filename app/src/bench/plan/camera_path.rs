//! `--camera`: the path a bench's camera takes, frame by frame: still, or turning about
//! the scene centre, turning in place, walking (docs/src/measured/how-the-bench-measures.md,
//! "Errors where the view moves").

use anyhow::{Context, bail};

/// `--camera static|orbit:DEG|pan:DEG|walk:M`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraPath {
    Static,
    /// Turns about the vertical axis through the scene centre by this many degrees per frame.
    Orbit(f32),
    /// Turns in place about the vertical axis by this many degrees per frame: new surfaces
    /// enter at one edge of the image, without parallax.
    Pan(f32),
    /// Moves forward along the view direction by this many scene units per frame: parallax,
    /// and surfaces disoccluded behind every edge that slides.
    Walk(f32),
}

/// The largest per-frame step a path takes: beyond it a frame shares nothing with the last
/// (a camera cut, `render --cut-at`, is the tool for that).
const MAX_DEGREES_PER_FRAME: f32 = 90.0;

impl CameraPath {
    pub fn parse(text: &str) -> anyhow::Result<CameraPath> {
        if text == "static" {
            return Ok(CameraPath::Static);
        }
        let usage = || {
            format!(
                "--camera '{text}': expected static, orbit:DEGREES_PER_FRAME, \
                 pan:DEGREES_PER_FRAME or walk:UNITS_PER_FRAME"
            )
        };
        let (kind, amount) = text.split_once(':').with_context(usage)?;
        let amount = amount
            .parse::<f32>()
            .ok()
            .filter(|d| d.is_finite())
            .with_context(usage)?;
        if amount == 0.0 {
            return Ok(CameraPath::Static);
        }
        let degrees = |d: f32| {
            if d.abs() > MAX_DEGREES_PER_FRAME {
                bail!(
                    "--camera '{text}': {d}° per frame leaves nothing to reuse; use at most \
                     {MAX_DEGREES_PER_FRAME}°"
                );
            }
            Ok(d)
        };
        Ok(match kind {
            "orbit" => CameraPath::Orbit(degrees(amount)?),
            "pan" => CameraPath::Pan(degrees(amount)?),
            "walk" => CameraPath::Walk(amount),
            _ => bail!(usage()),
        })
    }

    pub fn label(&self) -> String {
        match self {
            CameraPath::Static => "static".into(),
            CameraPath::Orbit(d) => format!("orbit {d}°/frame"),
            CameraPath::Pan(d) => format!("pan {d}°/frame"),
            CameraPath::Walk(m) => format!("walk {m}/frame"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_camera_paths_parse() {
        assert_eq!(CameraPath::parse("static").unwrap(), CameraPath::Static);
        assert_eq!(
            CameraPath::parse("orbit:0.5").unwrap(),
            CameraPath::Orbit(0.5)
        );
        assert_eq!(CameraPath::parse("orbit:0").unwrap(), CameraPath::Static);
        assert!(CameraPath::parse("orbit").is_err());
        assert!(CameraPath::parse("orbit:nan").is_err());
        assert!(CameraPath::parse("spin:3").is_err());
        assert_eq!(CameraPath::parse("pan:-1").unwrap(), CameraPath::Pan(-1.0));
        assert_eq!(
            CameraPath::parse("walk:0.02").unwrap(),
            CameraPath::Walk(0.02)
        );
        assert_eq!(CameraPath::parse("walk:0").unwrap(), CameraPath::Static);
        for bad in ["pan:inf", "walk:", "pan:200", "orbit:-91"] {
            let e = CameraPath::parse(bad).unwrap_err().to_string();
            assert!(e.contains(bad), "{bad}: {e}");
        }
    }
}
