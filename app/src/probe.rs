//! A pixel's history (docs/src/viewer.md, "Pixel history"): one row per frame of what the pixel
//! inspector captured at the selected pixel — its luminance, the reference there when one exists
//! for the moment shown, and the survivor's M, W, source, light and age — plus whether a light
//! event of the scene fell on that frame. The viewer's inspector charts the last N rows and exports
//! them; `render --probe X,Y --probe-out FILE.csv` writes the same rows headless.

use std::collections::VecDeque;
use std::path::Path;

use anyhow::{Context, bail};
use restir_render::di::constants::{AGE_SHIFT, SOURCE_MASK};
use restir_render::gpu_types::NO_LIGHT;
use restir_render::image::luminance;
use restir_render::renderer::PixelInspection;
use restir_render::scene::animation::{ClipChoice, SceneAnimation};
use restir_render::shader_constants::SOURCE_NAMES;

/// One frame at the probed pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeSample {
    pub frame: u64,
    /// Scene time of the frame (animated scenes).
    pub time: Option<f32>,
    pub rgb: [f32; 3],
    pub luminance: f32,
    /// The reference's luminance at the pixel, when there is a reference of this moment.
    pub reference: Option<f32>,
    /// The survivor after the last stage: M, W, source (`SOURCE_*`), light, age.
    pub m: f32,
    pub w: f32,
    pub source: u32,
    /// `None`: the null sample.
    pub light: Option<u32>,
    pub age: u32,
    /// A light event of the scene (a STEP emission key) happened since the last frame.
    pub event: bool,
}

impl ProbeSample {
    /// The row of one inspection. A reference frame has no stages: M, W and age are 0.
    pub fn from_inspection(
        i: &PixelInspection,
        time: Option<f32>,
        reference: Option<f32>,
        event: bool,
    ) -> ProbeSample {
        let last = i.stages.last().map(|s| s.reservoir);
        ProbeSample {
            frame: i.frame,
            time,
            rgb: i.radiance,
            luminance: luminance(i.radiance),
            reference,
            m: last.map_or(0.0, |r| r.m),
            w: i.debug.weight,
            source: i.debug.source,
            light: last.map(|r| r.light).filter(|&l| l != NO_LIGHT),
            age: last.map_or(0, |r| r.source >> AGE_SHIFT),
            event,
        }
    }

    pub fn source_name(&self) -> &'static str {
        SOURCE_NAMES
            .get((self.source & SOURCE_MASK) as usize)
            .copied()
            .unwrap_or("?")
    }
}

/// The last `capacity` samples of one pixel, oldest first.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelHistory {
    pub pixel: Option<(u32, u32)>,
    pub capacity: usize,
    pub samples: VecDeque<ProbeSample>,
}

impl PixelHistory {
    /// The inspector's default length.
    pub const DEFAULT_FRAMES: usize = 120;
    pub const FRAMES_RANGE: std::ops::RangeInclusive<usize> = 10..=2000;

    pub fn new(capacity: usize) -> PixelHistory {
        PixelHistory {
            pixel: None,
            capacity,
            samples: VecDeque::new(),
        }
    }

    /// Adds the sample of `pixel`; a new pixel starts a new history.
    pub fn push(&mut self, pixel: (u32, u32), sample: ProbeSample) {
        if self.pixel != Some(pixel) {
            self.pixel = Some(pixel);
            self.samples.clear();
        }
        if self.samples.back().is_some_and(|s| s.frame >= sample.frame) {
            return;
        }
        self.samples.push_back(sample);
        self.trim();
    }

    /// Drops what no longer fits (after `capacity` shrank).
    pub fn trim(&mut self) {
        while self.samples.len() > self.capacity.max(1) {
            self.samples.pop_front();
        }
    }

    pub fn clear(&mut self) {
        self.pixel = None;
        self.samples.clear();
    }
}

/// The CSV's columns (docs/src/viewer.md, "Pixel history").
pub const CSV_HEADER: &str = "frame,time,x,y,r,g,b,luminance,reference,m,w,source,light,age,event";

