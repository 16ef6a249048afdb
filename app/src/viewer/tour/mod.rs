//! A guided tour in the viewer (`--tour FILE`, the Tour section): the current step, what
//! going to a step does to the plain state (this file: no GPU, testable), the live
//! numbers the step asks for (`lag.rs` for the reference-free lag), and the viewer's side
//! of it (`driver.rs`: loading a step's scene, measuring the numbers).

pub mod driver;
pub mod lag;

use crate::tour::{LiveNumber, Tour, TourStep};
use crate::viewer::state::{Action, CompareState, ViewerState};

use lag::LagMeter;

/// The live numbers of one side of the image.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SideNumbers {
    /// Per-frame luma RMSE against the Accuracy reference.
    pub rmse: Option<f64>,
    /// (mean luma − reference's) / reference's, this frame.
    pub bias: Option<f64>,
    pub lag: LagMeter,
}

/// Side A and B (B while the step has a split screen).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LiveNumbers {
    pub a: SideNumbers,
    pub b: SideNumbers,
}

#[derive(Clone, Debug, PartialEq)]
pub struct TourState {
    pub tour: Tour,
    /// The step shown (0-based; the panel counts from 1).
    pub current: usize,
    /// A step whose scene is loading: its camera and time apply once the scene is there.
    pub pending: Option<usize>,
    /// The environment the tour last set (the one loaded now).
    pub env: Option<String>,
    pub numbers: LiveNumbers,
}

impl TourState {
    /// A tour about to show its first step; `env` is the environment already loaded.
    pub fn new(tour: Tour, env: Option<String>) -> TourState {
        TourState {
            tour,
            current: 0,
            pending: None,
            env,
            numbers: LiveNumbers::default(),
        }
    }

    pub fn step(&self) -> &TourStep {
        &self.tour.steps[self.current]
    }

    pub fn shows(&self, number: LiveNumber) -> bool {
        self.step().show.contains(&number)
    }
}

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
