//! One à-trous iteration (denoise/atrous.wgsl); the `PassInfo` slot is the iteration, its
//! taps 2^slot pixels apart.

use super::FILTERED;
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "denoise atrous",
    shader: "denoise/atrous.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&FILTERED, Role::In)),
        read(PassInfo),
        write(Chain(&FILTERED, Role::Out)),
    ],
    dispatch: Dispatch::Pixels,
};
