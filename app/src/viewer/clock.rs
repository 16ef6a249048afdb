//! Scene time in the viewer: the clock of an animated scene, advanced and applied before
//! each rendered frame (the Time section edits `TimeState`; this turns it into poses).

use std::sync::Arc;

use restir_render::Scene;
use restir_render::scene::animation::ClipChoice;
use restir_render::timeline::AnimatedScene;

use super::state::TimeState;
use super::window::Viewer;

/// A clock for an animated scene, and the Time section's view of it.
pub(super) fn clock_for(scene: &Scene, time: &mut TimeState) -> Option<AnimatedScene> {
    *time = TimeState::default();
    let anim = scene.animation.as_ref()?;
    time.duration = anim.duration(ClipChoice::All);
    time.clips = anim.clips.iter().map(|c| c.name.clone()).collect();
    Some(AnimatedScene::new(scene.clone()))
}

impl Viewer {
    /// Moves scene time on (playing, a step, a scrub) and poses the scene there. A paused
    /// scene that changed also becomes the Accuracy panel's scene, so its reference is
    /// of the moment shown. Returns whether a light event of the scene was passed (the
    /// pixel history and the tour's lag mark it).
    pub(super) fn advance_time(&mut self, dt: f32) -> bool {
        let Some(clock) = &mut self.clock else {
            return false;
        };
        let time = &mut self.state.time;
        clock.set_clip_choice(time.clip.map_or(ClipChoice::All, ClipChoice::One));
        time.duration = clock.duration();
        let before = time.time;
        time.advance(dt);
        // Unwrapped: a loop back to the start is time moving on, not back.
        let after = if time.time < before && time.looping {
            time.time + time.duration
        } else {
            time.time
        };
        let event = after > before
            && crate::probe::event_between(clock.scene().animation.as_ref(), before, after);
        let (change, _) = clock.set_time(&mut self.renderer, time.time);
        // The split screen's B shows the same moment.
        if let Some(b) = self.compare.as_mut().filter(|_| change.any()) {
            b.renderer.update_scene(clock.scene(), change.clone());
        }
        if change.camera {
            // A camera on an animated node: follow it unless the user flew away from it.
            let followed = clock.scene().default_camera();
            let cam = &mut self.state.camera;
            if cam.camera == cam.scene_camera {
                cam.camera = followed;
            }
            cam.scene_camera = followed;
        }
        if change.any() && !time.playing {
            self.scene = Arc::new(clock.scene().clone());
        }
        event
    }
}
