//! One window's viewer and its frame, in order: UI (panels edit the state) → actions →
//! state into the renderer → render (unless frozen) → accuracy (reference, score) →
//! reports back → draw image + UI → present, with a screenshot when one is due.

use std::sync::Arc;
use std::time::{Duration, Instant};

use restir_render::effects::EffectSet;
use restir_render::reference_cache::ReferenceCache;
use restir_render::timeline::AnimatedScene;
use restir_render::view::auto_exposure_ev;
use restir_render::{Gpu, PipelineCompile, Renderer, Scene};
use winit::dpi::PhysicalSize;
use winit::window::Window;

use super::Launch;
use super::accuracy::AccuracyState;
use super::accuracy::tracker::{AccuracyTracker, SceneSource};
use super::apply;
use super::camera::CameraState;
use super::clock::clock_for;
use super::compare_side::CompareSide;
use super::egui_layer::EguiLayer;
use super::gpu_surface::GpuSurface;
use super::panels;
use super::scene_loader::{Loaded, SceneLoader, is_environment_spec, with_environment};
use super::scene_view;
use super::screenshot::{self, Shot, WindowCapture};
use super::state::{Action, DeviceInfo, DisplayOptions, ViewerState};

/// What the event loop should do after an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum After {
    Continue,
    Exit,
}

pub struct Viewer {
    window: Arc<Window>,
    gpu: Gpu,
    surface: GpuSurface,
    pub(super) renderer: Renderer,
    egui: EguiLayer,
    pub state: ViewerState,
    /// The scene shown, kept for the accuracy panel's reference jobs.
    pub(super) scene: Arc<Scene>,
    /// An animated scene's clock (its own posed copy of the scene); `None` when static.
    pub(super) clock: Option<AnimatedScene>,
    pub(super) accuracy: AccuracyTracker,
    /// Configuration B of the split screen, while the Compare section has it on.
    pub(super) compare: Option<CompareSide>,
    /// When the two sides were last scored (each score reads both images back).
    compare_scored: Option<Instant>,
    loader: SceneLoader,
    startup: Startup,
    /// A change's pipelines warming beside the window (CPU adapters): the effect set and
    /// the job (`Viewer::pipelines_ready`).
    warming: Option<(EffectSet, WarmJob)>,
    /// A prepared scene was just swapped in: its load warmed the next frame's pipelines.
    just_prepared: bool,
    screenshots: screenshot::Schedule,
    exit_after_screenshot: bool,
    frames_rendered: u64,
    /// Set the exposure automatically once this many frames have rendered (after a
    /// scene load, when the first frames have something to measure).
    auto_exposure_at: Option<u64>,
    last_redraw: Option<Instant>,
    /// When the last frame was rendered (frozen: redraw a little longer, until its report
    /// and inspection have come back).
    last_render: Option<Instant>,
    /// When egui asked to run again.
    ui_wakeup: Option<Instant>,
    /// Hidden behind other windows or on another workspace (where the platform says so).
    occluded: bool,
    /// The pixel history's frame facts and a recording (viewer/tour/driver.rs).
    pub(super) teaching: super::tour::driver::Teaching,
}

/// A change's pipelines compiling on a sibling device (`ScenePreparer::warm_effects`).
type WarmJob = std::thread::JoinHandle<Result<Vec<PipelineCompile>, String>>;

/// Where the viewer's start is: its first frame waits for the warm-up (`Viewer::started`).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Startup {
    NotStarted,
    Warming,
    Done,
}

/// How long a frozen viewer keeps redrawing after rendering a frame, so the frame's
/// report and pixel inspection (read back asynchronously) reach the panels.
const REPORT_GRACE: Duration = Duration::from_millis(500);

/// How often the split screen's per-side errors are measured.
const COMPARE_SCORE_INTERVAL: Duration = Duration::from_millis(250);

/// Frames rendered before the automatic exposure of a new scene is measured.
const AUTO_EXPOSURE_FRAMES: u64 = 3;

