//! ReSTIR GI spatial reuse (gi/spatial.wgsl): neighbours shifted with the reconnection
//! Jacobian, reconnection visibility (switchable), 1/M or pairwise merge.

use super::initial::{GI_DEBUG, GI_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "gi spatial",
    shader: "gi/spatial.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&GI_RESERVOIRS, Role::In)),
        write(Chain(&GI_RESERVOIRS, Role::Out)),
        write(Pixels(&GI_DEBUG)),
    ],
    dispatch: Dispatch::Pixels,
};
