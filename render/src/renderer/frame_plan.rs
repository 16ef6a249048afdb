//! The frame as an ordered list of passes, read top to bottom like the pipeline diagram
//! (docs/src/introduction.md, "The pipeline at a glance"): G-buffer → (light tiles) → DI initial →
//! temporal → spatial × P → shade → (GI initial → temporal → spatial → shade, or PT initial →
//! temporal → spatial → shade) → moments → (temporal window) → display (→ GI or PT view) (→ bias
//! view) (→ window view), or G-buffer (jitter off) → reference → moments → (temporal window) →
//! display. A stage the settings switch off is not in the list, hence never dispatched or compiled.

use std::ops::Range;

use crate::passes::resources::{Chain, RESERVOIRS};
use crate::passes::{
    PassDef, bias_view, display, gbuffer, gi, initial, moments, presample, pt, reference, shade,
    spatial, temporal, temporal_window, window_view,
};

/// One pass of the frame.
#[derive(Clone, Debug)]
pub struct Step {
    pub pass: &'static PassDef,
    /// `PassInfo` slots: one dispatch per slot, in one timed pass (empty: one dispatch,
    /// with slot 0 if the pass reads `PassInfo`).
    pub slots: Range<u32>,
    /// After this step the pixel inspector captures this chain's reservoir as a stage.
    pub inspect: Option<Inspect>,
}

/// What the inspector captures after a step: the current reservoir of `chain`, as `stage`.
#[derive(Clone, Copy, Debug)]
pub struct Inspect {
    pub chain: &'static Chain,
    pub stage: &'static str,
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
        self.inspect = Some(Inspect {
            chain: &RESERVOIRS,
            stage,
        });
        self
    }

    fn inspect_gi(mut self, stage: &'static str) -> Step {
        self.inspect = Some(Inspect {
            chain: &gi::initial::GI_RESERVOIRS,
            stage,
        });
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
    /// ReSTIR GI (real-time frames only) and its reuse stages.
    pub gi: bool,
    pub gi_temporal: bool,
    pub gi_spatial: bool,
    /// ReSTIR PT (real-time frames only; GI is off while it is on) and its reuse stages.
    pub pt: bool,
    pub pt_temporal: bool,
    pub pt_spatial: bool,
    /// A PT debug view (or the indirect light) is shown (drawn over the display's output).
    pub pt_view: bool,
    /// A GI debug view is shown (drawn over the display's output).
    pub gi_view: bool,
    /// The bias view is shown (drawn over the display's output).
    pub bias_view: bool,
    /// The boiling or survivor-change view is shown: the temporal window is kept and the
    /// view drawn over the display's output.
    pub temporal_window: bool,
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
        if f.gi {
            steps.push(Step::new(&gi::initial::PASS).inspect_gi("gi initial"));
            if f.gi_temporal {
                steps.push(Step::new(&gi::temporal::PASS).inspect_gi("gi temporal"));
            }
            if f.gi_spatial {
                steps.push(Step::new(&gi::spatial::PASS).inspect_gi("gi spatial"));
            }
            steps.push(Step::new(&gi::shade::PASS));
        }
        if f.pt {
            steps.push(Step::new(&pt::initial::PASS));
            if f.pt_temporal {
                steps.push(Step::new(&pt::temporal::PASS));
            }
            if f.pt_spatial {
                steps.push(Step::new(&pt::spatial::PASS));
            }
            steps.push(Step::new(&pt::shade::PASS));
        }
    } else {
        steps.push(Step::new(&reference::PASS).slots(0..f.reference_chunks.max(1)));
    }
    // The frame's radiance is final here (DI, GI, or the reference).
    steps.push(Step::new(&moments::PASS));
    if f.temporal_window {
        // The frame's radiance is final here; slot 1 says its reservoirs are this frame's.
        let slot = if f.realtime {
            temporal_window::REALTIME_SLOT
        } else {
            0
        };
        steps.push(Step::new(&temporal_window::PASS).slots(slot..slot + 1));
    }
    steps.push(Step::new(&display::PASS));
    if f.realtime && f.gi && f.gi_view {
        steps.push(Step::new(&gi::view::PASS));
    }
    if f.realtime && f.pt && f.pt_view {
        steps.push(Step::new(&pt::view::PASS));
    }
    if f.bias_view {
        steps.push(Step::new(&bias_view::PASS));
    }
    if f.temporal_window {
        steps.push(Step::new(&window_view::PASS));
    }
    steps
}

/// Only the display (and GI, PT, bias or window view) passes, on the last frame's buffers
/// (`Renderer::redisplay`).
pub fn display_only(gi_view: bool, pt_view: bool, bias_view: bool, window_view: bool) -> Vec<Step> {
    let mut steps = vec![Step::new(&display::PASS)];
    if gi_view {
        steps.push(Step::new(&gi::view::PASS));
    }
    if pt_view {
        steps.push(Step::new(&pt::view::PASS));
    }
    if bias_view {
        steps.push(Step::new(&bias_view::PASS));
    }
    if window_view {
        steps.push(Step::new(&window_view::PASS));
    }
    steps
}