impl Viewer {
    pub fn new(window: Arc<Window>, launch: Launch, scene: Arc<Scene>) -> anyhow::Result<Viewer> {
        let (surface, gpu) = GpuSurface::new(window.clone())?;
        let display = DisplayOptions::for_adapter(gpu.is_cpu());
        let size = window.inner_size();
        let (w, h) = apply::render_size(
            (size.width as f32, size.height as f32),
            display.render_scale,
        )
        .unwrap_or((64, 64));
        let mut renderer = Renderer::new(gpu.clone(), &scene, w, h, launch.settings.clone())?;
        let mut state = ViewerState::new(
            launch.settings,
            CameraState::new(renderer.camera(), renderer.scene_bounds()),
            display,
        );
        state.camera.automatic = renderer.scene_info().camera_automatic;
        state.view.view = launch.debug_view;
        if let Some(b) = &launch.compare {
            state.compare.enabled = true;
            state.compare.spec = b.clone();
        }
        if let Some(preset) = &launch.preset {
            state.preset_path = preset.display().to_string();
        }
        state.device = DeviceInfo {
            adapter: gpu.adapter_name(),
            driver: gpu.driver_info(),
            is_cpu: gpu.is_cpu(),
            timing: format!("{:?}", renderer.timing_mode()),
            ray_query: gpu.ray_query,
            ray_backend: None,
        };
        state.accuracy = AccuracyState::new(gpu.is_cpu());
        renderer.set_view(state.view);
        apply::scene_loaded(&renderer, &mut state, launch.scene_spec);
        let clock = clock_for(&scene, &mut state.time);
        if let Some((tour, step)) = launch.tour {
            state.tour = Some(super::tour::TourState::new(tour, launch.env_spec));
            super::tour::go(&mut state, step);
        }
        window.set_title(&title(&state));
        let egui = EguiLayer::new(
            &window,
            &gpu,
            surface.format(),
            &renderer,
            state.display.smooth,
        );
        Ok(Viewer {
            window,
            gpu,
            surface,
            renderer,
            egui,
            state,
            scene,
            clock,
            accuracy: AccuracyTracker::new(
                ReferenceCache::at_default_dir(),
                AccuracyTracker::SETTLE,
            ),
            compare: None,
            compare_scored: None,
            loader: SceneLoader::default(),
            startup: Startup::NotStarted,
            warming: None,
            just_prepared: false,
            screenshots: screenshot::Schedule {
                after: launch.screenshot_after,
                ..Default::default()
            },
            exit_after_screenshot: launch.exit,
            frames_rendered: 0,
            auto_exposure_at: Some(AUTO_EXPOSURE_FRAMES),
            last_redraw: None,
            last_render: None,
            ui_wakeup: None,
            occluded: false,
            teaching: Default::default(),
        })
    }

    pub fn window(&self) -> &Window {
        &self.window
    }

    pub fn frames_rendered(&self) -> u64 {
        self.frames_rendered
    }

    /// The surface size in physical pixels (0×0 while minimised).
    pub fn surface_size(&self) -> (u32, u32) {
        if self.surface.is_drawable() {
            self.surface.size()
        } else {
            (0, 0)
        }
    }

    /// Whether frames should be drawn now (false while minimised or occluded).
    pub fn is_drawable(&self) -> bool {
        self.surface.is_drawable() && !self.occluded
    }

    pub fn set_occluded(&mut self, occluded: bool) {
        self.occluded = occluded;
        self.window.request_redraw();
    }

    /// When the next frame should be drawn: `now` while rendering (progressive frames
    /// never stop), when egui asks while frozen, never while minimised.
    pub fn next_redraw(&self, now: Instant) -> Option<Instant> {
        if !self.is_drawable() {
            return None;
        }
        let inspector = &self.state.inspector;
        let rendering = !inspector.frozen
            || inspector.step
            || self.loader.loading().is_some()
            || self.last_render.is_some_and(|t| now - t < REPORT_GRACE);
        if rendering { Some(now) } else { self.ui_wakeup }
    }

    /// Feeds a window event to egui (all keyboard and pointer input goes through egui);
    /// input egui cares about draws a frame even while frozen.
    pub fn egui_event(&mut self, event: &winit::event::WindowEvent) {
        // (egui-winit asks to repaint on RedrawRequested itself: that would never idle.)
        let repaint = self.egui.on_window_event(&self.window, event);
        if repaint && !matches!(event, winit::event::WindowEvent::RedrawRequested) {
            self.window.request_redraw();
        }
    }

    /// A new window size; 0×0 (minimised) pauses drawing until the next real size.
    pub fn resized(&mut self, size: PhysicalSize<u32>) {
        self.surface.resize(&self.gpu, size.width, size.height);
        if self.surface.is_drawable() {
            self.window.request_redraw();
        }
    }

