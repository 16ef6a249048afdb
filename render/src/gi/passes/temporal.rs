//! ReSTIR GI temporal reuse (gi/temporal.wgsl): reprojection, validation, the
//! reconnection Jacobian from the previous visible point, 1/M or pairwise merge.

use super::initial::{GI_DEBUG, GI_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "gi temporal",
    shader: "gi/temporal.wgsl",
    group: &[
        read(Surfaces),
        read(PrevSurfaces),
        read(Chain(&GI_RESERVOIRS, Role::In)),
        read(Chain(&GI_RESERVOIRS, Role::History)),
        write(Chain(&GI_RESERVOIRS, Role::Out)),
        write(Pixels(&GI_DEBUG)),
    ],
    dispatch: Dispatch::Pixels,
};
