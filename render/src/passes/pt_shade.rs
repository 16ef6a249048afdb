//! ReSTIR PT shading (pt_shade.wgsl): adds the pixel's path, f(x̄) · W, to the frame DI
//! shaded and keeps it alone for the `indirect` view.

use super::gi_initial::INDIRECT;
use super::pass::{Dispatch, PassDef, read, write};
use super::pt_initial::PT_RESERVOIRS;
use super::resources::{ACCUMULATION, RADIANCE, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt shade",
    shader: "pt_shade.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&PT_RESERVOIRS, Role::In)),
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
        write(Pixels(&INDIRECT)),
    ],
    dispatch: Dispatch::Pixels,
};
