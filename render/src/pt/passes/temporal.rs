//! ReSTIR PT temporal reuse (pt/temporal.wgsl): reprojection and G-buffer validation, the
//! previous pixel's path shifted here and this pixel's path shifted back, merged under
//! pairwise MIS with the history's confidence capped at `pt_m_cap`.

use super::initial::{PT_DEBUG, PT_PROBE, PT_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{LightData, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt temporal",
    shader: "pt/temporal.wgsl",
    group: &[
        read(Surfaces),
        read(PrevSurfaces),
        read(Chain(&PT_RESERVOIRS, Role::In)),
        read(Chain(&PT_RESERVOIRS, Role::History)),
        write(Chain(&PT_RESERVOIRS, Role::Out)),
        write(Pixels(&PT_DEBUG)),
        write(Pixels(&PT_PROBE)),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    dispatch: Dispatch::Pixels,
};
