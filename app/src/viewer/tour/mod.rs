//! A guided tour in the viewer (`--tour FILE`, the Tour section): the current step and
//! its live numbers (`state.rs`, part of the viewer's plain state), what going to a step
//! does to the plain state (this file: no GPU, testable), the reference-free lag (`lag.rs`),
//! and the viewer's side of it (`driver.rs`: loading a step's scene, measuring the numbers;
//! `teaching.rs`: what it keeps between frames).

pub mod driver;
pub mod lag;
pub mod state;
pub mod teaching;

use crate::viewer::state::{Action, CompareState, ViewerState};

use state::LiveNumbers;

/// Goes to step `index` (clamped): its mode, parameters, B, view and exposure now; its
/// scene (with its environment) loads in the background if it is not the one shown, and
/// its camera and time follow once it is there (`after_load`).
pub fn go(state: &mut ViewerState, index: usize) {
    let Some(tour) = &mut state.tour else {
        return;
    };
    let index = index.min(tour.tour.steps.len() - 1);
    tour.current = index;
    tour.numbers = LiveNumbers::default();
    let step = tour.tour.steps[index].clone();
    let reload = step.scene != state.scene.spec || step.env != tour.env;
    tour.pending = reload.then_some(index);
    if reload {
        tour.env = step.env.clone();
    }
    state.settings = step.settings.clone();
    state.mode = step.mode;
    state.view.view = step.debug_view;
    state.view.accumulate = false;
    match step.exposure {
        Some(ev) => state.view.exposure_ev = ev,
        None => state.request(Action::AutoExposureSoon),
    }
    state.compare = match &step.compare {
        Some(b) => CompareState {
            enabled: true,
            spec: b.label.clone(),
            target: Some(b.clone()),
            error: None,
            errors: None,
            ..state.compare.clone()
        },
        None => CompareState {
            enabled: false,
            target: None,
            errors: None,
            ..state.compare.clone()
        },
    };
    state.inspector.history.samples.clear();
    if reload {
        state.request(Action::LoadTourScene {
            scene: step.scene,
            env: step.env,
        });
    } else {
        after_load(state, index);
    }
}

/// The next or previous step (`delta` ±1), if there is one.
pub fn advance(state: &mut ViewerState, delta: isize) {
    let Some(tour) = &state.tour else {
        return;
    };
    let next = tour.current as isize + delta;
    if (0..tour.tour.steps.len() as isize).contains(&next) {
        go(state, next as usize);
    }
}

/// A step's camera and scene time, once its scene is the one shown.
pub fn after_load(state: &mut ViewerState, index: usize) {
    let Some(tour) = &mut state.tour else {
        return;
    };
    if tour.pending == Some(index) {
        tour.pending = None;
    }
    let step = tour.tour.steps[index].clone();
    let camera = &mut state.camera;
    camera.camera = step.camera.unwrap_or(camera.scene_camera);
    camera.motion.orbit = false;
    camera.motion.dolly = false;
    let time = &mut state.time;
    if time.duration > 0.0 {
        time.time = step.time.start.unwrap_or(0.0).clamp(0.0, time.duration);
        time.playing = !step.time.paused;
        time.step = false;
        time.frame_fps = step.time.fps;
        time.clip = step
            .time
            .clip
            .as_ref()
            .and_then(|name| time.clips.iter().position(|c| c == name));
    }
}
