//! The one place the UI's plain state meets the renderer: before a frame the state is
//! handed over (the renderer ignores what did not change), after it the renderer's
//! outputs (reports, inspection, effect set) come back into the state.

use restir_render::renderer::{MAX_SIZE, PixelInspection};
use restir_render::settings::RayBackendChoice;
use restir_render::{Renderer, Settings, ViewSettings};

use super::camera::CameraState;
use super::state::{InspectorState, ViewerState};

/// Render-target size for a scene area of `area` physical pixels at `scale`; `None`
/// while the area is empty (window minimised, panel covering everything).
pub fn render_size(area: (f32, f32), scale: f32) -> Option<(u32, u32)> {
    if !(area.0 >= 1.0 && area.1 >= 1.0) {
        return None;
    }
    let side = |v: f32| ((v * scale).round().max(1.0) as u32).min(MAX_SIZE);
    Some((side(area.0), side(area.1)))
}

/// Everything that goes into the next frame. The accumulation restarts when the camera
/// moves or accumulation is switched on (the renderer itself restarts it on mode,
/// parameter, scene and size changes).
pub fn before_frame(renderer: &mut Renderer, state: &ViewerState) {
    renderer.set_mode(state.mode);
    renderer.set_settings(runnable_settings(renderer, &state.settings));
    let turned_on = state.view.accumulate && !renderer.view().accumulate;
    renderer.set_view(state.view);
    let moved = renderer.camera() != state.camera.camera;
    if moved {
        renderer.set_camera(state.camera.camera);
    }
    if moved || turned_on {
        renderer.reset_accumulation();
    }
    renderer.set_inspected_pixel(state.inspector.pixel);
}

/// The settings as this device can run them: `ray_backend=ray-query` without hardware ray
/// queries renders with the software backend (the Pipeline panel says why) instead of
/// failing every frame.
pub fn runnable_settings(renderer: &Renderer, settings: &Settings) -> Settings {
    let mut s = settings.clone();
    if restir_render::tracing::resolve_for(renderer.gpu(), s.ray_backend).is_err() {
        s.ray_backend = RayBackendChoice::Software;
    }
    s
}

/// Shows a view change on a frozen frame (only the display pass runs again).
pub fn redisplay_if_changed(renderer: &mut Renderer, view: &ViewSettings) -> anyhow::Result<()> {
    if renderer.view() != view {
        renderer.set_view(*view);
        renderer.redisplay()?;
    }
    Ok(())
}

/// Reports, the inspected pixel and frame facts back into the state; `on_inspection`
/// sees every inspection that came back (the pixel history).
pub fn after_frame(
    renderer: &mut Renderer,
    state: &mut ViewerState,
    mut on_inspection: impl FnMut(&mut ViewerState, &PixelInspection),
) {
    for report in renderer.collect_reports(false) {
        if let Some(inspection) = &report.inspection {
            on_inspection(state, inspection);
            state.inspector.last = Some(inspection.clone());
        }
        state.accuracy.curves.record_report(&report);
        state.stats.push_report(report);
    }
    state.render_size = renderer.size();
    state.device.ray_backend = renderer.last_ray_backend();
    state.accumulated_frames = renderer.accumulated_frames();
    state.window_frames = renderer.temporal_window_frames();
    if state.denoise_depth.as_ref() != renderer.denoise_depth_choice() {
        state.denoise_depth = renderer.denoise_depth_choice().cloned();
    }
    // Copied only when they change (an effect set carries a sentence per effect).
    if state.scene.effects.as_ref() != renderer.last_effects() {
        state.scene.effects = renderer.last_effects().cloned();
    }
    if state.scene.passes != renderer.last_passes() {
        state.scene.passes = renderer.last_passes().to_vec();
    }
    // The pipelines phase joins after the scene's first frame.
    if state.scene.load.phases.len() != renderer.load_phase_count() {
        state.scene.load = renderer.load_phases();
    }
    // The environment's light share follows the `environment_share` setting.
    let share = renderer
        .scene_info()
        .environment
        .as_ref()
        .map(|e| e.light_share);
    if let Some(env) = state
        .scene
        .info
        .as_mut()
        .and_then(|i| i.environment.as_mut())
        && Some(env.light_share) != share
    {
        env.light_share = share.unwrap_or(0.0);
    }
}

/// A new scene is in the renderer: its camera, facts and fresh statistics.
pub fn scene_loaded(renderer: &Renderer, state: &mut ViewerState, spec: String) {
    let motion = state.camera.motion;
    state.camera = CameraState::new(renderer.camera(), renderer.scene_bounds());
    state.camera.motion = motion;
    state.camera.automatic = renderer.scene_info().camera_automatic;
    state.scene.info = Some(renderer.scene_info().clone());
    state.scene.spec = spec;
    state.scene.error = None;
    state.stats.clear();
    state.inspector = InspectorState {
        pixel: state.inspector.pixel,
        history: crate::probe::PixelHistory::new(state.inspector.history.capacity),
        history_path: std::mem::take(&mut state.inspector.history_path),
        ..Default::default()
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_size_scales_and_never_reaches_zero() {
        assert_eq!(render_size((900.0, 720.0), 0.25), Some((225, 180)));
        assert_eq!(render_size((3.0, 2.0), 0.1), Some((1, 1)));
        assert_eq!(render_size((0.0, 720.0), 1.0), None);
        assert_eq!(render_size((f32::NAN, 1.0), 1.0), None);
        assert_eq!(render_size((1e6, 10.0), 1.0), Some((MAX_SIZE, 10)));
    }
}
