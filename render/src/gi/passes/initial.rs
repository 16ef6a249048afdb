//! ReSTIR GI initial sample (gi/initial.wgsl): one BSDF ray from the primary hit, the
//! secondary hit's outgoing direct light by light RIS + one shadow ray. Declares the GI
//! resources the other GI passes share.

use crate::gpu_types::{GpuGiPixelDebug, GpuGiReservoir};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{Chain, LightData, PixelBuffer, Resource::*, Role};

/// ReSTIR GI reservoirs (their own ping-pong, history kept for GI temporal reuse).
pub const GI_RESERVOIRS: Chain = Chain {
    name: "gi reservoirs",
    stride: std::mem::size_of::<GpuGiReservoir>(),
};
/// Per-pixel GI debug records (masks, Jacobian, M per stage).
pub const GI_DEBUG: PixelBuffer =
    PixelBuffer::full("gi debug", std::mem::size_of::<GpuGiPixelDebug>());

pub const PASS: PassDef = PassDef {
    name: "gi initial",
    shader: "gi/initial.wgsl",
    group: &[
        read(Surfaces),
        write(Chain(&GI_RESERVOIRS, Role::Out)),
        write(Pixels(&GI_DEBUG)),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    dispatch: Dispatch::Pixels,
};
