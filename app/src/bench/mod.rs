//! `bench`: what accuracy costs in time. Runs named configurations from a clean
//! history with the same seed against a cached reference and writes `results.csv`,
//! `frames.csv`, `results.md` and PNG plots; `--budget-ms` compares them at equal time and
//! `--sweep-lights` times light selection against the light count. See docs/bench.md.
//!
//! `configs` names what runs, `references` finds the images to compare with, `run_loop`
//! measures one configuration, `scoring` turns frames into the numbers docs/bench.md defines
//! ("How it measures"),
//! `equal_time` holds the budget rule, `csv`, `markdown` and `plots` write the results and
//! `sweep` is the light-count benchmark.

pub mod bvh_cost;
mod compile_table;
pub(crate) mod configs;
pub(crate) mod csv;
pub mod env_cost;
mod equal_error;
mod equal_time;
mod equal_time_gain;
mod event_strip;
mod events;
pub mod jobs;
mod lag;
pub mod load_cost;
pub mod map;
pub(crate) mod markdown;
mod motion;
mod plots;
pub mod ray_cost;
mod references;
mod run_loop;
mod scoring;
pub mod seed_figures;
mod seed_maps;
pub mod shift_cost;
mod strip;
mod sweep;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, bail};
use clap::Args;
use restir_render::metrics::motion_masks::MotionMasks;
use restir_render::reference_cache::ReferenceCache;
use restir_render::scene::animation::ClipChoice;
use restir_render::timeline::AnimatedScene;
use restir_render::{Gpu, Renderer, load_scene};

use crate::cli::environment::EnvArgs;
use crate::cli::setup::{PipelineArgs, parse_size};
use configs::{BASE_ASSIGNMENTS, DEFAULT_CONFIGS, parse_configs};
use equal_time::{Budget, mse_ratio};
use events::{Events, LagProbe};
use references::{CameraPath, ReferencePlan, ReferenceSets, References, Shot};
use run_loop::{ConfigResult, ConfigRun, RunPlan, run_interleaved};
use scoring::Scoring;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A .gltf/.glb file or a built-in scene (`builtin:many-lights`, see `scenes`).
    #[arg(long)]
    pub scene: String,
    /// Output size, WxH.
    #[arg(long)]
    pub size: String,
    /// Measured frames per configuration (not with --budget-ms).
    #[arg(long, required_unless_present = "budget_ms")]
    pub frames: Option<u32>,
    /// static; orbit:DEG (turn DEG degrees per frame about the scene centre); pan:DEG (turn
    /// in place); walk:M (move M scene units per frame along the view).
    #[arg(long, default_value = "static")]
    pub camera: String,
    /// Comma-separated configurations and preset files (.toml).
    #[arg(long, default_value = DEFAULT_CONFIGS)]
    pub configs: String,
    /// A cost curve per configuration: each runs once per value of this parameter
    /// (`light_candidates=1,2,4,8,16`), and results.md states the cost at which each
    /// reaches the target error (docs/bench.md, "Equal error").
    #[arg(long, value_name = "NAME=V1,V2,...")]
    pub knob: Option<String>,
    /// The per-frame luma RMSE the equal-error table reads costs at (default: the first
    /// configuration's at the middle knob value).
    #[arg(long, requires = "knob")]
    pub target_rmse: Option<f64>,
    /// Equal-time mode: each configuration accumulates frames until its measured time
    /// reaches this many milliseconds (still camera only).
    #[arg(long)]
    pub budget_ms: Option<f64>,
    /// Output directory (created).
    #[arg(long)]
    pub out: PathBuf,
    /// Frames rendered before measuring, so history builds up (not timed, not scored).
    #[arg(long, default_value_t = 0)]
    pub warmup: u32,
    /// Samples per pixel of the reference (per frame of an orbit).
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u32,
    /// Seed, `--set`, preset and effect set of every configuration. The bench applies
    /// `jitter=false` first (see docs/bench.md); `--set jitter=true` turns it back on.
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    /// `--env`, `--env-strength`, `--env-rotation` (the reference is keyed by them too).
    #[command(flatten)]
    pub env: EnvArgs,
    /// Reference cache directory (default: $RESTIR_CACHE_DIR, else target/restir-cache).
    #[arg(long)]
    pub cache_dir: Option<PathBuf>,
    /// Equal-time mode stops a configuration after this many frames whatever its time.
    #[arg(long, default_value_t = 10_000)]
    pub max_frames: u32,
    /// Light-count sweep on builtin:many-lights:N for these N (comma-separated): timing,
    /// scene load and BVH build only, no reference.
    #[arg(long, value_name = "N,N,...")]
    pub sweep_lights: Option<String>,
    /// Scene time of an animated scene (`--time`, `--fps`): frame i (warm-up included) is
    /// at T + i/F, and with F > 0 every measured frame has its own reference.
    #[command(flatten)]
    pub time: crate::cli::setup::TimeArgs,
    /// Runs every configuration K times, seeds S..S+K (S = `--seed`): every image figure
    /// is then stated as a mean with a 95 % interval over the seeds, with the accumulated
    /// image's squared bias and variance apart (docs/src/results.md, "Error bars"), and the
    /// lag metrics of a dynamic scene's events are averaged over them. Times, frames and
    /// the strip are seed S's, except `--knob`'s cost curves: their milliseconds are the
    /// mean of every seed's median, each seed's kept beside it, and the equal-time gain over
    /// the first configuration, which rests on every seed's error and median time.
    #[arg(long, default_value_t = 1)]
    pub seeds: u32,
    /// A job of a sweep: write the tables and figures.json only (no plots, strip or
    /// seeds.png) and print nothing.
    #[arg(long)]
    pub quiet: bool,
    /// Print one `bench` command per configuration (each writing OUT/jobs/NAME) and run
    /// nothing: the sweep as independent jobs (docs/src/headless.md).
    #[arg(long, conflicts_with = "merge")]
    pub list_jobs: bool,
    /// Gather the jobs' figures under OUT's jobs folder into its figures.md and figures.csv and run
    /// nothing (the same command line as --list-jobs otherwise).
    #[arg(long)]
    pub merge: bool,
}