    pub fn redraw(&mut self) -> anyhow::Result<After> {
        if !self.is_drawable() {
            return Ok(After::Continue);
        }
        let now = Instant::now();
        if let Some(last) = self.last_redraw.replace(now) {
            self.state
                .stats
                .push_frame_ms((now - last).as_secs_f64() * 1e3);
        }
        let images = scene_view::Images {
            a: self.egui.image(),
            b: self.egui.compare_image(),
        };
        let state = &mut self.state;
        let mut area = egui::Rect::NOTHING;
        let (mut output, ui_delay) = self.egui.run(&self.window, |ui| {
            panels::shortcuts(ui.ctx(), state);
            panels::side_panel(ui, state);
            area = scene_view::show(ui, state, Some(images));
        });
        self.ui_wakeup = now.checked_add(ui_delay);
        self.run_actions();
        self.poll_loader();
        let ppp = output.pixels_per_point;
        let rendered = match self.render((area.width() * ppp, area.height() * ppp)) {
            Ok(rendered) => rendered,
            Err(e) => {
                // Stopping: the UI's texture uploads will never be applied.
                output.textures_delta.clear();
                return Err(e);
            }
        };
        self.egui
            .bind_image(&self.gpu, &self.renderer, self.state.display.smooth);
        self.egui.bind_compare_image(
            &self.gpu,
            self.compare.as_ref().map(|c| &c.renderer),
            self.state.display.smooth,
        );
        let shot = self.screenshots.due(self.frames_rendered, rendered);
        let capture = shot
            .as_ref()
            .map(|_| WindowCapture::new(&self.gpu, self.surface.format(), self.surface.size()));
        let frame = self.surface.acquire(&self.gpu);
        let targets: Vec<&wgpu::TextureView> = frame
            .iter()
            .map(|f| &f.view)
            .chain(capture.iter().map(|c| &c.view))
            .collect();
        let (w, h) = self.surface.size();
        self.egui.paint(&self.gpu, output, &targets, [w, h]);
        if let Some(frame) = frame {
            self.surface.present(&self.gpu, frame);
        }
        self.gpu.check()?;
        match (shot, capture) {
            (Some(Shot::AfterFrames(path)), Some(capture)) => {
                let (w, h) = capture.save_png(&self.gpu, &path)?;
                let frames = self.frames_rendered;
                eprintln!(
                    "screenshot: {w}x{h} window after {frames} frames -> {}",
                    path.display()
                );
                if self.exit_after_screenshot {
                    return Ok(After::Exit);
                }
            }
            (Some(Shot::Requested), Some(capture)) => {
                let stem = screenshot::stem(
                    &self.state.screenshot_dir,
                    &self.state.scene.spec,
                    self.renderer.frame_index(),
                );
                let message = screenshot::save_all(&self.gpu, &capture, &self.renderer, &stem);
                self.state.screenshot_message = Some(message);
            }
            _ => {}
        }
        Ok(After::Continue)
    }

    /// Holds the `--screenshot-after` shot (while the resize test script runs).
    pub fn hold_screenshot(&mut self, hold: bool) {
        self.screenshots.hold = hold;
    }

    /// The first frame waits until its pipelines are warm (`ScenePreparer`): a CPU driver
    /// compiles at the first dispatch, on the thread that waits for the frame, and a cold
    /// StainedGlassLamp takes minutes. Returns whether frames may render.
    fn started(&mut self) -> bool {
        if self.startup == Startup::NotStarted {
            // The preparer warms what the first frame will use: the state as it applies.
            apply::before_frame(&mut self.renderer, &self.state);
            // A tour's first step may already be loading (and preparing) its own scene.
            if self.loader.loading().is_none() {
                let spec = self.state.scene.spec.clone();
                let preparer = self.renderer.preparer();
                self.loader
                    .start_warm_up(spec, self.scene.clone(), preparer);
            }
            self.startup = Startup::Warming;
        }
        if self.startup == Startup::Warming && self.loader.loading().is_none() {
            self.startup = Startup::Done;
        }
        self.state.scene.first_frame_waits = self.startup != Startup::Done;
        self.startup == Startup::Done
    }

