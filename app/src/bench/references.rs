//! The camera path of a bench and the reference images it is measured against: one for a
//! still camera, one per measured frame for an orbit, each loaded from the reference cache
//! or rendered (with progress on stderr) and stored there.

use std::io::Write;

use anyhow::{Context, bail};
use glam::Vec3;
use restir_render::effects::EffectSet;
use restir_render::phase_references::PhaseReferences;
use restir_render::reference_cache::{Progress, ReferenceCache, ReferenceRequest};
use restir_render::renderer::{JITTER_PERIOD, jitter_phase};
use restir_render::timeline::{AnimatedScene, Timeline};
use restir_render::{Camera, LinearImage, Renderer, Scene};

use crate::cli::camera_path::{orbit, pan, walk};

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

/// The camera of every frame: the scene's camera moved along the path; and, for an
/// animated scene, the scene time of every frame.
#[derive(Clone, Copy, Debug)]
pub struct Shot {
    pub start: Camera,
    pub center: Vec3,
    pub path: CameraPath,
    /// `--time`/`--fps` of an animated scene (`None` for a static one).
    pub timeline: Option<Timeline>,
}

impl Shot {
    pub fn of(renderer_start: Camera, center: Vec3, path: CameraPath) -> Shot {
        Shot {
            start: renderer_start,
            center,
            path,
            timeline: None,
        }
    }

    /// The same shot of an animated scene, whose frame i shows `timeline.time_of(i)`.
    pub fn with_time(self, timeline: Timeline) -> Shot {
        Shot {
            timeline: Some(timeline),
            ..self
        }
    }

    /// Scene time at frame `frame` (counted from the first warm-up frame).
    pub fn time(&self, frame: u32) -> f32 {
        self.timeline.map_or(0.0, |t| t.time_of(frame))
    }

    /// Whether frames differ from each other: a moving camera or running scene time. Then
    /// every measured frame has its own reference.
    pub fn moves(&self) -> bool {
        self.path != CameraPath::Static || self.timeline.is_some_and(|t| t.fps > 0.0)
    }

    /// The camera at frame `frame` (counted from the first warm-up frame).
    pub fn camera(&self, frame: u32) -> Camera {
        match self.path {
            CameraPath::Static => self.start,
            CameraPath::Orbit(d) => orbit(self.start, self.center, d * frame as f32),
            CameraPath::Pan(d) => pan(self.start, d * frame as f32),
            CameraPath::Walk(m) => walk(self.start, m * frame as f32),
        }
    }
}

/// The references of the measured frames.
pub struct References {
    /// One image (still camera) or one per measured frame.
    pub images: Vec<LinearImage>,
    pub spp: u32,
    /// The largest estimated own RMSE among them (see reference_cache docs).
    pub noise_luma_rmse: Option<f64>,
    pub noise_rgb_rmse: Option<f64>,
    pub loaded: usize,
    pub rendered: usize,
    pub render_seconds: f64,
    /// A still camera with jitter on: the reference of each jitter phase the measured
    /// frames use; their per-frame error is measured against it (docs/src/viewer.md,
    /// "Accuracy with jitter on"). `images[0]` stays the antialiased reference that the
    /// running average converges to.
    pub phases: Option<PhaseReferences>,
}

/// What the references are rendered with.
#[derive(Clone)]
pub struct ReferencePlan<'a> {
    /// With jitter on, the jitter phases whose references a still shot needs
    /// ([`measured_phases`]); empty otherwise.
    pub phases: Vec<u32>,
    pub cache: &'a ReferenceCache,
    pub scene_spec: &'a str,
    pub scene: &'a Scene,
    pub spp: u32,
    pub jitter: bool,
    /// `--effects` when forced, else what a still camera derives.
    pub effects: Option<EffectSet>,
    /// Path vertices the references shade (`max_bounces` of the configurations they serve).
    pub max_bounces: u32,
    /// The references sample lights with the light BVH (`--set reference_light_bvh=true`).
    pub light_bvh: bool,
    /// Light samples per vertex of the references (`--set reference_light_samples=N`).
    pub light_samples: u32,
}

