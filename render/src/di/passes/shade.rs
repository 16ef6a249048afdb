//! Final shading (di/shade.wgsl): one shadow ray for the survivor plus emission; writes the
//! frame's radiance and adds it to the accumulation.

use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{ACCUMULATION, DEBUG, RADIANCE, RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "shade",
    shader: "di/shade.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&RESERVOIRS, Role::In)),
        write(Pixels(&DEBUG)),
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
    ],
    dispatch: Dispatch::Pixels,
};
