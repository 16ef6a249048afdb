//! What `render` renders, resolved once from its flags and, with `--tour FILE
//! --tour-step K`, from that tour step: the step sets the scene, environment, camera,
//! time, mode, parameters, B, debug view and exposure; a flag given on the command line
//! wins over the step (`--set` applies on top of the step's parameters).

use anyhow::{Context, bail};
use restir_render::scene::Scene;
use restir_render::scene::animation::ClipChoice;
use restir_render::timeline::Timeline;
use restir_render::{Camera, DebugView, Mode, Settings};

use super::environment::EnvArgs;
use super::render::RenderArgs;
use crate::compare::CompareTarget;
use crate::tour::{Tour, TourStep};

pub struct Job {
    pub scene: String,
    pub env: EnvArgs,
    pub mode: Mode,
    pub settings: Settings,
    pub compare: Option<CompareTarget>,
    pub view: DebugView,
    /// `auto` or a number of stops.
    pub exposure: String,
    /// The first frame's camera (`None`: the scene's).
    pub camera: Option<Camera>,
    pub timeline: Timeline,
    /// One clip by name (a tour step's `clip`).
    pub clip: Option<String>,
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
        Ok(Job {
            scene,
            env,
            mode,
            settings,
            compare,
            view,
            exposure,
            camera: step.and_then(|s| s.camera),
            timeline: args.time.timeline_or(start, fps)?,
            clip: step.and_then(|s| s.time.clip.clone()),
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
