//! Spatial reuse (di/spatial.wgsl): one dispatch per pass, reading the previous pass's
//! reservoirs and writing new ones; the pass index (a `PassInfo` slot) decorrelates the
//! passes' random numbers.

use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{DEBUG, RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "spatial",
    shader: "di/spatial.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&RESERVOIRS, Role::In)),
        write(Chain(&RESERVOIRS, Role::Out)),
        write(Pixels(&DEBUG)),
        read(PassInfo),
    ],
    dispatch: Dispatch::Pixels,
};
