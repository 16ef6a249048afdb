//! `render`: frames headless, to EXR (linear, untonemapped) or PNG (display pass: tonemapped
//! image or a debug view), with `--stats` JSON.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use clap::Args;
use restir_render::stats::{FrameReport, StatsSummary};
use restir_render::view::auto_exposure_ev;
use restir_render::{DebugView, LinearImage, Mode, Renderer};
use serde::Serialize;

use restir_render::gpu_scene::SceneUpdateTimes;
use restir_render::timeline::{AnimatedScene, Timeline};

use super::camera_path::{cut_viewpoint, orbit};
use super::setup::{PipelineArgs, TimeArgs, build_renderer_for, parse_size};

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A .gltf/.glb file or a built-in scene (`builtin:cornell`, see `scenes`).
    #[arg(long)]
    pub scene: String,
    /// Output size, WxH.
    #[arg(long, default_value = "640x360")]
    pub size: String,
    /// Frames to render.
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// reference | nee | ris | restir
    #[arg(long, default_value = "restir")]
    pub mode: String,
    /// Samples per pixel per frame of the reference mode.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Write the average of all frames instead of the last one.
    #[arg(long)]
    pub accumulate: bool,
    /// Seed, `--set`, preset and effect set.
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    /// Output image: .exr (linear radiance) or .png (what the display shows).
    #[arg(long)]
    pub out: PathBuf,
    /// Write statistics as JSON here.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// final | source | m | rejection | w | normals | albedo | depth | motion | age (PNG only).
    #[arg(long, default_value = "final")]
    pub debug_view: String,
    /// Orbit the camera about the scene centre by this many degrees per frame.
    #[arg(long, default_value_t = 0.0)]
    pub orbit: f32,
    /// Jump the camera to a distant viewpoint at this frame (a camera cut).
    #[arg(long)]
    pub cut_at: Option<u32>,
    /// Exposure in EV for PNG output, or `auto` (log-average luminance to middle grey).
    #[arg(long, default_value = "auto")]
    pub exposure: String,
    /// Scene time (`--time`, `--fps`).
    #[command(flatten)]
    pub time: TimeArgs,
}

/// Scene time and the per-frame update cost of an animated scene (`--stats`).
#[derive(Serialize)]
struct SceneTimeStats {
    /// Scene time of the first and the last frame, seconds.
    first_time: f32,
    last_time: f32,
    fps: f32,
    /// Median CPU cost per frame of the scene update (posing, BVH refit, light table,
    /// upload), over frames that changed something.
    median_pose_ms: f64,
    median_bvh_ms: f64,
    median_lights_ms: f64,
    median_upload_ms: f64,
    updated_frames: usize,
    /// Refit against rebuild at the last frame: SAH cost of the refitted tree, of a tree
    /// built from scratch over the same positions, and that build's time.
    bvh_refit_sah_cost: f64,
    bvh_rebuilt_sah_cost: f64,
    bvh_rebuild_ms: f64,
}

/// The `--stats` JSON document.
#[derive(Serialize)]
struct StatsFile<'a> {
    scene: &'a restir_render::gpu_scene::SceneInfo,
    adapter: String,
    /// "lavapipe timings are CPU timings": true when the adapter is a CPU implementation.
    adapter_is_cpu: bool,
    mode: Mode,
    size: [u32; 2],
    effects: String,
    effect_reasons: Vec<(String, String)>,
    passes: Vec<&'static str>,
    settings: std::collections::BTreeMap<String, String>,
    mean_luminance: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    scene_time: Option<SceneTimeStats>,
    #[serde(flatten)]
    summary: StatsSummary,
}

pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    let mode = Mode::from_name(&args.mode).with_context(|| {
        format!(
            "--mode '{}': expected reference, nee, ris or restir",
            args.mode
        )
    })?;
    let size = parse_size(&args.size)?;
    let view = DebugView::from_name(&args.debug_view).with_context(|| {
        let names: Vec<_> = DebugView::ALL.iter().map(|v| v.name()).collect();
        format!(
            "--debug-view '{}': expected one of {}",
            args.debug_view,
            names.join(", ")
        )
    })?;
    let format = output_format(&args.out)?;
    if view != DebugView::Final && format == Format::Exr {
        bail!(
            "--debug-view {} writes colours: use a .png --out",
            view.name()
        );
    }
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    let mut settings = args.pipeline.settings(&[])?;
    if let Some(spp) = args.spp {
        settings
            .set_from_str("reference_spp", &spp.to_string())
            .map_err(|e| anyhow::anyhow!("--spp: {e}"))?;
    }
    let effects = args.pipeline.effects()?;

    let timeline = args.time.timeline()?;
    let mut scene = AnimatedScene::new(restir_render::load_scene(&args.scene)?);
    scene.pose_only(timeline.time_of(0));
    let mut renderer = build_renderer_for(scene.scene(), size, settings)?;
    renderer.set_mode(mode);
    renderer.set_seed(args.pipeline.seed);
    renderer.force_effects(effects);
    let (reports, updates) = render_frames(&mut renderer, &mut scene, timeline, &args)?;
    let scene_time = scene
        .is_animated()
        .then(|| scene_time_stats(timeline, &args, &updates, &renderer, scene.scene()));

    let image = if args.accumulate {
        renderer.read_accumulated()
    } else {
        renderer.read_radiance()
    };
    let nan_inf = image.non_finite_count() as u64;
    match format {
        Format::Exr => image.save_exr(&args.out)?,
        Format::Png => write_png(&mut renderer, &image, view, &args)?,
    }
    if let Some(path) = &args.stats {
        write_stats(path, &renderer, &reports, nan_inf, &image, scene_time)?;
    }
    Ok(())
}

