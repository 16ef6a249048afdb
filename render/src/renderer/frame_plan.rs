//! The frame as an ordered list of passes, read top to bottom like the pipeline diagram
//! (docs/src/frame.md): G-buffer → (light tiles) → DI initial → temporal → spatial × P →
//! (mutation) → shade → (GI initial → temporal → spatial → shade, or PT initial → temporal → spatial →
//! shade) → (denoise temporal → variance → à-trous × N → modulate) → moments → (temporal
//! window) → display (→ GI or PT view) (→ denoiser view) (→ bias view) (→ window view), or
//! G-buffer (jitter off) → reference → moments → (temporal window) → display. A stage the
//! settings switch off is not in the list, hence never dispatched or compiled.

use std::ops::Range;

use crate::di::passes::{initial, mutation, shade, spatial, temporal};
use crate::passes::lights::{presample, regir};
use crate::passes::resources::{Chain, RESERVOIRS};
use crate::passes::{
    PassDef, bias_view, display, gbuffer, moments, reference, temporal_window, window_view,
};
use crate::{denoise::passes as denoise, gi::passes as gi, pt::passes as pt};

/// One pass of the frame.
#[derive(Clone, Debug)]
pub struct Step {
    pub pass: &'static PassDef,
    /// `PassInfo` slots: one dispatch per slot, in one timed pass (empty: one dispatch,
    /// with slot 0 if the pass reads `PassInfo`).
    pub slots: Range<u32>,
    /// After this step the pixel inspector captures this chain's reservoir as a stage.
    pub inspect: Option<Inspect>,
    /// Invocations of a `Dispatch::Threads` pass this frame, below its maximum (ReGIR's
    /// cells × slots); `None`: the maximum.
    pub threads: Option<u32>,
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
            threads: None,
        }
    }

    fn threads(mut self, threads: u32) -> Step {
        self.threads = Some(threads);
        self
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
    /// ReGIR's slots to fill this frame (cells × slots per cell; 0: ReGIR off).
    pub regir_slots: u32,
    pub temporal: bool,
    /// Spatial passes (0 = spatial reuse off).
    pub spatial_passes: u32,
    /// MCMC mutation of DI's samples after the last reuse pass.
    pub mutation: bool,
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
    /// The denoiser runs after shading (real-time frames), with this many à-trous passes,
    /// with or without temporal gradients.
    pub denoise: bool,
    pub denoise_gradients: bool,
    pub denoise_iterations: u32,
    /// Last frame left the denoiser a valid history.
    pub denoise_history: bool,
    /// A denoiser view is shown (drawn over the display's output).
    pub denoise_view: bool,
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
        if f.regir_slots > 0 {
            steps.push(Step::new(&regir::FILL).threads(f.regir_slots));
        }
        steps.push(Step::new(&initial::PASS).inspect("initial"));
        if f.temporal {
            steps.push(Step::new(&temporal::PASS).inspect("temporal"));
        }
        for p in 0..f.spatial_passes {
            steps.push(Step::new(&spatial::PASS).slots(p..p + 1).inspect("spatial"));
        }
        if f.mutation {
            steps.push(Step::new(&mutation::PASS).inspect("mutation"));
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
        if f.denoise {
            // The frame's radiance is final here: the denoiser replaces it.
            let slot = if f.denoise_history {
                denoise::temporal::WITH_HISTORY_SLOT
            } else {
                0
            };
            if f.denoise_gradients {
                steps.push(Step::new(&denoise::gradient::PASS));
            }
            steps.push(Step::new(&denoise::temporal::PASS).slots(slot..slot + 1));
            steps.push(Step::new(&denoise::variance::PASS));
            for i in 0..f.denoise_iterations.max(1) {
                steps.push(Step::new(&denoise::atrous::PASS).slots(i..i + 1));
            }
            steps.push(Step::new(&denoise::modulate::PASS));
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
    if f.realtime && f.denoise && f.denoise_view {
        steps.push(Step::new(&denoise::view::PASS));
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
pub fn display_only(
    gi_view: bool,
    pt_view: bool,
    denoise_view: bool,
    bias_view: bool,
    window_view: bool,
) -> Vec<Step> {
    let mut steps = vec![Step::new(&display::PASS)];
    if gi_view {
        steps.push(Step::new(&gi::view::PASS));
    }
    if pt_view {
        steps.push(Step::new(&pt::view::PASS));
    }
    if denoise_view {
        steps.push(Step::new(&denoise::view::PASS));
    }
    if bias_view {
        steps.push(Step::new(&bias_view::PASS));
    }
    if window_view {
        steps.push(Step::new(&window_view::PASS));
    }
    steps
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The denoiser runs after every shading pass, its à-trous passes one per iteration
    /// with taps 2^slot apart, its temporal pass told by its slot whether a history exists.
    #[test]
    fn the_denoiser_follows_shading_one_atrous_step_per_iteration() {
        let switches = FrameSwitches {
            realtime: true,
            gbuffer: true,
            pt: true,
            denoise: true,
            denoise_gradients: true,
            denoise_iterations: 3,
            denoise_history: true,
            ..Default::default()
        };
        let plan = frame_plan(&switches);
        let names: Vec<&str> = plan.iter().map(|s| s.pass.name).collect();
        let at = |name: &str| names.iter().position(|n| *n == name).unwrap();
        assert!(at("pt shade") < at("denoise gradient"), "{names:?}");
        assert!(at("denoise gradient") < at("denoise temporal"), "{names:?}");
        assert!(at("denoise modulate") < at("moments"), "{names:?}");
        let slots: Vec<_> = plan
            .iter()
            .filter(|s| s.pass.name == "denoise atrous")
            .map(|s| s.slots.clone())
            .collect();
        assert_eq!(slots, vec![0..1, 1..2, 2..3]);
        assert_eq!(plan[at("denoise temporal")].slots, 1..2);
        let fresh = frame_plan(&FrameSwitches {
            denoise_history: false,
            ..switches
        });
        assert!(
            fresh
                .iter()
                .any(|s| s.pass.name == "denoise temporal" && s.slots == (0..1))
        );
        let off = frame_plan(&FrameSwitches {
            denoise: false,
            ..switches
        });
        assert!(!off.iter().any(|s| s.pass.name.starts_with("denoise")));
    }
}
