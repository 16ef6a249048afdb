//! One window's viewer, opened, and its frame, in order: UI (panels edit the state) →
//! actions → state into the renderer → render (unless frozen) → accuracy (reference,
//! score) → reports back → draw image + UI → present, with a screenshot when one is due.
//! What the viewer holds is `window.rs`; the actions and finished loads are `actions.rs`.

use std::sync::Arc;
use std::time::Instant;

use restir_render::reference_cache::ReferenceCache;
use restir_render::{Renderer, Scene};
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
use super::scene_loader::SceneLoader;
use super::scene_view;
use super::screenshot::{self, Shot, WindowCapture};
use super::state::{Action, DeviceInfo, DisplayOptions, ViewerState};
use super::tour::driver::push_history;
use super::tour::state::TourState;
use super::window::{AUTO_EXPOSURE_FRAMES, Startup, Viewer, title};

/// What the event loop should do after an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum After {
    Continue,
    Exit,
}

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
            state.tour = Some(TourState::new(tour, launch.env_spec));
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
            push_history(state, teaching, i, reference);
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
            // The labels' errors and the tour's numbers (throttled per side inside).
            self.score_sides();
        }
    }
}