/// One frame's scene update: posing time (ms) and the renderer's update cost.
type FrameUpdate = (f64, SceneUpdateTimes);

fn render_frames(
    renderer: &mut Renderer,
    scene: &mut AnimatedScene,
    timeline: Timeline,
    args: &RenderArgs,
) -> anyhow::Result<(Vec<FrameReport>, Vec<FrameUpdate>)> {
    let mut start_camera = renderer.camera();
    let center = renderer.scene_bounds().center();
    let mut camera = start_camera;
    let mut reports = Vec::with_capacity(args.frames as usize);
    let mut updates = Vec::new();
    let started = Instant::now();
    let mut last_progress = Instant::now();
    for frame in 0..args.frames {
        if frame > 0 {
            let posing = Instant::now();
            let (change, times) = scene.set_time(renderer, timeline.time_of(frame));
            if change.camera {
                // A camera on an animated node: follow it (orbit and cuts start from it).
                start_camera = scene.scene().default_camera();
                camera = start_camera;
            }
            if change.any() {
                let total = posing.elapsed().as_secs_f64() * 1e3;
                updates.push(((total - times.total_ms()).max(0.0), times));
            }
        }
        if args.orbit != 0.0 {
            camera = orbit(start_camera, center, args.orbit * frame as f32);
        }
        if args.cut_at == Some(frame) {
            camera = cut_viewpoint(camera, renderer.scene_bounds());
            renderer.request_cut();
        }
        renderer.set_camera(camera);
        renderer.render_frame()?;
        // Headless: wait for each frame so no counter readback is ever dropped.
        reports.extend(renderer.collect_reports(true));
        if last_progress.elapsed().as_secs_f32() > 1.0
            || frame + 1 == args.frames && args.frames > 1
        {
            last_progress = Instant::now();
            eprint!(
                "\rframe {}/{} ({:.1} s)",
                frame + 1,
                args.frames,
                started.elapsed().as_secs_f32()
            );
        }
    }
    if args.frames > 1 && started.elapsed().as_secs_f32() > 1.0 {
        eprintln!();
    }
    Ok((reports, updates))
}

fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn scene_time_stats(
    timeline: Timeline,
    args: &RenderArgs,
    updates: &[FrameUpdate],
    renderer: &Renderer,
    scene: &restir_render::Scene,
) -> SceneTimeStats {
    let of = |f: fn(&FrameUpdate) -> f64| median(updates.iter().map(f).collect());
    let positions: Vec<_> = (0..scene.triangles.len())
        .map(|t| scene.triangle_positions(t))
        .collect();
    let build = Instant::now();
    let rebuilt = restir_render::scene::bvh::Bvh::build(&positions);
    let bvh_rebuild_ms = build.elapsed().as_secs_f64() * 1e3;
    SceneTimeStats {
        first_time: timeline.time_of(0),
        last_time: timeline.time_of(args.frames - 1),
        fps: timeline.fps,
        median_pose_ms: of(|u| u.0),
        median_bvh_ms: of(|u| u.1.bvh_ms),
        median_lights_ms: of(|u| u.1.lights_ms),
        median_upload_ms: of(|u| u.1.upload_ms),
        updated_frames: updates.len(),
        bvh_refit_sah_cost: renderer.bvh_sah_cost(),
        bvh_rebuilt_sah_cost: rebuilt.sah_cost(),
        bvh_rebuild_ms,
    }
}

#[derive(PartialEq)]
enum Format {
    Exr,
    Png,
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

fn write_png(
    renderer: &mut Renderer,
    image: &LinearImage,
    view: DebugView,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    let exposure_ev = if args.exposure == "auto" {
        auto_exposure_ev(image)
    } else {
        args.exposure
            .parse::<f32>()
            .ok()
            .filter(|x| x.is_finite())
            .with_context(|| {
                format!(
                    "--exposure '{}': expected a number of stops or auto",
                    args.exposure
                )
            })?
    };
    let mut settings = *renderer.view();
    settings.view = view;
    settings.exposure_ev = exposure_ev;
    settings.accumulate = args.accumulate;
    renderer.set_view(settings);
    renderer.redisplay()?;
    let (w, h) = renderer.size();
    restir_render::image::save_png_rgba8(&args.out, w, h, &renderer.read_display_rgba8())
}

fn write_stats(
    path: &Path,
    renderer: &Renderer,
    reports: &[FrameReport],
    nan_inf: u64,
    image: &LinearImage,
    scene_time: Option<SceneTimeStats>,
) -> anyhow::Result<()> {
    let effects = renderer
        .last_effects()
        .cloned()
        .unwrap_or_else(restir_render::effects::EffectSet::all);
    let settings = renderer.effective_settings();
    let doc = StatsFile {
        scene: renderer.scene_info(),
        adapter: renderer.gpu().adapter_name(),
        adapter_is_cpu: renderer.gpu().is_cpu(),
        mode: renderer.mode(),
        size: [renderer.size().0, renderer.size().1],
        effects: effects.to_string(),
        effect_reasons: effects
            .reasons
            .iter()
            .map(|(e, r)| (e.name().to_string(), r.clone()))
            .collect(),
        passes: renderer.last_passes().to_vec(),
        settings: restir_render::settings::PARAMS
            .iter()
            .map(|p| {
                (
                    p.name.to_string(),
                    settings
                        .get(p.name)
                        .map(|v| v.to_string())
                        .unwrap_or_default(),
                )
            })
            .collect(),
        mean_luminance: image.mean_luminance(),
        scene_time,
        summary: StatsSummary::from_reports(reports, nan_inf),
    };
    let text = serde_json::to_string_pretty(&doc)?;
    std::fs::write(path, text).with_context(|| format!("{}: cannot write stats", path.display()))
}
