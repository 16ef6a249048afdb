//! `render`: frames headless, to EXR (linear, untonemapped) or PNG (display pass: tonemapped
//! image or a debug view), with `--stats` JSON; every frame to a folder or a GIF
//! (`--out-sequence`, `--gif`), one pixel's history (`--probe`), or one step of a tour
//! (`--tour FILE --tour-step K`).

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use clap::Args;
use restir_render::gpu_scene::SceneUpdateTimes;
use restir_render::load_phases::{LoadEvent, phase_line};
use restir_render::view::auto_exposure_ev;
use restir_render::{DebugView, Gpu, LinearImage, Renderer, ViewSettings, load_scene_watched};

use super::render_job::Job;
use super::render_loop::{Progress, SideRun};
use super::render_reference::{check_comparable, reference_of};
use super::render_stats::{CompareStats, Side, scene_time_stats, side_stats};
use super::setup::{PipelineArgs, TimeArgs, parse_size};
use crate::compare::{divider_column, split_columns};
use crate::probe::{self, ProbeSample};
use crate::recording::{RecordedFrame, Recorder, RecordingPlan, SequenceFormat};

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A .gltf/.glb file or a built-in scene (`builtin:cornell`, see `scenes`); required
    /// unless `--tour` names it.
    #[arg(long)]
    pub scene: Option<String>,
    /// Output size, WxH.
    #[arg(long, default_value = "640x360")]
    pub size: String,
    /// Frames to render.
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// reference | nee | ris | restir [default: restir].
    #[arg(long)]
    pub mode: Option<String>,
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
    pub out: Option<PathBuf>,
    /// Write statistics as JSON here.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// final | source | m | rejection | w | ... | boiling | survivor-change (PNG only; see
    /// README "Debug views") [default: final].
    #[arg(long)]
    pub debug_view: Option<String>,
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
    /// Exposure in EV for PNG output, or `auto` (log-average luminance to middle grey; for
    /// a recording, the first frame's) [default: auto].
    #[arg(long)]
    pub exposure: Option<String>,
    /// Split screen: this configuration left, B right of the middle. B is a mode
    /// (reference, nee, ris, restir: these settings in that mode) or a preset .toml file.
    #[arg(long, value_name = "B")]
    pub compare: Option<String>,
    /// Scene time (`--time`, `--fps`).
    #[command(flatten)]
    pub time: TimeArgs,
    /// Write every frame into this folder: frame-00000.png, ... (see --sequence-format).
    #[arg(long, value_name = "DIR")]
    pub out_sequence: Option<PathBuf>,
    /// png (what the display shows) or exr (linear radiance) for --out-sequence.
    #[arg(long, default_value = "png")]
    pub sequence_format: String,
    /// Write every frame as an animated GIF (what the display shows, at the scene's fps).
    #[arg(long, value_name = "FILE.gif")]
    pub gif: Option<PathBuf>,
    /// Record this pixel's history (X,Y from the top left) into --probe-out.
    #[arg(long, value_name = "X,Y", requires = "probe_out")]
    pub probe: Option<String>,
    /// The pixel history as CSV: one row per frame (README "Pixel history").
    #[arg(long, value_name = "FILE.csv", requires = "probe")]
    pub probe_out: Option<PathBuf>,
    /// Render a step of a guided tour (README "Guided tours"): its scene, camera, time,
    /// mode, parameters, B, view and exposure; flags given here win over the step's.
    #[arg(long, value_name = "FILE.toml")]
    pub tour: Option<PathBuf>,
    /// The tour's step, from 1.
    #[arg(long, default_value_t = 1, requires = "tour")]
    pub tour_step: usize,
}

pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    let job = Job::resolve(&args)?;
    let size = parse_size(&args.size)?;
    let view = job.view;
    let format = args.out.as_deref().map(output_format).transpose()?;
    if view != DebugView::Final && format == Some(Format::Exr) {
        bail!(
            "--debug-view {} writes colours: use a .png --out",
            view.name()
        );
    }
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
    let probe = args
        .probe
        .as_deref()
        .map(|p| probe::parse_pixel(p, size))
        .transpose()?;
    let effects = args.pipeline.effects()?;
    if view == DebugView::Difference && job.compare.is_none() {
        bail!("--debug-view difference shows |A − B|: it needs --compare B");
    }
    let plan = RecordingPlan {
        sequence: args
            .out_sequence
            .clone()
            .map(|dir| anyhow::Ok((dir, SequenceFormat::parse(&args.sequence_format)?)))
            .transpose()?,
        gif: args.gif.clone(),
        fps: job.timeline.fps,
    };
    let mut recorder = Recorder::start(&plan)?;

    // The phases print as they finish (the pipelines' after the first frame).
    let print_phase = |e: LoadEvent| {
        if let LoadEvent::Finished(p) = e {
            eprintln!("{}", phase_line(p));
        }
    };
    let mut loaded = load_scene_watched(&job.scene, &print_phase)?;
    job.env.apply(&mut loaded)?;
    check_comparable(&job, &args, loaded.animation.is_some())?;
    let gpu = Gpu::new_headless()?;
    let mut view_settings = ViewSettings {
        view,
        accumulate: args.accumulate,
        ..ViewSettings::default()
    };
    let fixed_exposure = match job.exposure.as_str() {
        "auto" => None,
        text => Some(parse_exposure(text)?),
    };
    view_settings.exposure_ev = fixed_exposure.unwrap_or(0.0);
    let side = |mode, settings| {
        SideRun::new(
            &gpu,
            &loaded,
            &job,
            mode,
            settings,
            size,
            args.pipeline.seed,
            effects.clone(),
            view_settings,
        )
    };
    let mut left = side(job.mode, job.settings.clone())?;
    let mut right = job
        .compare
        .as_ref()
        .map(|b| side(b.mode, b.settings.clone()))
        .transpose()?;
    if let Some(p) = probe {
        left.renderer.set_inspected_pixel(Some(p));
    }
    let divider = divider_column(size.0, 0.5);
    let mut exposure = fixed_exposure;
    let mut history = Vec::new();
    let mut progress = Progress::new(args.frames);
    let loader_phases = loaded.load_phases.phases.len();
    for p in &left.renderer.scene_info().load.phases[loader_phases..] {
        eprintln!("{}", phase_line(p));
    }
    for frame in 0..args.frames {
        left.render(frame, &job, &args)?;
        if frame == 0 {
            let phases = left.renderer.load_phases();
            for p in ["pipelines", "first frame"]
                .iter()
                .filter_map(|n| phases.get(n))
            {
                eprintln!("{}", phase_line(p));
            }
        }
        if let Some(r) = &mut right {
            r.render(frame, &job, &args)?;
        }
        if let Some(p) = probe {
            history.extend(probe_sample(&left, &job, frame, p));
        }
        if recorder.wants_display() || recorder.wants_linear() {
            let image = shown_image(&left, right.as_ref(), divider, args.accumulate);
            let ev = *exposure.get_or_insert_with(|| auto_exposure_ev(&image));
            let rgba = if recorder.wants_display() {
                Some(display_rgba8(&mut left, right.as_mut(), view, ev, divider)?)
            } else {
                None
            };
            recorder.push(&RecordedFrame {
                width: size.0,
                height: size.1,
                rgba: rgba.as_deref(),
                linear: Some(&image),
            })?;
        }
        progress.frame_done(frame);
    }
    progress.finish();
    if recorder.frames() > 0 {
        eprintln!("wrote {}", recorder.finish()?);
    }
    if let (Some(p), Some(path)) = (probe, &args.probe_out) {
        probe::write_csv(path, p, &history)?;
    }

    // The image of one side, or the split of both.
    let image = shown_image(&left, right.as_ref(), divider, args.accumulate);
    if let (Some(out), Some(format)) = (&args.out, format) {
        match format {
            Format::Exr => image.save_exr(out)?,
            Format::Png => {
                // Both sides use the exposure of the split image, so equal radiance looks equal.
                let ev = exposure.unwrap_or_else(|| auto_exposure_ev(&image));
                if view.needs_reference() {
                    let (reference, noise) =
                        reference_of(&left, &gpu, &job, effects.as_ref(), &args)?;
                    left.renderer.set_reference_image(&reference, noise)?;
                    if let Some(r) = &mut right {
                        r.renderer.set_reference_image(&reference, noise)?;
                    }
                }
                let rgba = display_rgba8(&mut left, right.as_mut(), view, ev, divider)?;
                restir_render::image::save_png_rgba8(out, size.0, size.1, &rgba)?;
            }
        }
    }
    if let Some(path) = &args.stats {
        let side_of = |run: SideRun| Side {
            image: read_image(&run.renderer, args.accumulate),
            scene_time: run.scene.is_animated().then(|| {
                scene_time_stats(
                    job.timeline,
                    &args,
                    &run.updates,
                    &run.renderer,
                    run.scene.scene(),
                )
            }),
            renderer: run.renderer,
            reports: run.reports,
        };
        let left = side_of(left);
        let right = right.map(side_of);
        let mut doc = side_stats(&left);
        // The document's own count is the written image's (the split with --compare).
        doc.summary.nan_inf_pixels = image.non_finite_count() as u64;
        if let (Some(r), Some(b)) = (&right, &job.compare) {
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

/// The linear image a side shows: the last frame, or the average with `--accumulate`.
fn read_image(renderer: &Renderer, accumulate: bool) -> LinearImage {
    if accumulate {
        renderer.read_accumulated()
    } else {
        renderer.read_radiance()
    }
}

/// What is written: one side's image, or A left of the middle and B right of it.
fn shown_image(
    left: &SideRun,
    right: Option<&SideRun>,
    divider: u32,
    accumulate: bool,
) -> LinearImage {
    let a = read_image(&left.renderer, accumulate);
    match right {
        None => a,
        Some(r) => LinearImage {
            width: a.width,
            height: a.height,
            pixels: split_columns(
                &a.pixels,
                &read_image(&r.renderer, accumulate).pixels,
                a.width,
                divider,
            ),
        },
    }
}

/// The probed pixel's row of the frame just rendered (its inspection came with the
/// report; scene time and light events for an animated scene).
fn probe_sample(left: &SideRun, job: &Job, frame: u32, pixel: (u32, u32)) -> Option<ProbeSample> {
    let inspection = left.reports.last()?.inspection.as_ref()?;
    let animation = left.scene.scene().animation.as_ref();
    let time = animation.map(|_| job.timeline.time_of(frame));
    let event = frame > 0
        && probe::event_between(
            animation,
            job.timeline.time_of(frame - 1),
            job.timeline.time_of(frame),
        );
    debug_assert_eq!(inspection.pixel, pixel);
    Some(ProbeSample::from_inspection(inspection, time, None, event))
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

/// `--exposure`: a number of stops.
fn parse_exposure(text: &str) -> anyhow::Result<f32> {
    text.parse::<f32>()
        .ok()
        .filter(|x| x.is_finite())
        .with_context(|| format!("--exposure '{text}': expected a number of stops or auto"))
}

/// What the display shows for the last frame at exposure `ev`: one side, the split of
/// both, or |A − B| over the whole image.
fn display_rgba8(
    left: &mut SideRun,
    right: Option<&mut SideRun>,
    view: DebugView,
    ev: f32,
    divider: u32,
) -> anyhow::Result<Vec<u8>> {
    let (w, _) = left.renderer.size();
    match (right, view) {
        (Some(r), DebugView::Difference) => {
            let b = r.renderer.read_radiance();
            left.renderer.set_comparison_image(&b)?;
            redisplay(&mut left.renderer, ev)
        }
        (Some(r), _) => {
            let a = redisplay(&mut left.renderer, ev)?;
            let b = redisplay(&mut r.renderer, ev)?;
            Ok(split_columns(&a, &b, w * 4, divider * 4))
        }
        (None, _) => redisplay(&mut left.renderer, ev),
    }
}

/// The last frame's display pass again at exposure `ev` (the view is set once, before the
/// first frame: the boiling views keep their window only while they are shown).
fn redisplay(renderer: &mut Renderer, ev: f32) -> anyhow::Result<Vec<u8>> {
    let mut settings = *renderer.view();
    settings.exposure_ev = ev;
    renderer.set_view(settings);
    renderer.redisplay()?;
    Ok(renderer.read_display_rgba8())
}
