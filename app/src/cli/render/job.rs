//! What `render` renders and writes, resolved once from its flags and, with `--tour FILE
//! --tour-step K`, from that tour step: the step sets the scene, environment, camera,
//! time, mode, parameters, B, debug view and exposure; a flag given on the command line
//! wins over the step (`--set` applies on top of the step's parameters).
//!
//! This is the only module that reads `RenderArgs`. The checks run in the order the
//! command has always run them, so a command line with two mistakes reports the same one.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use restir_render::effects::EffectSet;
use restir_render::scene::Scene;
use restir_render::scene::animation::ClipChoice;
use restir_render::timeline::Timeline;
use restir_render::{Camera, DebugView, Mode, Settings};

use super::args::RenderArgs;
use crate::cli::environment::EnvArgs;
use crate::cli::setup::parse_size;
use crate::compare::CompareTarget;
use crate::probe;
use crate::recording::{RecordingPlan, SequenceFormat};
use crate::tour::{Tour, TourStep};

pub struct Job {
    pub scene: String,
    pub env: EnvArgs,
    pub mode: Mode,
    pub settings: Settings,
    pub compare: Option<CompareTarget>,
    pub view: DebugView,
    /// `auto` or a number of stops (checked by `fixed_exposure`).
    pub exposure: String,
    /// The first frame's camera (`None`: the scene's).
    pub camera: Option<Camera>,
    pub timeline: Timeline,
    /// One clip by name (a tour step's `clip`).
    pub clip: Option<String>,
    /// Output size in pixels, (width, height).
    pub size: (u32, u32),
    /// Frames to render (at least 1).
    pub frames: u32,
    /// Write the average of all frames instead of the last one.
    pub accumulate: bool,
    /// Seed of every random stream.
    pub seed: u32,
    /// `--effects`, when it names a set (`None`: from the scene).
    pub effects: Option<EffectSet>,
    pub motion: CameraMotion,
    pub outputs: Outputs,
    /// Samples per pixel of the reference the error and bias views compare with, and
    /// where it is cached (`None`: the default cache folder).
    pub reference_spp: u32,
    pub cache_dir: Option<PathBuf>,
}

/// How the camera moves from frame to frame (`--orbit`, `--cut-at`).
#[derive(Clone, Copy)]
pub struct CameraMotion {
    /// Degrees per frame about the scene centre.
    pub orbit: f32,
    /// The frame at which the camera jumps to a distant viewpoint.
    pub cut_at: Option<u32>,
}

/// What is written (at least one of them).
pub struct Outputs {
    /// `--out` and its format, from the file's extension.
    pub image: Option<(PathBuf, Format)>,
    /// `--stats`: the JSON document.
    pub stats: Option<PathBuf>,
    /// `--out-sequence` and `--gif`.
    pub recording: RecordingPlan,
    /// `--probe`: the pixel whose history is recorded, and `--probe-out`, its CSV.
    pub probe: Option<(u32, u32)>,
    pub probe_out: Option<PathBuf>,
}

/// The image file's kind.
#[derive(Clone, Copy, PartialEq)]
pub enum Format {
    /// Linear radiance.
    Exr,
    /// What the display shows.
    Png,
}

impl Job {
    pub fn resolve(args: &RenderArgs) -> anyhow::Result<Job> {
        let step = match &args.tour {
            Some(path) => {
                if args.pipeline.preset.is_some() {
                    bail!("--preset with --tour: the tour step is the preset (use --set on top)");
                }
                let tour = Tour::load(path)?;
                Some(tour.step(args.tour_step)?.clone())
            }
            None => None,
        };
        let step = step.as_ref();
        let scene = args
            .scene
            .clone()
            .or_else(|| step.map(|s| s.scene.clone()))
            .context("--scene is required (or --tour FILE --tour-step K)")?;
        let mode = match (&args.mode, step) {
            (Some(m), _) => Mode::from_name(m)
                .with_context(|| format!("--mode '{m}': expected reference, nee, ris or restir"))?,
            (None, Some(s)) => s.mode,
            (None, None) => Mode::Restir,
        };
        let view = match (&args.debug_view, step) {
            (Some(v), _) => DebugView::from_name(v).with_context(|| {
                let names: Vec<_> = DebugView::ALL.iter().map(|v| v.name()).collect();
                format!("--debug-view '{v}': expected one of {}", names.join(", "))
            })?,
            (None, Some(s)) => s.debug_view,
            (None, None) => DebugView::Final,
        };
        let settings = settings(args, step)?;
        let compare = match (&args.compare, step) {
            (Some(spec), _) => Some(CompareTarget::parse(spec, &settings)?),
            (None, Some(s)) => s.compare.clone(),
            (None, None) => None,
        };
        let mut env = args.env.clone();
        if env.env.is_none() {
            env.env = step.and_then(|s| s.env.clone());
        }
        let exposure = args
            .exposure
            .clone()
            .or_else(|| step.and_then(|s| s.exposure).map(|ev| ev.to_string()))
            .unwrap_or_else(|| "auto".to_string());
        let (start, fps) = match step {
            Some(s) => (
                s.time.start.unwrap_or(0.0),
                if s.time.paused {
                    0.0
                } else {
                    s.time.fps.unwrap_or(30.0)
                },
            ),
            None => (0.0, 30.0),
        };
        let timeline = args.time.timeline_or(start, fps)?;
        let size = parse_size(&args.size)?;
        let image = image_output(args, view)?;
        check_frames_and_outputs(args)?;
        let probe = args
            .probe
            .as_deref()
            .map(|p| probe::parse_pixel(p, size))
            .transpose()?;
        let effects = args.pipeline.effects()?;
        if view == DebugView::Difference && compare.is_none() {
            bail!("--debug-view difference shows |A − B|: it needs --compare B");
        }
        let recording = RecordingPlan {
            sequence: args
                .out_sequence
                .clone()
                .map(|dir| anyhow::Ok((dir, SequenceFormat::parse(&args.sequence_format)?)))
                .transpose()?,
            gif: args.gif.clone(),
            fps: timeline.fps,
        };
        Ok(Job {
            scene,
            env,
            mode,
            settings,
            compare,
            view,
            exposure,
            camera: step.and_then(|s| s.camera),
            timeline,
            clip: step.and_then(|s| s.time.clip.clone()),
            size,
            frames: args.frames,
            accumulate: args.accumulate,
            seed: args.pipeline.seed,
            effects,
            motion: CameraMotion {
                orbit: args.orbit,
                cut_at: args.cut_at,
            },
            outputs: Outputs {
                image,
                stats: args.stats.clone(),
                recording,
                probe,
                probe_out: args.probe_out.clone(),
            },
            reference_spp: args.reference_spp,
            cache_dir: args.cache_dir.clone(),
        })
    }