/// Everything the writers need besides the results.
pub struct BenchInfo {
    pub scene: String,
    pub size: (u32, u32),
    pub camera: CameraPath,
    pub frames: Option<u32>,
    pub warmup: u32,
    pub budget_ms: Option<f64>,
    pub seed: u32,
    pub device: String,
    pub device_is_cpu: bool,
    /// The spatial radius as set (px at 1080p) and as used at this height (px).
    pub radius: (f32, f32),
    pub jitter: bool,
    pub reference_spp: u32,
    pub reference_noise_luma: Option<f64>,
    pub reference_noise_rgb: Option<f64>,
    pub reference_count: usize,
    /// The `max_bounces` of the references (one set each; configurations are scored
    /// against the set of their own max_bounces).
    pub reference_bounces: Vec<u32>,
    /// Seeds every configuration ran (the image figures over seeds and the lag metrics rest
    /// on them), and where the events came from.
    pub seeds: u32,
    pub event_source: Option<&'static str>,
}

impl BenchInfo {
    /// The sentence that goes next to every time.
    pub fn timing_note(&self) -> &'static str {
        timing_note(self.device_is_cpu)
    }
}

pub fn timing_note(device_is_cpu: bool) -> &'static str {
    if device_is_cpu {
        "CPU adapter (lavapipe): pass times are CPU wall-clock; only ratios within one run are meaningful"
    } else {
        "GPU timestamp queries"
    }
}

