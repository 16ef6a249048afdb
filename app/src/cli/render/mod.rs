//! `render`: frames headless, to EXR (linear, untonemapped) or PNG (display pass: tonemapped
//! image or a debug view), with `--stats` JSON; every frame to a folder or a GIF
//! (`--out-sequence`, `--gif`), one pixel's history (`--probe`), or one step of a tour
//! (`--tour FILE --tour-step K`).
//!
//! - `args.rs`: the flags; `job.rs`: the flags (and a tour step) resolved and checked, the
//!   only reader of the flags;
//! - `render_loop.rs`: each side's renderer, stepped frame by frame;
//! - `display.rs`: the images written; `reference.rs`: the reference the error and bias
//!   views compare with; `stats.rs`: the `--stats` document.
//!
//! `run` below is the command in order: resolve, load, render every frame (recording and
//! probing as it goes), then write the image and the statistics.

mod args;
mod display;
mod job;
mod reference;
mod render_loop;
mod stats;

use restir_render::load_phases::{LoadEvent, phase_line};
use restir_render::view::auto_exposure_ev;
use restir_render::{Gpu, ViewSettings, load_scene_watched};

use crate::compare::divider_column;
use crate::probe::{self, ProbeSample};
use crate::recording::{RecordedFrame, Recorder};

pub use args::RenderArgs;
use display::{display_rgba8, shown_image};
use job::{Format, Job};
use reference::{check_comparable, reference_of};
use render_loop::{Progress, SideRun};

pub fn run(args: RenderArgs) -> anyhow::Result<()> {
    let job = Job::resolve(&args)?;
    let (size, view) = (job.size, job.view);
    let outputs = &job.outputs;
    let mut recorder = Recorder::start(&outputs.recording)?;

    // The phases print as they finish (the pipelines' after the first frame).
    let print_phase = |e: LoadEvent| {
        if let LoadEvent::Finished(p) = e {
            eprintln!("{}", phase_line(p));
        }
    };
    let mut loaded = load_scene_watched(&job.scene, &print_phase)?;
    job.env.apply(&mut loaded)?;
    check_comparable(&job, loaded.animation.is_some())?;
    let gpu = Gpu::new_headless()?;
    let mut view_settings = ViewSettings {
        view,
        accumulate: job.accumulate,
        ..ViewSettings::default()
    };
    let fixed_exposure = job.fixed_exposure()?;
    view_settings.exposure_ev = fixed_exposure.unwrap_or(0.0);
    let side = |mode, settings| SideRun::new(&gpu, &loaded, &job, mode, settings, view_settings);
    let mut left = side(job.mode, job.settings.clone())?;
    let mut right = job
        .compare
        .as_ref()
        .map(|b| side(b.mode, b.settings.clone()))
        .transpose()?;
    let probe = outputs.probe;
    if let Some(p) = probe {
        left.renderer.set_inspected_pixel(Some(p));
    }
    let divider = divider_column(size.0, 0.5);
    let mut exposure = fixed_exposure;
    let mut history = Vec::new();
    let mut progress = Progress::new(job.frames);
    let loader_phases = loaded.load_phases.phases.len();
    for p in &left.renderer.scene_info().load.phases[loader_phases..] {
        eprintln!("{}", phase_line(p));
    }
    for frame in 0..job.frames {
        left.render(frame, &job)?;
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
            r.render(frame, &job)?;
        }
        if let Some(p) = probe {
            history.extend(probe_sample(&left, &job, frame, p));
        }
        if recorder.wants_display() || recorder.wants_linear() {
            let image = shown_image(&left, right.as_ref(), divider, job.accumulate);
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
    if let (Some(p), Some(path)) = (probe, &outputs.probe_out) {
        probe::write_csv(path, p, &history)?;
    }

    // The image of one side, or the split of both.
    let image = shown_image(&left, right.as_ref(), divider, job.accumulate);
    if let Some((out, format)) = &outputs.image {
        match format {
            Format::Exr => image.save_exr(out)?,
            Format::Png => {
                // Both sides use the exposure of the split image, so equal radiance looks equal.
                let ev = exposure.unwrap_or_else(|| auto_exposure_ev(&image));
                if view.needs_reference() {
                    let (reference, noise) = reference_of(&left, &gpu, &job)?;
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
    if let Some(path) = &outputs.stats {
        stats::write(path, &job, left, right, &image, divider)?;
    }
    Ok(())
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
