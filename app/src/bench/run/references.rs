//! The reference images a bench is measured against: one for a still shot, one per measured
//! frame of a moving one, each loaded from the reference cache or rendered (with progress on
//! stderr) and stored there.

use std::io::Write;

use anyhow::bail;
use restir_render::effects::EffectSet;
use restir_render::phase_references::PhaseReferences;
use restir_render::reference_cache::{Progress, ReferenceCache, ReferenceRequest};
use restir_render::timeline::AnimatedScene;
use restir_render::{Camera, LinearImage, Renderer, Scene};

use super::shot::Shot;

/// The references of the measured frames.
pub struct References {
    /// One image (still camera) or one per measured frame.
    pub images: Vec<LinearImage>,
    pub spp: u32,
    /// The largest estimated own RMSE among `images` (see reference_cache docs): the
    /// noise in every error against them, the accumulated image's included.
    pub noise_luma_rmse: Option<f64>,
    pub noise_rgb_rmse: Option<f64>,
    /// The largest among the jitter phases' references, which a jittered still shot's
    /// per-frame errors are measured against instead. Not the antialiased reference's:
    /// that one integrates the pixel footprint and is several times noisier at the same
    /// spp (docs/src/measured/how-the-bench-measures.md, "How it measures").
    pub phase_noise_luma_rmse: Option<f64>,
    pub phase_noise_rgb_rmse: Option<f64>,
    pub loaded: usize,
    pub rendered: usize,
    pub render_seconds: f64,
    /// A still camera with jitter on: the reference of each jitter phase the measured
    /// frames use; their per-frame error is measured against it (docs/src/viewer.md,
    /// "Accuracy with jitter on"). `images[0]` stays the antialiased reference that the
    /// running average converges to.
    pub phases: Option<PhaseReferences>,
}

impl References {
    /// The reference noise in every per-frame error: the phases' with jitter on (a still
    /// shot), else the references' own.
    pub fn frame_noise_luma(&self) -> Option<f64> {
        match self.phases {
            Some(_) => self.phase_noise_luma_rmse,
            None => self.noise_luma_rmse,
        }
    }
}

/// Which of a bench's references one is: its noise is counted with its kind's.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Shot,
    Phase,
}

/// What the references are rendered with.
#[derive(Clone)]
pub struct ReferencePlan<'a> {
    /// With jitter on, the jitter phases whose references a still shot needs
    /// (`reference_sets::measured_phases`); empty otherwise.
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
        phase_noise_luma_rmse: None,
        phase_noise_rgb_rmse: None,
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
        let image = fetch(plan, renderer, &request, &label, Kind::Shot, &mut refs)?;
        refs.images.push(image);
    }
    if !plan.phases.is_empty() && !shot.moves() {
        let mut phases = PhaseReferences::default();
        for &phase in &plan.phases {
            let request = request_of(plan, plan.scene, shot.camera(first), renderer.size())
                .at_jitter_phase(phase);
            let label = format!("reference of jitter phase {phase}{bounces}");
            let image = fetch(plan, renderer, &request, &label, Kind::Phase, &mut refs)?;
            phases.insert(phase, image);
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
    kind: Kind,
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
    let (luma, rgb) = match kind {
        Kind::Shot => (&mut refs.noise_luma_rmse, &mut refs.noise_rgb_rmse),
        Kind::Phase => (
            &mut refs.phase_noise_luma_rmse,
            &mut refs.phase_noise_rgb_rmse,
        ),
    };
    *luma = max(*luma, reference.meta.noise_luma_rmse);
    *rgb = max(*rgb, reference.meta.noise_rgb_rmse);
    if reference.image.non_finite_count() > 0 {
        bail!(
            "{}: the reference has non-finite pixels",
            reference.path.display()
        );
    }
    Ok(reference.image)
}
