//! Temporal reuse (temporal.wgsl): reprojection, validation with a rejection mask,
//! target re-evaluation and the merge with the previous frame's reservoir.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{DEBUG, RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "temporal",
    shader: "temporal.wgsl",
    group: &[
        read(Surfaces),
        read(PrevSurfaces),
        read(Chain(&RESERVOIRS, Role::In)),
        read(Chain(&RESERVOIRS, Role::History)),
        write(Chain(&RESERVOIRS, Role::Out)),
        write(Pixels(&DEBUG)),
    ],
    dispatch: Dispatch::Pixels,
};