    /// Whether the next frame's pipelines are ready to run. On a CPU adapter a change that
    /// needs new ones (GI on, another debug view, a mode) first warms them beside the
    /// window, as a scene load does, and the window shows the last frame meanwhile: the
    /// driver would compile them at the first dispatch, on the thread that waits for it.
    fn pipelines_ready(&mut self) -> anyhow::Result<bool> {
        apply::before_frame(&mut self.renderer, &self.state);
        if std::mem::take(&mut self.just_prepared) {
            return Ok(true);
        }
        let needed = self.renderer.effects_to_compile()?;
        if let Some((warmed, job)) = self.warming.take() {
            if !job.is_finished() {
                self.warming = Some((warmed, job));
                return Ok(false);
            }
            match job.join() {
                Ok(Ok(_)) => {}
                Ok(Err(e)) => log::warn!("pipeline warm-up failed ({e}): compiling here"),
                Err(_) => log::warn!("pipeline warm-up stopped: compiling here"),
            }
            if needed.as_ref().is_none_or(|n| *n == warmed) {
                return Ok(true);
            }
        }
        let Some(effects) = needed.filter(|_| self.gpu.is_cpu()) else {
            return Ok(true);
        };
        let job = self
            .renderer
            .preparer()
            .warm_effects(self.scene.clone(), effects.clone());
        self.warming = Some((effects, job));
        Ok(false)
    }

    /// Renders a frame unless frozen (a Step renders one); returns whether it did.
    fn render(&mut self, area: (f32, f32)) -> anyhow::Result<bool> {
        if !self.started() {
            return Ok(false);
        }
        let render_now = !self.state.inspector.frozen || self.state.inspector.step;
        let ready = !render_now || self.pipelines_ready()?;
        self.state.scene.pipelines_warming = !ready;
        if !ready {
            return Ok(false);
        }
        let state = &mut self.state;
        let render_now = !state.inspector.frozen || std::mem::take(&mut state.inspector.step);
        if render_now {
            if let Some((w, h)) = apply::render_size(area, state.display.render_scale) {
                self.renderer.resize(w, h)?;
            }
            state.camera.advance_auto();
            let dt = self.last_render.map_or(0.0, |t| t.elapsed().as_secs_f32());
            let event = self.advance_time(dt);
            let state = &mut self.state;
            apply::before_frame(&mut self.renderer, state);
            // B starts from the scene as posed now (an animated scene's clock has it).
            let posed = self.clock.as_ref().map_or(&*self.scene, |c| c.scene());
            if CompareSide::sync(&mut self.compare, &self.gpu, posed, &self.renderer, state) {
                self.egui.unbind_compare_image();
            }
            if let Some(compare) = &mut self.compare {
                compare.render(&mut self.renderer)?;
            }
            self.renderer.render_frame()?;
            self.frames_rendered += 1;
            self.last_render = Some(Instant::now());
            self.frame_rendered(event);
            let state = &mut self.state;
            if self
                .auto_exposure_at
                .is_some_and(|at| self.frames_rendered >= at)
            {
                self.auto_exposure_at = None;
                state.request(Action::AutoExposure);
            }
        } else {
            apply::redisplay_if_changed(&mut self.renderer, &state.view)?;
            if let Some(compare) = &mut self.compare {
                compare.redisplay(&self.renderer)?;
            }
        }
        self.follow_accuracy(render_now);
        let (teaching, accuracy) = (&self.teaching, &self.accuracy);
        apply::after_frame(&mut self.renderer, &mut self.state, |state, i| {
            let reference = accuracy.reference_luminance(i.pixel);
            super::tour::driver::push_history(state, teaching, i, reference);
        });
        Ok(render_now)
    }

    /// The accuracy tracker follows the view the frame was rendered with (a moved camera
    /// drops the old reference) before it scores the frame against the reference.
    fn follow_accuracy(&mut self, rendered: bool) {
        let tour_wants = self.tour_wants_reference();
        let state = &mut self.state;
        let source = SceneSource {
            spec: &state.scene.spec,
            scene: &self.scene,
        };
        // While scene time plays there is no reference of "now" to compare with.
        let playing = state.time.playing && state.time.duration > 0.0;
        let wanted = (state.accuracy.panel_open
            || state.view.view.needs_reference()
            || state.compare.enabled
            || tour_wants)
            && !playing;
        self.accuracy
            .update(&mut self.renderer, &source, &mut state.accuracy, wanted);
        if rendered {
            self.accuracy.measure(&self.renderer, &mut state.accuracy);
            // The labels' errors and the tour's numbers: a readback per side, so a few
            // times a second, not every frame.
            let now = Instant::now();
            let due = self
                .compare_scored
                .is_none_or(|t| now - t >= COMPARE_SCORE_INTERVAL);
            if due {
                self.compare_scored = Some(now);
                self.score_sides();
            }
        }
    }

