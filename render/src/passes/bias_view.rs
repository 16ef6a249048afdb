//! The `bias` debug view (bias_view.wgsl), drawn over the display's output when selected:
//! the running average's statistics (moments pass) against the uploaded reference.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{MOMENTS, REFERENCE, Resource::*};

pub const PASS: PassDef = PassDef {
    name: "bias view",
    shader: "bias_view.wgsl",
    group: &[
        read(Pixels(&MOMENTS)),
        read(Pixels(&REFERENCE)),
        read(DisplayUniform),
        write(Output),
    ],
    dispatch: Dispatch::Pixels,
};
