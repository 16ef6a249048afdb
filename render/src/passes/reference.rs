//! The reference renderer (reference.wgsl): ray-traced camera rays, light and BSDF
//! sampling with MIS; writes radiance and adds it to the accumulation. With jitter off it
//! shades the rasterised G-buffer's surfaces instead of tracing its own camera rays.
//! One dispatch per chunk of samples, the chunk picked by its `PassInfo` slot.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{ACCUMULATION, LightData, RADIANCE, Resource::*};

pub const PASS: PassDef = PassDef {
    name: "reference",
    shader: "reference.wgsl",
    group: &[
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
        read(PassInfo),
        read(Surfaces),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    dispatch: Dispatch::Pixels,
};