    fn run_actions(&mut self) {
        for action in std::mem::take(&mut self.state.actions) {
            match action {
                Action::LoadScene(spec) => {
                    self.state.scene.error = None;
                    let env = self.scene.environment.clone();
                    self.loader.start(spec, env, self.renderer.preparer());
                }
                Action::LoadEnvironment(Some(spec)) => {
                    self.state.scene.env_error = None;
                    let shown = self.scene.clone();
                    self.loader
                        .start_environment(spec, shown, self.renderer.preparer());
                }
                Action::LoadEnvironment(None) => {
                    if let Err(e) = self.remove_environment() {
                        self.state.scene.env_error = Some(e);
                    }
                }
                Action::Screenshot => self.screenshots.requested = true,
                Action::AutoExposure => {
                    let linear = if self.state.view.accumulate {
                        self.renderer.read_accumulated()
                    } else {
                        self.renderer.read_radiance()
                    };
                    self.state.view.exposure_ev = auto_exposure_ev(&linear);
                }
                Action::ResetAccumulation => self.renderer.reset_accumulation(),
                Action::AutoExposureSoon => {
                    self.auto_exposure_at = Some(self.frames_rendered + AUTO_EXPOSURE_FRAMES);
                }
                Action::LoadTourScene { scene, env } => {
                    self.state.scene.error = None;
                    self.loader
                        .start_with_environment(scene, env, self.renderer.preparer());
                }
                Action::ExportPixelHistory => self.export_pixel_history(),
                Action::StartRecording => self.start_recording(),
                Action::StopRecording => self.stop_recording(),
            }
        }
        self.state.scene.loading = self.loader.loading().map(str::to_string);
    }

    /// The same scene without its environment, seen from the same camera (uploaded here:
    /// no image to decode). On failure nothing changes.
    fn remove_environment(&mut self) -> Result<(), String> {
        let scene = with_environment(&self.scene, None)?;
        let camera = self.renderer.camera();
        self.renderer
            .set_scene(&scene)
            .map_err(|e| format!("{e:#}"))?;
        self.environment_replaced(scene, camera);
        Ok(())
    }

    /// The renderer shows `scene`, the shown scene under another environment: the camera
    /// stays where it was.
    fn environment_replaced(&mut self, scene: Scene, camera: restir_render::Camera) {
        self.renderer.set_camera(camera);
        self.scene = Arc::new(scene);
        self.state.scene.info = Some(self.renderer.scene_info().clone());
        self.state.scene.env_error = None;
        self.state.stats.clear();
    }

    /// A finished background load replaces the scene or the environment (keeping scene
    /// and camera); a failed one keeps what there was and shows why. The load prepared
    /// the scene, so the swap itself is quick.
    fn poll_loader(&mut self) {
        self.state.scene.progress = self.loader.progress();
        let Some((spec, result)) = self.loader.poll() else {
            return;
        };
        self.state.scene.loading = None;
        match result {
            Ok(Loaded::Warmed(prepared)) => {
                let camera = self.renderer.camera();
                self.renderer.set_prepared_scene(prepared);
                self.just_prepared = true;
                self.renderer.set_camera(camera);
                self.state.scene.info = Some(self.renderer.scene_info().clone());
            }
            Ok(Loaded::Environment(ready)) => {
                let camera = self.renderer.camera();
                self.renderer.set_prepared_scene(ready.prepared);
                self.just_prepared = true;
                self.environment_replaced(*ready.scene, camera);
            }
            Err(e) if is_environment_spec(&spec) => {
                log::warn!("cannot load {spec}: {e}");
                self.state.scene.env_error = Some(e);
            }
            Ok(Loaded::Scene(ready) | Loaded::SceneWithEnvironment(ready)) => {
                self.renderer.set_prepared_scene(ready.prepared);
                self.just_prepared = true;
                let scene = *ready.scene;
                self.clock = clock_for(&scene, &mut self.state.time);
                self.scene = Arc::new(scene);
                // B is rebuilt on the new scene at the next frame.
                self.compare = None;
                apply::scene_loaded(&self.renderer, &mut self.state, spec);
                self.tour_scene_loaded();
                self.window.set_title(&title(&self.state));
                self.auto_exposure_at = Some(self.frames_rendered + AUTO_EXPOSURE_FRAMES);
            }
            Err(e) => {
                log::warn!("cannot load {spec}: {e}");
                self.state.scene.error = Some(e);
            }
        }
    }
}

fn title(state: &ViewerState) -> String {
    let name = state
        .scene
        .info
        .as_ref()
        .map_or(state.scene.spec.as_str(), |i| i.name.as_str());
    format!("ReSTIR lab — {name}")
}
