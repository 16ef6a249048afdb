//! Remodulation (denoise/modulate.wgsl): the filtered illumination times the surface
//! colour, plus emission, in place of the frame's radiance; the running average follows.

use super::{FILTERED, INPUT};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{ACCUMULATION, RADIANCE, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "denoise modulate",
    shader: "denoise/modulate.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&FILTERED, Role::In)),
        write(Pixels(&RADIANCE)),
        write(Pixels(&ACCUMULATION)),
        write(Pixels(&INPUT)),
    ],
    dispatch: Dispatch::Pixels,
};
