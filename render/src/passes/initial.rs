//! Initial RIS candidates (initial.wgsl): surfaces → reservoir (M = 1) + debug record.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{DEBUG, RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "initial",
    shader: "initial.wgsl",
    group: &[
        read(Surfaces),
        write(Chain(&RESERVOIRS, Role::Out)),
        write(Pixels(&DEBUG)),
        read(LightTiles),
    ],
    dispatch: Dispatch::Pixels,
};
