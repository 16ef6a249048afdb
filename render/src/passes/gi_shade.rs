//! ReSTIR GI shading (gi_shade.wgsl): adds f_r · L_o · cos θ · W to the frame DI shaded
//! and keeps it alone for the `indirect` view.

use super::gi_initial::{GI_RESERVOIRS, INDIRECT};
use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{ACCUMULATION, RADIANCE, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "gi shade",
    shader: "gi_shade.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&GI_RESERVOIRS, Role::In)),
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
        write(Pixels(&INDIRECT)),
    ],
    dispatch: Dispatch::Pixels,
};