/// Writes `samples` of pixel `pixel` as CSV (empty cells for what is not known).
pub fn write_csv<'a>(
    path: &Path,
    pixel: (u32, u32),
    samples: impl IntoIterator<Item = &'a ProbeSample>,
) -> anyhow::Result<()> {
    let opt = |v: Option<String>| v.unwrap_or_default();
    let mut text = format!("{CSV_HEADER}\n");
    for s in samples {
        text.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            s.frame,
            opt(s.time.map(|t| t.to_string())),
            pixel.0,
            pixel.1,
            s.rgb[0],
            s.rgb[1],
            s.rgb[2],
            s.luminance,
            opt(s.reference.map(|r| r.to_string())),
            s.m,
            s.w,
            s.source_name(),
            opt(s.light.map(|l| l.to_string())),
            s.age,
            u8::from(s.event),
        ));
    }
    std::fs::write(path, text).with_context(|| format!("{}: cannot write", path.display()))
}

/// `X,Y` inside a `size` image (`--probe`).
pub fn parse_pixel(text: &str, size: (u32, u32)) -> anyhow::Result<(u32, u32)> {
    let parsed = text
        .split_once(',')
        .and_then(|(x, y)| Some((x.trim().parse::<u32>().ok()?, y.trim().parse::<u32>().ok()?)));
    let Some((x, y)) = parsed else {
        bail!("--probe '{text}': expected X,Y (pixel column and row, from 0)");
    };
    if x >= size.0 || y >= size.1 {
        bail!(
            "--probe {x},{y}: outside the {}x{} image (0..{}, 0..{})",
            size.0,
            size.1,
            size.0,
            size.1
        );
    }
    Ok((x, y))
}

/// Whether a light event of `animation` falls in (t0, t1] of scene time (the bench's
/// rule: the first frame whose clip time has passed the event).
pub fn event_between(animation: Option<&SceneAnimation>, t0: f32, t1: f32) -> bool {
    let Some(anim) = animation else {
        return false;
    };
    let events = anim.light_events(ClipChoice::All);
    let duration = anim.duration(ClipChoice::All);
    let wrap = |t: f32| anim.wrap(t, ClipChoice::All);
    !restir_render::timeline::event_frames(&[t0, t1], &events, duration, wrap).is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(frame: u64, luminance: f32) -> ProbeSample {
        ProbeSample {
            frame,
            time: Some(frame as f32 / 30.0),
            rgb: [luminance; 3],
            luminance,
            reference: None,
            m: 3.0,
            w: 0.5,
            source: 2,
            light: Some(7),
            age: 4,
            event: frame == 2,
        }
    }

    #[test]
    fn a_history_keeps_the_last_frames_of_one_pixel() {
        let mut h = PixelHistory::new(3);
        for f in 0..5 {
            h.push((1, 2), sample(f, f as f32));
        }
        let frames: Vec<u64> = h.samples.iter().map(|s| s.frame).collect();
        assert_eq!(frames, vec![2, 3, 4]);
        // The same frame again (a redisplay) is not a new row.
        h.push((1, 2), sample(4, 9.0));
        assert_eq!(h.samples.len(), 3);
        h.push((5, 5), sample(9, 1.0));
        assert_eq!((h.pixel, h.samples.len()), (Some((5, 5)), 1));
    }

    #[test]
    fn the_csv_has_one_row_per_frame_and_probe_coordinates_are_checked() {
        let path = std::env::temp_dir().join(format!("restir-probe-{}.csv", std::process::id()));
        write_csv(&path, (4, 5), &[sample(1, 0.25), sample(2, 0.5)]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], CSV_HEADER);
        assert_eq!(
            lines[2],
            "2,0.06666667,4,5,0.5,0.5,0.5,0.5,,3,0.5,temporal,7,4,1"
        );
        assert_eq!(parse_pixel("3, 4", (10, 10)).unwrap(), (3, 4));
        let e = parse_pixel("10,0", (10, 8)).unwrap_err().to_string();
        assert!(e.contains("--probe 10,0: outside the 10x8 image"), "{e}");
        assert!(
            parse_pixel("a,b", (10, 8))
                .unwrap_err()
                .to_string()
                .contains("expected X,Y")
        );
    }
}
