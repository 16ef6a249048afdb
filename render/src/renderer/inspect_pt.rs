//! The pixel inspector's ReSTIR PT part: the pixel's PT debug record and, per PT stage,
//! the path reservoir it kept with the path's vertices (the probe shaders/pt/probe.wgsl writes),
//! decoded into names a person reads: path length, end technique, the reconnection
//! vertex, lobes, |J|.

use crate::gpu_types::{GpuPtPixelDebug, GpuPtProbeStage, GpuPtReservoir};
use crate::pt::constants::*;
use crate::shader_constants::*;

/// The probe's stages, in its slot order.
pub const PT_STAGE_NAMES: [&str; PT_PROBE_STAGES as usize] =
    ["pt initial", "pt temporal", "pt spatial"];

/// One vertex of a probed path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PtVertex {
    pub position: [f32; 3],
    /// The reconnection vertex x_{k+1} (what shifts connect to).
    pub reconnection: bool,
    /// The light end z (a point, or a direction for the environment).
    pub light: bool,
    pub direction: bool,
}

/// One PT stage's path at the inspected pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct PtStagePath {
    pub stage: &'static str,
    pub reservoir: GpuPtReservoir,
    /// x_1 … x_n then z; shorter when the rebuild left the path (a prefix replayed from a
    /// moved camera can miss where the original went).
    pub vertices: Vec<PtVertex>,
}

impl PtStagePath {
    fn packed(&self) -> u32 {
        self.reservoir.packed
    }

    pub fn is_null(&self) -> bool {
        (self.packed() & 0xf) == SOURCE_NULL || !(self.reservoir.weight > 0.0)
    }

    pub fn source_name(&self) -> &'static str {
        SOURCE_NAMES
            .get((self.packed() & 0xf) as usize)
            .copied()
            .unwrap_or("?")
    }

    /// The path's last surface vertex x_n (its length in bounces).
    pub fn length(&self) -> u32 {
        (self.packed() >> 4) & 0xf
    }

    /// "light sampling" or "BSDF hit": how x_n connects to z.
    pub fn end_name(&self) -> &'static str {
        if (self.packed() >> 8) & 1 == PT_END_BSDF {
            "BSDF hit"
        } else {
            "light sampling"
        }
    }

    /// k of the reconnected step x_k → x_{k+1}; None for a pure replay.
    pub fn reconnection_step(&self) -> Option<u32> {
        let k = (self.packed() >> 9) & 0xf;
        (k != PT_RC_NONE).then_some(k)
    }

    /// The lobe that sampled each bounce ω_1 … ω_{n-1} (and ω_n for a BSDF end).
    pub fn lobes(&self) -> Vec<&'static str> {
        let lobes = (self.packed() >> 13) & 0x1ff;
        let last = self.length() - u32::from((self.packed() >> 8) & 1 == PT_END_NEE);
        (1..=last)
            .map(|b| {
                if (lobes >> b) & 1 == PT_LOBE_SPECULAR {
                    "specular"
                } else {
                    "diffuse"
                }
            })
            .collect()
    }
}

/// The ReSTIR PT part of an inspection (present when PT ran that frame).
#[derive(Clone, Debug, PartialEq)]
pub struct PtInspection {
    pub debug: GpuPtPixelDebug,
    /// The stages that ran, in order.
    pub stages: Vec<PtStagePath>,
}

impl PtInspection {
    /// The PT part of an inspection: the debug record and the probe's stages, in slot order.
    pub fn decode(debug: &GpuPtPixelDebug, probe: &[GpuPtProbeStage]) -> PtInspection {
        let debug = *debug;
        let stages = PT_STAGE_NAMES
            .iter()
            .zip(probe)
            .filter_map(|(&stage, probe)| {
                (probe.written == 1).then(|| PtStagePath {
                    stage,
                    reservoir: probe.reservoir,
                    vertices: probe.vertices
                        [..(probe.vertex_count as usize).min(probe.vertices.len())]
                        .iter()
                        .map(|v| {
                            let flags = v[3].to_bits();
                            PtVertex {
                                position: [v[0], v[1], v[2]],
                                reconnection: flags & PT_VERTEX_RECONNECTION != 0,
                                light: flags & PT_VERTEX_LIGHT != 0,
                                direction: flags & PT_VERTEX_DIRECTION != 0,
                            }
                        })
                        .collect(),
                })
            })
            .collect();
        PtInspection { debug, stages }
    }

    /// The previous path's shift to this pixel, by name (None: none was tried).
    pub fn temporal_outcome(&self) -> Option<&'static str> {
        PT_FAIL_NAMES
            .get(self.debug.temporal_failure as usize)
            .copied()
    }

    /// The spatial neighbours' shifts to this pixel: (outcome, count) for each outcome seen.
    pub fn spatial_outcomes(&self) -> Vec<(&'static str, u32)> {
        (0..PT_FAIL_REASON_COUNT as u32)
            .map(|f| (PT_FAIL_NAMES[f as usize], self.debug.spatial_count(f)))
            .filter(|&(_, n)| n > 0)
            .collect()
    }
}
