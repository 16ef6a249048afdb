//! `render`'s frames: each side (A, and B with `--compare`) on its own renderer and its
//! own posed copy of the scene, both stepped frame by frame, so a recording or a probe
//! sees every frame of both: the camera path (a tour step's camera, `--orbit`,
//! `--cut-at`, a camera on an animated node), scene time, and the per-frame outputs.

use std::time::Instant;

use glam::Vec3;
use restir_render::gpu_scene::SceneUpdateTimes;
use restir_render::stats::FrameReport;
use restir_render::timeline::AnimatedScene;
use restir_render::{Camera, Gpu, Mode, Renderer, Scene, Settings, ViewSettings};

use super::job::Job;
use crate::cli::camera_path::{cut_viewpoint, orbit};

/// One frame's scene update: posing time (ms) and the renderer's update cost.
pub type FrameUpdate = (f64, SceneUpdateTimes);

/// One side in progress.
pub struct SideRun {
    pub renderer: Renderer,
    pub scene: AnimatedScene,
    pub reports: Vec<FrameReport>,
    pub updates: Vec<FrameUpdate>,
    /// Where the orbit and the cut start from.
    start_camera: Camera,
    /// The job set a camera (a camera on an animated node is then not followed).
    fixed_camera: bool,
    center: Vec3,
}

impl SideRun {
    /// A renderer for one side: `mode` and `settings` (A's or B's), the job's size, seed
    /// and effects, and `view` (the debug view and exposure both sides show).
    pub fn new(
        gpu: &Gpu,
        loaded: &Scene,
        job: &Job,
        mode: Mode,
        settings: Settings,
        view: ViewSettings,
    ) -> anyhow::Result<SideRun> {
        let size = job.size;
        let mut scene = AnimatedScene::new(loaded.clone());
        scene.set_clip_choice(job.clip_choice(loaded)?);
        scene.pose_only(job.timeline.time_of(0));
        let mut renderer = Renderer::new(gpu.clone(), scene.scene(), size.0, size.1, settings)?;
        renderer.set_mode(mode);
        renderer.set_seed(job.seed);
        renderer.force_effects(job.effects.clone());
        renderer.set_view(view);
        let start_camera = job.camera.unwrap_or_else(|| renderer.camera());
        let center = renderer.scene_bounds().center();
        Ok(SideRun {
            renderer,
            scene,
            reports: Vec::new(),
            updates: Vec::new(),
            start_camera,
            fixed_camera: job.camera.is_some(),
            center,
        })
    }

    /// Poses the scene for `frame`, moves the camera and renders (waiting for the frame's
    /// report, so no counter readback is ever dropped).
    pub fn render(&mut self, frame: u32, job: &Job) -> anyhow::Result<()> {
        let renderer = &mut self.renderer;
        if frame > 0 {
            let posing = Instant::now();
            let (change, times) = self.scene.set_time(renderer, job.timeline.time_of(frame));
            if change.camera && !self.fixed_camera {
                // A camera on an animated node: follow it (orbit and cuts start from it).
                self.start_camera = self.scene.scene().default_camera();
            }
            if change.any() {
                let total = posing.elapsed().as_secs_f64() * 1e3;
                self.updates
                    .push(((total - times.total_ms()).max(0.0), times));
            }
        }
        let motion = job.motion;
        let mut camera = if motion.orbit != 0.0 {
            orbit(self.start_camera, self.center, motion.orbit * frame as f32)
        } else {
            self.start_camera
        };
        if motion.cut_at.is_some_and(|cut| frame >= cut) {
            camera = cut_viewpoint(camera, renderer.scene_bounds());
            if motion.cut_at == Some(frame) {
                renderer.request_cut();
            }
        }
        renderer.set_camera(camera);
        renderer.render_frame()?;
        self.reports.extend(renderer.collect_reports(true));
        Ok(())
    }
}

/// Progress on stderr, at most once a second.
pub struct Progress {
    started: Instant,
    last: Instant,
    frames: u32,
    printed: bool,
}

impl Progress {
    pub fn new(frames: u32) -> Progress {
        Progress {
            started: Instant::now(),
            last: Instant::now(),
            frames,
            printed: false,
        }
    }

    pub fn frame_done(&mut self, frame: u32) {
        let last = frame + 1 == self.frames && self.frames > 1;
        if self.last.elapsed().as_secs_f32() > 1.0 || last {
            self.last = Instant::now();
            self.printed = true;
            eprint!(
                "\rframe {}/{} ({:.1} s)",
                frame + 1,
                self.frames,
                self.started.elapsed().as_secs_f32()
            );
        }
    }

    pub fn finish(&self) {
        if self.printed {
            eprintln!();
        }
    }
}
