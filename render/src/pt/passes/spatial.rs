//! ReSTIR PT spatial reuse (pt/spatial.wgsl): neighbours' paths shifted here by the chosen
//! shift mapping, merged under pairwise MIS.

use super::initial::{PT_DEBUG, PT_PROBE, PT_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{LightData, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt spatial",
    shader: "pt/spatial.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&PT_RESERVOIRS, Role::In)),
        write(Chain(&PT_RESERVOIRS, Role::Out)),
        write(Pixels(&PT_DEBUG)),
        write(Pixels(&PT_PROBE)),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    dispatch: Dispatch::Pixels,
};
