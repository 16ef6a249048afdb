//! The viewer's side of what the UI asks for (`Action`s queued on the plain state) and of
//! the background loads it starts: a finished load swaps the scene or the environment in,
//! a failed one keeps what there was and says why.

use std::sync::Arc;

use restir_render::Scene;
use restir_render::view::auto_exposure_ev;

use super::apply;
use super::clock::clock_for;
use super::scene_loader::{Loaded, is_environment_spec, with_environment};
use super::state::Action;
use super::window::{AUTO_EXPOSURE_FRAMES, Viewer, title};

impl Viewer {
    /// What the UI asked for this frame (`Action`s queued on the state).
    pub(super) fn run_actions(&mut self) {
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
    pub(super) fn poll_loader(&mut self) {
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
