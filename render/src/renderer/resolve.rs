//! From a frame plan to buffers: which surface buffer is current, which buffer of each
//! reservoir chain every step reads and writes (the ping-pong), and what must be
//! allocated. A pure function of the plan and last frame's state, tested below.

use std::collections::HashMap;

use super::frame_plan::Step;
use crate::frame_targets::Needs;
use crate::passes::pass::Access;
use crate::passes::resources::{ACCUMULATION, Chain, LightData, RADIANCE, Resource, Role};

/// A binding resolved to one concrete resource (a bind group cache key).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Bound {
    Surfaces(usize),
    Pixels(&'static str),
    Chain(&'static str, usize),
    PassInfo,
    DisplayUniform,
    Lights(LightData),
    Visibility,
    Output,
}

/// Last frame's state the resolution starts from.
#[derive(Clone, Debug, Default)]
pub struct Carried {
    /// Per chain last frame used, the buffer holding its final reservoirs.
    pub history: HashMap<&'static str, usize>,
    /// The surface buffer last frame wrote.
    pub surfaces: usize,
    /// Surface buffers allocated so far.
    pub surface_buffers: usize,
}

impl Carried {
    /// Whether last frame left `chain` a history (it used the chain).
    pub fn has_history(&self, chain: &Chain) -> bool {
        self.history.contains_key(chain.name)
    }

    /// The buffer of `chain` holding last frame's final reservoirs.
    pub fn history(&self, chain: &Chain) -> usize {
        self.history.get(chain.name).copied().unwrap_or(0)
    }
}

#[derive(Debug)]
pub struct ResolvedStep {
    pub bound: Vec<Bound>,
    /// (chain, stage name, its buffer) to capture after the step.
    pub inspect: Option<(&'static Chain, &'static str, usize)>,
}

#[derive(Debug)]
pub struct Resolved {
    pub steps: Vec<ResolvedStep>,
    /// The surface buffer this frame writes.
    pub surfaces: usize,
    /// Per chain, the buffer current after the last step (next frame's history).
    pub finals: HashMap<&'static str, usize>,
    pub needs: Needs,
}

/// The first buffer index that is neither `a` nor `b`.
fn other(a: usize, b: usize) -> usize {
    (0..).find(|&i| i != a && i != b).expect("an index")
}

/// `advance`: a new frame writes the other surface buffer once there are two; false
/// re-reads last frame's (redisplay). `shown_accumulation`: what `ShownImage` is.
pub fn resolve(
    plan: &[Step],
    carried: &Carried,
    advance: bool,
    shown_accumulation: bool,
) -> Resolved {
    let reads = |step: &Step, wanted: fn(&Resource) -> bool| {
        step.pass.group.iter().any(|b| wanted(&b.resource))
    };
    let previous_surfaces = carried.surface_buffers >= 2
        || plan
            .iter()
            .any(|s| reads(s, |r| matches!(r, Resource::PrevSurfaces)));
    let surfaces = match (previous_surfaces, advance) {
        (true, true) => 1 - carried.surfaces.min(1),
        (true, false) => carried.surfaces.min(1),
        (false, _) => 0,
    };
    // Per chain: (current buffer, history buffer, highest index used).
    let mut chains: Vec<(&'static Chain, usize, usize, usize)> = Vec::new();
    let mut pixels = Vec::new();
    let mut steps = Vec::new();
    for (i, step) in plan.iter().enumerate() {
        let mut bound = Vec::with_capacity(step.pass.group.len());
        let mut outs = Vec::new();
        for binding in step.pass.group {
            bound.push(match binding.resource {
                Resource::Surfaces => Bound::Surfaces(surfaces),
                Resource::PrevSurfaces => Bound::Surfaces(1 - surfaces),
                Resource::Pixels(p) => {
                    pixels.push(p);
                    Bound::Pixels(p.name)
                }
                Resource::ShownImage => {
                    let p = if shown_accumulation { &ACCUMULATION } else { &RADIANCE };
                    Bound::Pixels(p.name)
                }
                Resource::Chain(chain, role) => {
                    let slot = match chains.iter().position(|c| c.0.name == chain.name) {
                        Some(slot) => slot,
                        None => {
                            let h = carried.history.get(chain.name).copied().unwrap_or(0);
                            chains.push((chain, h, h, h));
                            chains.len() - 1
                        }
                    };
                    let (_, current, history, _) = chains[slot];
                    match role {
                        Role::In => Bound::Chain(chain.name, current),
                        Role::History => Bound::Chain(chain.name, history),
                        Role::Out => {
                            // Keep the history while this or a later step still reads it.
                            let history_read = plan[i..].iter().any(|s| {
                                s.pass.group.iter().any(|b| {
                                    matches!(b.resource, Resource::Chain(c, Role::History) if c.name == chain.name)
                                })
                            });
                            let keep = if history_read { history } else { current };
                            let out = other(current, keep);
                            debug_assert_eq!(binding.access, Access::ReadWrite);
                            outs.push((slot, out));
                            Bound::Chain(chain.name, out)
                        }
                    }
                }
                Resource::PassInfo => Bound::PassInfo,
                Resource::DisplayUniform => Bound::DisplayUniform,
                Resource::Lights(data) => Bound::Lights(data),
                Resource::Visibility => Bound::Visibility,
                Resource::Output => Bound::Output,
            });
        }
        for (slot, out) in outs {
            chains[slot].1 = out;
            chains[slot].3 = chains[slot].3.max(out);
        }
        let inspect = step.inspect.map(|inspect| {
            let current = chains
                .iter()
                .find(|c| c.0.name == inspect.chain.name)
                .map_or(0, |c| c.1);
            (inspect.chain, inspect.stage, current)
        });
        steps.push(ResolvedStep { bound, inspect });
    }
    let finals = chains.iter().map(|c| (c.0.name, c.1)).collect();
    let needs = Needs {
        chains: chains.iter().map(|c| (c.0, c.3 + 1)).collect(),
        previous_surfaces,
        pixels,
    };
    Resolved {
        steps,
        surfaces,
        finals,
        needs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::renderer::frame_plan::{FrameSwitches, frame_plan};

    fn all_switch_combinations() -> Vec<FrameSwitches> {
        let mut out = Vec::new();
        for realtime in [true, false] {
            for temporal in [false, true] {
                for spatial_passes in [0, 1, 3] {
                    for (gi, pt) in [(false, false), (true, false), (false, true)] {
                        out.push(FrameSwitches {
                            realtime,
                            gbuffer: true,
                            light_tiles: true,
                            regir_slots: if temporal { 4096 } else { 0 },
                            temporal,
                            spatial_passes,
                            mutation: temporal,
                            reference_chunks: 2,
                            gi,
                            gi_temporal: temporal,
                            gi_spatial: spatial_passes > 0,
                            pt,
                            pt_temporal: temporal,
                            pt_spatial: spatial_passes > 0,
                            pt_view: pt,
                            gi_view: gi,
                            bias_view: !gi,
                            temporal_window: gi,
                            denoise: spatial_passes != 1,
                            denoise_gradients: gi,
                            denoise_iterations: spatial_passes + 1,
                            denoise_history: temporal,
                            denoise_view: pt,
                        });
                    }
                }
            }
        }
        out
    }

    /// Within a step, a buffer that is written is bound once (no read of what the step
    /// overwrites), and no step writes last frame's reservoirs before temporal reuse has
    /// read them.
    #[test]
    fn stages_never_write_a_buffer_they_read_nor_the_history_before_it_is_read() {
        for switches in all_switch_combinations() {
            let plan = frame_plan(&switches);
            for history in 0..3 {
                let carried = Carried {
                    history: [
                        ("reservoirs", history),
                        ("gi reservoirs", history),
                        ("pt reservoirs", history),
                        ("denoise history", history),
                        ("denoise filtered", history),
                    ]
                    .into_iter()
                    .collect(),
                    surfaces: 1,
                    surface_buffers: 2,
                };
                let resolved = resolve(&plan, &carried, true, false);
                for chain in [
                    "reservoirs",
                    "gi reservoirs",
                    "pt reservoirs",
                    "denoise history",
                    "denoise filtered",
                ] {
                    let reads_history = |step: &Step| {
                        step.pass.group.iter().any(|b| {
                            matches!(b.resource, Resource::Chain(c, Role::History) if c.name == chain)
                        })
                    };
                    let history_reader = plan.iter().position(reads_history);
                    for (i, (step, r)) in plan.iter().zip(&resolved.steps).enumerate() {
                        for (binding, bound) in step.pass.group.iter().zip(&r.bound) {
                            if binding.access != Access::ReadWrite {
                                continue;
                            }
                            let aliases = r.bound.iter().filter(|b| *b == bound).count();
                            assert_eq!(aliases, 1, "{} binds {bound:?} twice", step.pass.name);
                            let overwrites = *bound == Bound::Chain(chain, history)
                                && history_reader.is_some_and(|reader| i < reader);
                            assert!(
                                !overwrites,
                                "{} overwrites the {chain} history before it is read ({switches:?})",
                                step.pass.name
                            );
                        }
                    }
                }
            }
        }
    }

    /// Without temporal reuse two reservoir buffers and one surface buffer suffice; with
    /// it, three and two.
    #[test]
    fn history_buffers_are_needed_only_with_temporal_reuse() {
        let mut switches = FrameSwitches {
            realtime: true,
            gbuffer: true,
            spatial_passes: 2,
            ..Default::default()
        };
        let fresh = Carried::default();
        let r = resolve(&frame_plan(&switches), &fresh, true, false);
        assert_eq!(r.needs.chains[0].1, 2);
        assert!(!r.needs.previous_surfaces);
        switches.temporal = true;
        let r = resolve(&frame_plan(&switches), &fresh, true, false);
        assert_eq!(r.needs.chains[0].1, 3);
        assert!(r.needs.previous_surfaces);
        // The surfaces alternate once there are two buffers.
        assert_eq!(r.surfaces, 1);
    }

    /// The display of a reference frame shows the reservoirs real-time frames left.
    #[test]
    fn a_reference_frame_keeps_the_history() {
        let switches = FrameSwitches {
            realtime: false,
            gbuffer: false,
            reference_chunks: 3,
            ..Default::default()
        };
        let carried = Carried {
            history: [("reservoirs", 2)].into_iter().collect(),
            surfaces: 0,
            surface_buffers: 1,
        };
        let r = resolve(&frame_plan(&switches), &carried, true, true);
        assert_eq!(r.finals["reservoirs"], 2);
        let display = r.steps.last().unwrap();
        assert!(display.bound.contains(&Bound::Chain("reservoirs", 2)));
        assert!(display.bound.contains(&Bound::Pixels("accumulation")));
    }
}
