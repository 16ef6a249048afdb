//! The frame as an ordered list of passes, read top to bottom like the pipeline diagram
//! (README): G-buffer → (light tiles) → initial → temporal → spatial × P → shade →
//! display, or G-buffer (jitter off) → reference → display. A stage the settings switch
//! off is not in the list, hence never dispatched or compiled.

use std::ops::Range;

use crate::passes::{
    PassDef, display, gbuffer, initial, presample, reference, shade, spatial, temporal,
};

/// One pass of the frame.
#[derive(Clone, Debug)]
pub struct Step {
    pub pass: &'static PassDef,
    /// `PassInfo` slots: one dispatch per slot, in one timed pass (empty: one dispatch,
    /// with slot 0 if the pass reads `PassInfo`).
    pub slots: Range<u32>,
    /// After this step the pixel inspector captures the DI reservoir as this stage.
    pub inspect: Option<&'static str>,
}

impl Step {
    fn new(pass: &'static PassDef) -> Step {
        Step {
            pass,
            slots: 0..0,
            inspect: None,
        }
    }

    fn slots(mut self, slots: Range<u32>) -> Step {
        self.slots = slots;
        self
    }

    fn inspect(mut self, stage: &'static str) -> Step {
        self.inspect = Some(stage);
        self
    }
}

/// What decides which passes a frame runs.
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameSwitches {
    /// False in `reference` mode.
    pub realtime: bool,
    /// Rasterise the G-buffer (every real-time frame; the reference with jitter off).
    pub gbuffer: bool,
    pub light_tiles: bool,
    pub temporal: bool,
    /// Spatial passes (0 = spatial reuse off).
    pub spatial_passes: u32,
    /// Dispatches of the reference (chunks of samples).
    pub reference_chunks: u32,
}

pub fn frame_plan(f: &FrameSwitches) -> Vec<Step> {
    let mut steps = Vec::new();
    if f.gbuffer {
        steps.push(Step::new(&gbuffer::RASTER));
        steps.push(Step::new(&gbuffer::RESOLVE));
    }
    if f.realtime {
        if f.light_tiles {
            steps.push(Step::new(&presample::PASS));
        }
        steps.push(Step::new(&initial::PASS).inspect("initial"));
        if f.temporal {
            steps.push(Step::new(&temporal::PASS).inspect("temporal"));
        }
        for p in 0..f.spatial_passes {
            steps.push(Step::new(&spatial::PASS).slots(p..p + 1).inspect("spatial"));
        }
        steps.push(Step::new(&shade::PASS));
    } else {
        steps.push(Step::new(&reference::PASS).slots(0..f.reference_chunks.max(1)));
    }
    steps.push(Step::new(&display::PASS));
    steps
}

/// Only the display pass, on the last frame's buffers (`Renderer::redisplay`).
pub fn display_only() -> Vec<Step> {
    vec![Step::new(&display::PASS)]
}