/// Loads or renders the references of frames `first..first + count` of `shot` (one for a
/// still shot). An animated scene's `clock` poses the scene (and `renderer`) at each
/// frame's time first: a reference of one moment, keyed by that time. A still, jittered
/// shot also gets the reference of each of `plan.phases`.
pub fn obtain(
    renderer: &mut Renderer,
    plan: &ReferencePlan,
    shot: &Shot,
    first: u32,
    count: u32,
    mut clock: Option<&mut AnimatedScene>,
) -> anyhow::Result<References> {
    let frames: Vec<u32> = if shot.moves() {
        (first..first + count).collect()
    } else {
        vec![first]
    };
    let mut refs = References {
        images: Vec::with_capacity(frames.len()),
        spp: plan.spp,
        noise_luma_rmse: None,
        noise_rgb_rmse: None,
        loaded: 0,
        rendered: 0,
        render_seconds: 0.0,
        phases: None,
    };
    let bounces = match plan.max_bounces {
        1 => String::new(),
        n => format!(", {n} bounces"),
    };
    for (i, &frame) in frames.iter().enumerate() {
        if let Some(clock) = clock.as_deref_mut() {
            clock.set_time(renderer, shot.time(frame));
        }
        let scene = clock.as_deref().map_or(plan.scene, |c| c.scene());
        let request = request_of(plan, scene, shot.camera(frame), renderer.size());
        let label = format!("reference {}/{}{bounces}", i + 1, frames.len());
        let image = fetch(plan, renderer, &request, &label, &mut refs)?;
        refs.images.push(image);
    }
    if !plan.phases.is_empty() && !shot.moves() {
        let mut phases = PhaseReferences::default();
        for &phase in &plan.phases {
            let request = request_of(plan, plan.scene, shot.camera(first), renderer.size())
                .at_jitter_phase(phase);
            let label = format!("reference of jitter phase {phase}{bounces}");
            phases.insert(phase, fetch(plan, renderer, &request, &label, &mut refs)?);
        }
        refs.phases = Some(phases);
    }
    eprintln!(
        "references ({} bounce{}): {} loaded from {}, {} rendered ({:.1} s), {} spp each, \
         mean luma {:.5} (first)",
        plan.max_bounces,
        if plan.max_bounces == 1 { "" } else { "s" },
        refs.loaded,
        plan.cache.dir().display(),
        refs.rendered,
        refs.render_seconds,
        plan.spp,
        refs.images.first().map_or(0.0, LinearImage::mean_luminance),
    );
    Ok(refs)
}

/// The request for one reference of `plan` seen from `camera`.
fn request_of(
    plan: &ReferencePlan,
    scene: &Scene,
    camera: Camera,
    size: (u32, u32),
) -> ReferenceRequest {
    let mut request =
        ReferenceRequest::new(plan.scene_spec, scene, camera, size, plan.spp, plan.jitter)
            .with_light_bvh(plan.light_bvh, scene);
    if let Some(e) = &plan.effects {
        request.effects = e.clone();
    }
    request
        .with_max_bounces(plan.max_bounces)
        .with_light_samples(plan.light_samples)
}

/// Loads or renders one reference with progress on stderr, and counts it into `refs`.
fn fetch(
    plan: &ReferencePlan,
    renderer: &mut Renderer,
    request: &ReferenceRequest,
    label: &str,
    refs: &mut References,
) -> anyhow::Result<LinearImage> {
    let mut progress = |p: &Progress| {
        let eta = p
            .eta()
            .map(|d| format!(", ~{:.0} s left", d.as_secs_f64()))
            .unwrap_or_default();
        eprint!(
            "\r{label}: {}/{} spp ({:.1} s{eta})   ",
            p.samples_done,
            p.samples_total,
            p.elapsed.as_secs_f64()
        );
        let _ = std::io::stderr().flush();
        true
    };
    let reference = plan.cache.get_or_render(renderer, request, &mut progress)?;
    if reference.from_cache {
        refs.loaded += 1;
    } else {
        eprintln!();
        refs.rendered += 1;
        refs.render_seconds += reference.meta.render_seconds;
    }
    let max = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    };
    refs.noise_luma_rmse = max(refs.noise_luma_rmse, reference.meta.noise_luma_rmse);
    refs.noise_rgb_rmse = max(refs.noise_rgb_rmse, reference.meta.noise_rgb_rmse);
    if reference.image.non_finite_count() > 0 {
        bail!(
            "{}: the reference has non-finite pixels",
            reference.path.display()
        );
    }
    Ok(reference.image)
}