pub fn run(args: BenchArgs) -> anyhow::Result<()> {
    let size = parse_size(&args.size)?;
    let camera = CameraPath::parse(&args.camera)?;
    if let Some(t) = args.budget_ms {
        if !(t.is_finite() && t > 0.0) {
            bail!("--budget-ms {t}: expected a positive number of milliseconds");
        }
        if camera != CameraPath::Static {
            bail!("--budget-ms compares running averages, which need --camera static");
        }
        if args.warmup > 0 {
            bail!("--warmup and --budget-ms do not mix: warm-up frames would be free time");
        }
    }
    if args.frames == Some(0) {
        bail!("--frames must be at least 1");
    }
    if args.seeds == 0 {
        bail!("--seeds must be at least 1");
    }
    let base = args.pipeline.settings(BASE_ASSIGNMENTS)?;
    let radius = (base.spatial_radius, base.effective_spatial_radius(size.1));
    let config_list = match &args.knob {
        Some(knob) => configs::expand_knob(&args.configs, knob)?,
        None => args.configs.clone(),
    };
    if let Some(t) = args.target_rmse {
        if !(t.is_finite() && t > 0.0) {
            bail!("--target-rmse {t}: expected a positive error");
        }
    }
    let configs = parse_configs(&config_list, &base)?;
    let effects = args.pipeline.effects()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("--out {}: cannot create", args.out.display()))?;
    if let Some(list) = &args.sweep_lights {
        return sweep::run(&args, list, size, &configs, effects);
    }
    if args.list_jobs {
        return jobs::list(&configs, &args.out);
    }
    if args.merge {
        return jobs::merge(&configs, &args.out);
    }

    let started = Instant::now();
    let timeline = args.time.timeline()?;
    let mut scene = load_scene(&args.scene)?;
    args.env.apply(&mut scene)?;
    let animated = scene.animation.is_some();
    if animated && args.budget_ms.is_some() && timeline.fps > 0.0 {
        bail!("--budget-ms compares running averages of one moment: use --fps 0");
    }
    scene.pose(timeline.time_of(0), ClipChoice::All);
    let gpu = Gpu::new_headless()?;
    // One renderer per configuration, so their frames can interleave (see run_loop.rs).
    let mut renderers = configs
        .iter()
        .map(|_| Renderer::new(gpu.clone(), &scene, size.0, size.1, base.clone()))
        .collect::<Result<Vec<_>, _>>()?;
    eprintln!(
        "{}: loaded and uploaded {} times in {:.1} s",
        args.scene,
        configs.len(),
        started.elapsed().as_secs_f64()
    );
    if let Some(knob) = &args.knob {
        check_knob_points(&mut renderers[0], &configs, knob)?;
    }
    // The references get a renderer of their own: a configuration's frames then depend on
    // its seed alone, never on whether its renderer rendered a reference first (so a sweep
    // split into jobs measures what one process measures; docs/src/headless.md).
    let mut reference_renderer = Renderer::new(gpu.clone(), &scene, size.0, size.1, base.clone())?;
    let mut shot = Shot::of(
        reference_renderer.camera(),
        reference_renderer.scene_bounds().center(),
        camera,
    );
    if animated {
        shot = shot.with_time(timeline);
    }
    let clock = || animated.then(|| AnimatedScene::new(scene.clone()));
    let mut reference_clock = clock();
    let cache = ReferenceCache::new(
        args.cache_dir
            .clone()
            .unwrap_or_else(ReferenceCache::default_dir),
    );
    let measured = args.frames.unwrap_or(1);
    let reference_plan = ReferencePlan {
        cache: &cache,
        scene_spec: &args.scene,
        scene: &scene,
        spp: args.reference_spp,
        jitter: base.jitter,
        effects: effects.clone(),
        max_bounces: 1,
        light_bvh: base.reference_light_bvh,
        light_samples: base.reference_light_samples,
        phases: if base.jitter {
            references::measured_phases(
                args.seeds,
                args.warmup,
                args.budget_ms.is_none().then_some(measured),
            )
        } else {
            Vec::new()
        },
    };
    let ref_sets = ReferenceSets::obtain(
        &mut reference_renderer,
        &reference_plan,
        &shot,
        (args.warmup, measured),
        reference_clock.as_mut(),
        configs.iter().map(|c| c.settings.reference_bounces()),
    )?;
    let refs = ref_sets.primary();
    let plan = RunPlan {
        frames: measured,
        warmup: args.warmup,
        budget: args.budget_ms.map(|ms| Budget {
            ms,
            max_frames: args.max_frames.max(1),
        }),
        shot,
        seed: args.pipeline.seed,
        effects,
    };
    let events = Events::find(&scene, &shot, args.warmup, &refs.images);
    // A moving shot's disoccluded and near-moving pixels, frame by frame (the same for
    // every configuration and seed).
    let masks = if shot.moves() && args.budget_ms.is_none() {
        motion::shot_masks(&scene, &shot, args.warmup, measured, size)
    } else {
        Vec::new()
    };
    // Light events are found on the first configuration's references; each configuration
    // measures its lag against the references of its own max_bounces.
    drop(reference_renderer);
    // Every seed runs every configuration; the image figures are stated over the seeds
    // (seed_figures.rs), the lag metrics averaged over them.
    let mut per_seed: Vec<Vec<ConfigResult>> = vec![Vec::new(); configs.len()];
    for k in 0..args.seeds {
        let plan = RunPlan {
            seed: args.pipeline.seed.wrapping_add(k),
            ..plan.clone()
        };
        if args.seeds > 1 {
            eprintln!("seed {} ({}/{})", plan.seed, k + 1, args.seeds);
        }
        let runs = configs
            .iter()
            .zip(renderers.drain(..))
            .map(|(c, r)| {
                let own = ref_sets.for_bounces(c.settings.reference_bounces());
                let probe = events
                    .as_ref()
                    .map(|e| LagProbe::new(e, &own.images, k == 0));
                let scoring = scoring_for(own, &shot, &masks);
                let run = ConfigRun::start(r, c, &plan, scoring, clock(), probe)?;
                Ok((c.name.clone(), run))
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        let (seed_results, back): (Vec<ConfigResult>, Vec<Renderer>) =
            run_interleaved(runs, &plan)?.into_iter().unzip();
        renderers = back;
        for (all, r) in per_seed.iter_mut().zip(seed_results) {
            all.push(r);
        }
    }
    // Seed S's run carries the times, frames and strip; every seed's goes into the figures.
    let mut results: Vec<ConfigResult> = per_seed.iter().map(|runs| runs[0].clone()).collect();
    for ((r, runs), c) in results.iter_mut().zip(&per_seed).zip(&configs) {
        let own = ref_sets.for_bounces(c.settings.reference_bounces());
        let runs: Vec<seed_figures::SeedRun> = runs
            .iter()
            .map(|r| seed_figures::SeedRun {
                scores: r.scores.as_ref(),
                moments: r.moments.as_ref(),
                frames: r.frames.len(),
            })
            .collect();
        r.over_seeds = seed_figures::of_seeds(&runs, &own.images[0], own.noise_luma_rmse);
    }
    for (r, runs) in results.iter_mut().zip(&per_seed) {
        r.seed_frame_ms = runs.iter().filter_map(|r| r.median_frame_ms()).collect();
    }
    if !shot.moves() && args.seeds > 1 && !args.quiet {
        write_seed_maps(&args.out, &per_seed, &configs, &ref_sets)?;
    }
    let per_seed: Vec<Vec<Vec<events::SeedEvent>>> = per_seed
        .iter()
        .map(|runs| runs.iter().map(|r| r.seed_events.clone()).collect())
        .collect();
    if let Some(e) = &events {
        for (r, seeds) in results.iter_mut().zip(&per_seed) {
            r.lag = events::average(e, seeds);
        }
        event_strip::write(&args.out.join("event_strip.png"), e, &results, refs)?;
    }
    compare_with_nee(&mut results);
    // One reference for every frame: a still camera on a still (or frozen) scene.
    if !shot.moves() && args.budget_ms.is_none() && !args.quiet {
        write_strip(&args.out, &results, &renderers, &ref_sets)?;
    }
    let info = BenchInfo {
        scene: args.scene.clone(),
        size,
        camera,
        frames: args.budget_ms.is_none().then_some(measured),
        warmup: args.warmup,
        budget_ms: args.budget_ms,
        seed: args.pipeline.seed,
        device: format!("{}, {}", gpu.adapter_name(), gpu.driver_info()),
        device_is_cpu: gpu.is_cpu(),
        radius,
        jitter: base.jitter,
        reference_spp: refs.spp,
        reference_noise_luma: max_noise(&ref_sets, |r| r.noise_luma_rmse),
        reference_noise_rgb: max_noise(&ref_sets, |r| r.noise_rgb_rmse),
        reference_count: refs.images.len(),
        reference_bounces: ref_sets.bounces().map(|(b, _)| b).collect(),
        seeds: args.seeds,
        event_source: events.as_ref().map(|e| e.source),
    };
    write_outputs(&args.out, &info, &results, args.quiet)?;
    if let Some(knob) = &args.knob {
        let name = knob
            .split_once('=')
            .map_or(knob.as_str(), |(n, _)| n.trim());
        let note = format!("{} · {}", plots::subtitle(&info), info.timing_note());
        let noise: Vec<f64> = configs
            .iter()
            .map(|c| {
                ref_sets
                    .for_bounces(c.settings.reference_bounces())
                    .noise_luma_rmse
                    .unwrap_or(0.0)
            })
            .collect();
        let section =
            equal_error::write(&args.out, &results, &noise, name, args.target_rmse, &note)?;
        let path = args.out.join("results.md");
        let mut md = std::fs::read_to_string(&path)?;
        md.push_str(&section);
        std::fs::write(&path, md).with_context(|| format!("{}: cannot write", path.display()))?;
        if !args.quiet {
            println!("{section}");
        }
    }
    Ok(())
}

/// Refuses a sweep whose knob the renderer overrides at some point (auto's light BVH
/// draws at most `AUTO_BVH_CANDIDATES`; `nee` draws one candidate): such points render the
/// same frames under different names, and the cost curve would be a flat line that says
/// nothing. Checked on one renderer before anything is rendered.
fn check_knob_points(
    renderer: &mut Renderer,
    configs: &[configs::Config],
    knob: &str,
) -> anyhow::Result<()> {
    let name = knob.split_once('=').map_or(knob, |(n, _)| n).trim();
    for c in configs {
        renderer.set_mode(c.mode);
        renderer.set_settings(c.settings.clone());
        let asked = c.settings.get(name);
        let ran = renderer.effective_settings().get(name);
        if asked != ran {
            let show = |v: Option<restir_render::settings::ParamValue>| {
                v.map_or("-".to_string(), |v| v.to_string())
            };
            bail!(
                "--knob {name}: configuration '{}' asks for {name} = {} but would render with \
                 {} (its mode or `auto` chooses it: auto's light BVH draws at most {} \
                 candidates); name the choice (e.g. --set light_sampler=bvh) or leave the \
                 configuration out of the sweep",
                c.name,
                show(asked),
                show(ran),
                restir_render::effects::AUTO_BVH_CANDIDATES,
            );
        }
    }
    Ok(())
}

/// `seeds.png`: each configuration's bias and spread over the seeds (seed_maps.rs), against
/// the primary reference; configurations of another max_bounces are left out.
fn write_seed_maps(
    out: &std::path::Path,
    per_seed: &[Vec<ConfigResult>],
    configs: &[configs::Config],
    sets: &ReferenceSets,
) -> anyhow::Result<()> {
    let primary = sets.primary();
    let primary_bounces = sets.bounces().next().map_or(1, |(b, _)| b);
    let seed_sets: Vec<seed_maps::SeedSet> = per_seed
        .iter()
        .zip(configs)
        .filter(|(_, c)| c.settings.reference_bounces() == primary_bounces)
        .map(|(runs, c)| seed_maps::SeedSet {
            name: &c.name,
            moments: runs.iter().filter_map(|r| r.moments.as_ref()).collect(),
        })
        .collect();
    seed_maps::write(
        &out.join("seeds.png"),
        &seed_sets,
        &primary.images[0],
        primary.noise_luma_rmse.unwrap_or(0.0),
    )
}

/// The largest estimated own noise among all references.
fn max_noise(sets: &ReferenceSets, of: impl Fn(&References) -> Option<f64>) -> Option<f64> {
    sets.bounces().filter_map(|(_, r)| of(r)).reduce(f64::max)
}

/// `strip.png`: each configuration's last frame, then the reference (one per bounce count).
fn write_strip(
    out: &std::path::Path,
    results: &[ConfigResult],
    renderers: &[Renderer],
    sets: &ReferenceSets,
) -> anyhow::Result<()> {
    let frames: Vec<_> = renderers.iter().map(Renderer::read_radiance).collect();
    let mut panels: Vec<strip::Panel> = results
        .iter()
        .zip(&frames)
        .map(|(r, image)| strip::Panel {
            label: match &r.scores {
                Some(s) => format!("{} · RMSE {:.3}", r.config.name, s.mean_luma_rmse),
                None => r.config.name.clone(),
            },
            image,
        })
        .collect();
    for (bounces, refs) in sets.bounces() {
        let label = match bounces {
            1 => format!("reference · {} spp", refs.spp),
            n => format!("reference · {n} bounces · {} spp", refs.spp),
        };
        panels.push(strip::Panel {
            label,
            image: &refs.images[0],
        });
    }
    strip::write(&out.join("strip.png"), &panels)
}

fn scoring_for<'a>(refs: &'a References, shot: &Shot, masks: &'a [MotionMasks]) -> Scoring<'a> {
    let noise = refs.noise_luma_rmse.unwrap_or(0.0);
    if shot.moves() {
        Scoring::moving(&refs.images, masks, noise)
    } else {
        Scoring::still(&refs.images[0], refs.phases.as_ref(), noise)
    }
}

/// Time and MSE ratios relative to `nee` (when it ran).
fn compare_with_nee(results: &mut [ConfigResult]) {
    let Some(nee) = results.iter().find(|r| r.config.name == "nee").cloned() else {
        return;
    };
    let nee_ms = nee.median_frame_ms();
    let nee_frame_rmse = nee.scores.as_ref().map(|s| s.mean_luma_rmse);
    for r in results.iter_mut() {
        r.time_vs_nee = match (r.median_frame_ms(), nee_ms) {
            (Some(a), Some(b)) if b > 0.0 => Some(a / b),
            _ => None,
        };
        r.frame_mse_vs_nee = mse_ratio(r.scores.as_ref().map(|s| s.mean_luma_rmse), nee_frame_rmse);
        if r.budget.is_some() {
            r.budget_mse_vs_nee =
                mse_ratio(r.final_accumulated_rmse(), nee.final_accumulated_rmse());
        }
    }
}

fn write_outputs(
    out: &std::path::Path,
    info: &BenchInfo,
    results: &[ConfigResult],
    quiet: bool,
) -> anyhow::Result<()> {
    csv::write_results(&out.join("results.csv"), info, results)?;
    let rows: Vec<seed_figures::FigureRow> = results
        .iter()
        .filter_map(|r| {
            Some(seed_figures::FigureRow {
                scene: info.scene.clone(),
                size: info.size,
                camera: info.camera.label(),
                config: r.config.name.clone(),
                description: r.config.description.clone(),
                first_seed: info.seed,
                reference_spp: info.reference_spp,
                figures: r.over_seeds.clone()?,
            })
        })
        .collect();
    seed_figures::write_rows(&out.join(seed_figures::FIGURES_FILE), &rows)?;
    csv::write_frames(&out.join("frames.csv"), results)?;
    if results.iter().any(|r| !r.lag.is_empty()) {
        csv::write_events(&out.join("events.csv"), results)?;
    }
    let md = markdown::results(info, results);
    std::fs::write(out.join("results.md"), &md)
        .with_context(|| format!("{}: cannot write", out.display()))?;
    let written = if quiet {
        Vec::new()
    } else {
        plots::write_all(out, info, results)?
    };
    if !quiet {
        println!("{md}");
    }
    eprintln!(
        "wrote {}/results.csv, frames.csv, results.md, figures.json, {}",
        out.display(),
        written.join(", ")
    );
    Ok(())
}
