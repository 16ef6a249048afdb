//! `render`: frames headless, to EXR (linear, untonemapped) or PNG (display pass: tonemapped
//! image or a debug view), with `--stats` JSON.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, bail};
use clap::Args;
use restir_render::gpu_scene::SceneUpdateTimes;
use restir_render::stats::FrameReport;
use restir_render::timeline::{AnimatedScene, Timeline};
use restir_render::view::auto_exposure_ev;
use restir_render::{DebugView, Gpu, LinearImage, Mode, Renderer, Settings, load_scene};

use super::camera_path::{cut_viewpoint, orbit};
use super::render_reference::{check_comparable, reference_of};
use super::render_stats::{CompareStats, Side, scene_time_stats, side_stats};
use super::setup::{PipelineArgs, TimeArgs, parse_size};
use crate::compare::{CompareTarget, divider_column, split_columns};

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
    /// `--env`, `--env-strength`, `--env-rotation`.
    #[command(flatten)]
    pub env: super::environment::EnvArgs,
    /// Output image: .exr (linear radiance) or .png (what the display shows).
    #[arg(long)]
    pub out: PathBuf,
    /// Write statistics as JSON here.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// final | source | m | rejection | w | normals | albedo | depth | motion | error | bias | ...
    /// (PNG only; see README "Debug views").
    #[arg(long, default_value = "final")]
    pub debug_view: String,
    /// Samples per pixel of the reference the error and bias views compare with.
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u32,
    /// Where that reference is cached (default `$RESTIR_CACHE_DIR`, else target/restir-cache).
    #[arg(long)]
    pub cache_dir: Option<PathBuf>,
    /// Orbit the camera about the scene centre by this many degrees per frame.
    #[arg(long, default_value_t = 0.0)]
    pub orbit: f32,
    /// Jump the camera to a distant viewpoint at this frame (a camera cut).
    #[arg(long)]
    pub cut_at: Option<u32>,
    /// Exposure in EV for PNG output, or `auto` (log-average luminance to middle grey).
    #[arg(long, default_value = "auto")]
    pub exposure: String,
    /// Split screen: this configuration left, B right of the middle. B is a mode
    /// (reference, nee, ris, restir: these settings in that mode) or a preset .toml file.
    #[arg(long, value_name = "B")]
    pub compare: Option<String>,
    /// Scene time (`--time`, `--fps`).
    #[command(flatten)]
    pub time: TimeArgs,
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
    let compare = args
        .compare
        .as_deref()
        .map(|spec| CompareTarget::parse(spec, &settings))
        .transpose()?;
    if view == DebugView::Difference && compare.is_none() {
        bail!("--debug-view difference shows |A − B|: it needs --compare B");
    }

    let timeline = args.time.timeline()?;
    let mut loaded = load_scene(&args.scene)?;
    args.env.apply(&mut loaded)?;
    check_comparable(view, &args, loaded.animation.is_some())?;
    let gpu = Gpu::new_headless()?;
    // Each side poses its own copy of the scene along the same timeline.
    let side = |mode: Mode, settings: Settings| -> anyhow::Result<Side> {
        let mut scene = AnimatedScene::new(loaded.clone());
        scene.pose_only(timeline.time_of(0));
        let mut renderer = Renderer::new(gpu.clone(), scene.scene(), size.0, size.1, settings)?;
        renderer.set_mode(mode);
        renderer.set_seed(args.pipeline.seed);
        renderer.force_effects(effects.clone());
        let (reports, updates) = render_frames(&mut renderer, &mut scene, timeline, &args)?;
        let scene_time = scene
            .is_animated()
            .then(|| scene_time_stats(timeline, &args, &updates, &renderer, scene.scene()));
        let image = if args.accumulate {
            renderer.read_accumulated()
        } else {
            renderer.read_radiance()
        };
        Ok(Side {
            renderer,
            reports,
            image,
            scene_time,
        })
    };
    let mut left = side(mode, settings)?;
    let mut right = compare
        .as_ref()
        .map(|b| side(b.mode, b.settings.clone()))
        .transpose()?;
    let divider = divider_column(size.0, 0.5);

    // The image of one side, or the split of both.
    let image = match &right {
        None => left.image.clone(),
        Some(r) => LinearImage {
            width: size.0,
            height: size.1,
            pixels: split_columns(&left.image.pixels, &r.image.pixels, size.0, divider),
        },
    };
    match format {
        Format::Exr => image.save_exr(&args.out)?,
        Format::Png => {
            // Both sides use the exposure of the split image, so equal radiance looks equal.
            let exposure_ev = exposure_ev(&image, &args.exposure)?;
            if view.needs_reference() {
                let (reference, noise) =
                    reference_of(&left.renderer, &gpu, &loaded, effects.as_ref(), &args)?;
                left.renderer.set_reference_image(&reference, noise)?;
                if let Some(r) = &mut right {
                    r.renderer.set_reference_image(&reference, noise)?;
                }
            }
            let rgba = match (&mut right, view) {
                // |A − B| over the whole image, on A's display pass.
                (Some(r), DebugView::Difference) => {
                    left.renderer.set_comparison_image(&r.image)?;
                    display_rgba8(&mut left.renderer, view, exposure_ev, &args)?
                }
                (Some(r), _) => {
                    let a = display_rgba8(&mut left.renderer, view, exposure_ev, &args)?;
                    let b = display_rgba8(&mut r.renderer, view, exposure_ev, &args)?;
                    split_columns(&a, &b, size.0 * 4, divider * 4)
                }
                (None, _) => display_rgba8(&mut left.renderer, view, exposure_ev, &args)?,
            };
            restir_render::image::save_png_rgba8(&args.out, size.0, size.1, &rgba)?;
        }
    }
    if let Some(path) = &args.stats {
        let mut doc = side_stats(&left);
        // The document's own count is the written image's (the split with --compare).
        doc.summary.nan_inf_pixels = image.non_finite_count() as u64;
        if let (Some(r), Some(b)) = (&right, &compare) {
            doc.compare = Some(Box::new(CompareStats {
                divider_column: divider,
                left: side_stats(&left),
                right_config: b.label.clone(),
                right: side_stats(r),
            }));
        }
        let text = serde_json::to_string_pretty(&doc)?;
        std::fs::write(path, text)
            .with_context(|| format!("{}: cannot write stats", path.display()))?;
    }
    Ok(())
}

/// One frame's scene update: posing time (ms) and the renderer's update cost.
pub(super) type FrameUpdate = (f64, SceneUpdateTimes);

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

/// `--exposure`: a number of stops, or `auto` from the image.
fn exposure_ev(image: &LinearImage, text: &str) -> anyhow::Result<f32> {
    if text == "auto" {
        return Ok(auto_exposure_ev(image));
    }
    text.parse::<f32>()
        .ok()
        .filter(|x| x.is_finite())
        .with_context(|| format!("--exposure '{text}': expected a number of stops or auto"))
}

/// What the display pass shows for the renderer's last frame (or its average).
fn display_rgba8(
    renderer: &mut Renderer,
    view: DebugView,
    exposure_ev: f32,
    args: &RenderArgs,
) -> anyhow::Result<Vec<u8>> {
    let mut settings = *renderer.view();
    settings.view = view;
    settings.exposure_ev = exposure_ev;
    settings.accumulate = args.accumulate;
    renderer.set_view(settings);
    renderer.redisplay()?;
    Ok(renderer.read_display_rgba8())
}
