//! ReSTIR GI shading (gi/shade.wgsl): adds f_r · L_o · cos θ · W to the frame DI shaded
//! and keeps it alone for the `indirect` view.

use super::initial::GI_RESERVOIRS;
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::INDIRECT;
use crate::passes::resources::{ACCUMULATION, RADIANCE, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "gi shade",
    shader: "gi/shade.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&GI_RESERVOIRS, Role::In)),
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
        write(Pixels(&INDIRECT)),
    ],
    dispatch: Dispatch::Pixels,
};
