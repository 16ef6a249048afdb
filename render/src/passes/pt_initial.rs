//! ReSTIR PT initial path (pt_initial.wgsl): one path per pixel, its sub-paths (light
//! sampling and BSDF ends at every vertex past the first) the candidates of the pixel's
//! path reservoir. Declares the PT reservoirs the other PT passes share.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{Chain, Resource::*, Role};
use crate::gpu_types::GpuPtReservoir;

/// ReSTIR PT path reservoirs (their own ping-pong).
pub const PT_RESERVOIRS: Chain = Chain {
    name: "pt reservoirs",
    stride: std::mem::size_of::<GpuPtReservoir>(),
};

pub const PASS: PassDef = PassDef {
    name: "pt initial",
    shader: "pt_initial.wgsl",
    group: &[read(Surfaces), write(Chain(&PT_RESERVOIRS, Role::Out))],
    dispatch: Dispatch::Pixels,
};
