//! Temporal reuse (di/temporal.wgsl): reprojection, validation with a rejection mask,
//! target re-evaluation and the merge with the previous frame's reservoir.

use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{DEBUG, RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "temporal",
    shader: "di/temporal.wgsl",
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