/// The jitter phases of the measured frames of every configuration when every seed runs
/// `measured` frames after `warmup` (ConfigRun::start renders two compile frames and the
/// warm-up on each configuration's own renderer, which renders nothing else), or every
/// phase when the frame count is not known in advance (equal time).
pub fn measured_phases(seeds: u32, warmup: u32, measured: Option<u32>) -> Vec<u32> {
    let Some(measured) = measured else {
        return (0..JITTER_PERIOD as u32).collect();
    };
    let per_seed = (2 + warmup + measured) as u64;
    let mut phases: Vec<u32> = (0..seeds as u64)
        .flat_map(|k| {
            (0..measured as u64).map(move |i| jitter_phase(k * per_seed + 2 + warmup as u64 + i))
        })
        .collect();
    phases.sort_unstable();
    phases.dedup();
    phases
}

/// The references of a bench: one set per `max_bounces` its configurations use, so each
/// configuration is scored against the integral it estimates (`path-2b` against a
/// 2-bounce reference, `ris` against the direct-light one).
pub struct ReferenceSets {
    /// (max_bounces, references), in the order the configurations first use them.
    sets: Vec<(u32, References)>,
}

impl ReferenceSets {
    /// [`obtain`] once per distinct value in `bounces` (the configurations' max_bounces).
    pub fn obtain(
        renderer: &mut Renderer,
        plan: &ReferencePlan,
        shot: &Shot,
        (first, count): (u32, u32),
        mut clock: Option<&mut AnimatedScene>,
        bounces: impl IntoIterator<Item = u32>,
    ) -> anyhow::Result<ReferenceSets> {
        let mut sets: Vec<(u32, References)> = Vec::new();
        for b in bounces {
            if sets.iter().any(|(have, _)| *have == b) {
                continue;
            }
            let plan = ReferencePlan {
                max_bounces: b,
                ..plan.clone()
            };
            let refs = obtain(renderer, &plan, shot, first, count, clock.as_deref_mut())?;
            sets.push((b, refs));
        }
        anyhow::ensure!(
            !sets.is_empty(),
            "no configuration to obtain references for"
        );
        Ok(ReferenceSets { sets })
    }

    /// The references of configurations with `max_bounces` (obtained for every one).
    pub fn for_bounces(&self, max_bounces: u32) -> &References {
        self.sets
            .iter()
            .find(|(b, _)| *b == max_bounces)
            .map(|(_, r)| r)
            .expect("references are obtained for every configuration's max_bounces")
    }

    /// The first configuration's references: what the report's reference line, the
    /// strip and the light events use.
    pub fn primary(&self) -> &References {
        &self.sets[0].1
    }

    /// The bounce counts with references, in order.
    pub fn bounces(&self) -> impl Iterator<Item = (u32, &References)> {
        self.sets.iter().map(|(b, r)| (*b, r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measured_frames_phases_follow_each_renderers_frame_count() {
        // Two compile frames, then 3 measured: frames 2, 3, 4; the next seed starts at 5.
        assert_eq!(measured_phases(2, 0, Some(3)), vec![2, 3, 4, 7, 8, 9]);
        // 62 warm-up frames: the measured frames 64..67 wrap to phases 0..3.
        assert_eq!(measured_phases(1, 62, Some(4)), vec![0, 1, 2, 3]);
        assert_eq!(measured_phases(1, 0, None).len(), JITTER_PERIOD as usize);
    }

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
