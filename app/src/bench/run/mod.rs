//! Running it: the scene on one renderer per configuration, the shot along the camera path
//! (`shot.rs`), the references every frame is measured against (`references.rs`, one set
//! per bounce count in `reference_sets.rs`), a dynamic scene's light events (`events.rs`)
//! and a moving shot's masks (`motion.rs`), all set up once; then every seed runs every
//! configuration, interleaved frame by frame (`seeds.rs`, `run_loop.rs`), each frame scored
//! as it is rendered (score/scoring.rs).

pub mod events;
pub mod motion;
pub mod reference_sets;
pub mod references;
pub mod run_loop;
pub mod seeds;
pub mod shot;

use std::time::Instant;

use anyhow::bail;
use restir_render::metrics::motion_masks::MotionMasks;
use restir_render::reference_cache::ReferenceCache;
use restir_render::scene::animation::ClipChoice;
use restir_render::timeline::{AnimatedScene, Timeline};
use restir_render::{Gpu, Renderer, Scene, load_scene};

use crate::bench::plan::Plan;
use crate::bench::plan::args::BenchArgs;
use crate::bench::plan::budget::Budget;
use crate::bench::plan::configs::Config;
use crate::bench::plan::knob::check_knob_points;
use crate::bench::score::over_seeds::{EventTimes, SeedReference};
use events::Events;
use reference_sets::{ReferenceSets, measured_phases};
use references::ReferencePlan;
use run_loop::RunPlan;
use shot::Shot;

/// What a bench renders with and measures against, set up before any seed runs.
pub struct Bench {
    pub gpu: Gpu,
    /// Posed at the first frame's time.
    pub scene: Scene,
    /// One renderer per configuration, so their frames can interleave (run_loop.rs).
    pub renderers: Vec<Renderer>,
    pub shot: Shot,
    pub references: ReferenceSets,
    /// How every configuration runs, with seed S (each seed runs it with its own).
    pub run_plan: RunPlan,
    /// Found on the first configuration's references; each configuration measures its lag
    /// against the references of its own max_bounces.
    pub events: Option<Events>,
    /// A moving shot's disoccluded and near-moving pixels, frame by frame (the same for
    /// every configuration and seed); none for a still shot or in equal-time mode.
    pub masks: Vec<MotionMasks>,
}

impl Bench {
    /// Loads the scene, uploads it once per configuration, checks a `--knob`'s points,
    /// then obtains the references and finds the events and masks.
    pub fn set_up(args: &BenchArgs, plan: &Plan) -> anyhow::Result<Bench> {
        let started = Instant::now();
        let (scene, timeline) = load(args)?;
        let gpu = Gpu::new_headless()?;
        let mut renderers = plan
            .configs
            .iter()
            .map(|_| {
                Renderer::new(
                    gpu.clone(),
                    &scene,
                    plan.size.0,
                    plan.size.1,
                    plan.base.clone(),
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        eprintln!(
            "{}: loaded and uploaded {} times in {:.1} s",
            args.scene,
            plan.configs.len(),
            started.elapsed().as_secs_f64()
        );
        if let Some(knob) = &args.knob {
            check_knob_points(&mut renderers[0], &plan.configs, knob)?;
        }
        let (shot, references) = obtain_references(args, plan, &gpu, &scene, timeline)?;
        let run_plan = RunPlan {
            frames: plan.measured,
            warmup: args.warmup,
            budget: args.budget_ms.map(|ms| Budget {
                ms,
                max_frames: args.max_frames.max(1),
            }),
            shot,
            seed: args.pipeline.seed,
            effects: plan.effects.clone(),
        };
        let events = Events::find(&scene, &shot, args.warmup, &references.primary().images);
        let masks = if shot.moves() && args.budget_ms.is_none() {
            motion::shot_masks(&scene, &shot, args.warmup, plan.measured, plan.size)
        } else {
            Vec::new()
        };
        Ok(Bench {
            gpu,
            scene,
            renderers,
            shot,
            references,
            run_plan,
            events,
            masks,
        })
    }

    /// An animated scene's clock for one renderer (none for a still scene): each poses
    /// its own copy of the scene.
    pub fn clock(&self) -> Option<AnimatedScene> {
        self.scene
            .animation
            .is_some()
            .then(|| AnimatedScene::new(self.scene.clone()))
    }

    /// The reference each configuration's figures over seeds are scored against.
    pub fn seed_references(&self, configs: &[Config]) -> Vec<SeedReference<'_>> {
        configs
            .iter()
            .map(|c| {
                let own = self.references.for_bounces(c.settings.reference_bounces());
                SeedReference {
                    image: &own.images[0],
                    noise: own.noise_luma_rmse,
                    frame_noise: own.frame_noise_luma(),
                }
            })
            .collect()
    }

    /// The light events' frames and times, when there are any.
    pub fn event_times(&self) -> Option<EventTimes<'_>> {
        self.events.as_ref().map(|e| EventTimes {
            frames: &e.frames,
            times: &e.times,
        })
    }
}

/// The scene with `--env`, posed at the first frame's time, and the `--time`/`--fps`
/// timeline.
fn load(args: &BenchArgs) -> anyhow::Result<(Scene, Timeline)> {
    let timeline = args.time.timeline()?;
    let mut scene = load_scene(&args.scene)?;
    args.env.apply(&mut scene)?;
    if scene.animation.is_some() && args.budget_ms.is_some() && timeline.fps > 0.0 {
        bail!("--budget-ms compares running averages of one moment: use --fps 0");
    }
    scene.pose(timeline.time_of(0), ClipChoice::All);
    Ok((scene, timeline))
}

/// The shot and its references, loaded from the cache or rendered.
fn obtain_references(
    args: &BenchArgs,
    plan: &Plan,
    gpu: &Gpu,
    scene: &Scene,
    timeline: Timeline,
) -> anyhow::Result<(Shot, ReferenceSets)> {
    let (w, h) = plan.size;
    // The references get a renderer of their own: a configuration's frames then depend on
    // its seed alone, never on whether its renderer rendered a reference first (so a sweep
    // split into jobs measures what one process measures; docs/src/headless.md).
    let mut renderer = Renderer::new(gpu.clone(), scene, w, h, plan.base.clone())?;
    let mut shot = Shot::of(
        renderer.camera(),
        renderer.scene_bounds().center(),
        plan.camera,
    );
    let mut clock = None;
    if scene.animation.is_some() {
        shot = shot.with_time(timeline);
        clock = Some(AnimatedScene::new(scene.clone()));
    }
    let cache = ReferenceCache::new(
        args.cache_dir
            .clone()
            .unwrap_or_else(ReferenceCache::default_dir),
    );
    let reference_plan = ReferencePlan {
        cache: &cache,
        scene_spec: &args.scene,
        scene,
        spp: args.reference_spp,
        jitter: plan.base.jitter,
        effects: plan.effects.clone(),
        max_bounces: 1,
        light_bvh: plan.base.reference_light_bvh,
        light_samples: plan.base.reference_light_samples,
        phases: if plan.base.jitter {
            let measured = args.budget_ms.is_none().then_some(plan.measured);
            measured_phases(args.seeds, args.warmup, measured)
        } else {
            Vec::new()
        },
    };
    let references = ReferenceSets::obtain(
        &mut renderer,
        &reference_plan,
        &shot,
        (args.warmup, plan.measured),
        clock.as_mut(),
        plan.configs.iter().map(|c| c.settings.reference_bounces()),
    )?;
    Ok((shot, references))
}
