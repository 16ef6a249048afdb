//! Initial RIS candidates (di/initial.wgsl): surfaces → reservoir (M = 1) + debug record.

use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{DEBUG, LightData, RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "initial",
    shader: "di/initial.wgsl",
    group: &[
        read(Surfaces),
        write(Chain(&RESERVOIRS, Role::Out)),
        write(Pixels(&DEBUG)),
        read(Lights(LightData::Presampled)),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    dispatch: Dispatch::Pixels,
};
