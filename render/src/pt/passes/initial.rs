//! ReSTIR PT initial path (pt/initial.wgsl): one path per pixel, its sub-paths (light
//! sampling and BSDF ends at every vertex past the first) the candidates of the pixel's
//! path reservoir. Declares the PT resources the other PT passes share.

use crate::gpu_types::{GpuPtPixelDebug, GpuPtProbeStage, GpuPtReservoir};
use crate::passes::pass::{Binding, Dispatch, PassDef, concat, read, write};
use crate::passes::resources::{Allocation, Chain, LightData, PixelBuffer, Resource::*, Role};
use crate::pt::constants::PT_PROBE_STAGES;

/// ReSTIR PT path reservoirs (their own ping-pong, history kept for PT temporal reuse).
pub const PT_RESERVOIRS: Chain = Chain {
    name: "pt reservoirs",
    stride: std::mem::size_of::<GpuPtReservoir>(),
};
/// Per-pixel PT debug records (shift outcomes, the survivor's |J|, M per stage).
pub const PT_DEBUG: PixelBuffer =
    PixelBuffer::full("pt debug", std::mem::size_of::<GpuPtPixelDebug>());
/// The inspected pixel's path after each PT stage (shaders/pt/probe.wgsl): one record per stage,
/// whatever the image size.
pub const PT_PROBE: PixelBuffer = PixelBuffer {
    name: "pt probe",
    stride: std::mem::size_of::<GpuPtProbeStage>(),
    allocation: Allocation::Fixed(PT_PROBE_STAGES as u64),
};

/// What every PT path pass binds after its inputs: its reservoirs out, its debug records,
/// the inspector's path probe, and the light BVH for the vertex sampler.
pub const PT_OUTPUTS: [Binding; 5] = [
    write(Chain(&PT_RESERVOIRS, Role::Out)),
    write(Pixels(&PT_DEBUG)),
    write(Pixels(&PT_PROBE)),
    read(Lights(LightData::BvhNodes)),
    read(Lights(LightData::BvhTrails)),
];

pub const PASS: PassDef = PassDef {
    name: "pt initial",
    shader: "pt/initial.wgsl",
    group: &concat::<1, 5, 6>([read(Surfaces)], PT_OUTPUTS),
    dispatch: Dispatch::Pixels,
};
