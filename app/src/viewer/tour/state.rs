//! The tour's part of the viewer's plain state (`ViewerState::tour`): the tour, the step
//! shown, a step whose scene is loading, and the live numbers the step asks for. Plain
//! data, so the viewer's state can hold it without knowing how a step is entered
//! (`mod.rs`).

use super::lag::LagMeter;
use crate::tour::{LiveNumber, Tour, TourStep};

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
