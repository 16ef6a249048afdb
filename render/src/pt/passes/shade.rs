//! ReSTIR PT shading (pt/shade.wgsl): adds the pixel's path, f(x̄) · W, to the frame DI
//! shaded and keeps it alone for the `indirect` view.

use super::initial::PT_RESERVOIRS;
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::INDIRECT;
use crate::passes::resources::{ACCUMULATION, RADIANCE, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt shade",
    shader: "pt/shade.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&PT_RESERVOIRS, Role::In)),
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
        write(Pixels(&INDIRECT)),
    ],
    dispatch: Dispatch::Pixels,
};