    /// The clip choice for `scene` (`clip` names one of its clips).
    pub fn clip_choice(&self, scene: &Scene) -> anyhow::Result<ClipChoice> {
        let Some(name) = &self.clip else {
            return Ok(ClipChoice::All);
        };
        let clips: Vec<&str> = scene
            .animation
            .as_ref()
            .map(|a| a.clips.iter().map(|c| c.name.as_str()).collect())
            .unwrap_or_default();
        clips
            .iter()
            .position(|c| c == name)
            .map(ClipChoice::One)
            .with_context(|| {
                format!(
                    "clip '{name}': {} has {}",
                    self.scene,
                    if clips.is_empty() {
                        "no clips".to_string()
                    } else {
                        format!("the clips {}", clips.join(", "))
                    }
                )
            })
    }

    /// `--exposure` as a number of stops, or `None` for `auto`. `run` asks for it once the
    /// scene is loaded and the device is open, where the command has always checked it, so
    /// a bad scene is still reported before a bad exposure.
    pub fn fixed_exposure(&self) -> anyhow::Result<Option<f32>> {
        match self.exposure.as_str() {
            "auto" => Ok(None),
            text => text
                .parse::<f32>()
                .ok()
                .filter(|x| x.is_finite())
                .map(Some)
                .with_context(|| {
                    format!("--exposure '{text}': expected a number of stops or auto")
                }),
        }
    }
}

/// Defaults (or the step's parameters), the preset, then `--set` and `--spp`.
fn settings(args: &RenderArgs, step: Option<&TourStep>) -> anyhow::Result<Settings> {
    let mut settings = match step {
        Some(s) => {
            let mut settings = s.settings.clone();
            for w in settings
                .apply_assignments(args.pipeline.set.iter().map(String::as_str))
                .map_err(|e| anyhow::anyhow!("--set {e}"))?
            {
                eprintln!("warning: --set {w}");
            }
            settings
        }
        None => args.pipeline.settings(&[])?,
    };
    if let Some(spp) = args.spp {
        settings
            .set_from_str("reference_spp", &spp.to_string())
            .map_err(|e| anyhow::anyhow!("--spp: {e}"))?;
    }
    Ok(settings)
}

/// `--out` and its format; a debug view is colours, which only a PNG holds.
fn image_output(args: &RenderArgs, view: DebugView) -> anyhow::Result<Option<(PathBuf, Format)>> {
    let Some(out) = &args.out else {
        return Ok(None);
    };
    let format = output_format(out)?;
    if view != DebugView::Final && format == Format::Exr {
        bail!(
            "--debug-view {} writes colours: use a .png --out",
            view.name()
        );
    }
    Ok(Some((out.clone(), format)))
}

/// At least one frame, and something to write.
fn check_frames_and_outputs(args: &RenderArgs) -> anyhow::Result<()> {
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    if args.out.is_none()
        && args.out_sequence.is_none()
        && args.gif.is_none()
        && args.probe_out.is_none()
    {
        bail!("nothing to write: give --out, --out-sequence, --gif or --probe-out");
    }
    Ok(())
}

fn output_format(path: &Path) -> anyhow::Result<Format> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("exr") => Ok(Format::Exr),
        Some("png") => Ok(Format::Png),
        _ => bail!("--out '{}': expected a .exr or .png file", path.display()),
    }
}
