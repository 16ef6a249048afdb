//! The ReSTIR GI debug views (gi/view.wgsl), drawn over the display's output when one
//! is selected and GI runs.

use super::initial::{GI_DEBUG, GI_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::INDIRECT;
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "gi view",
    shader: "gi/view.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&GI_RESERVOIRS, Role::In)),
        read(Pixels(&GI_DEBUG)),
        read(Pixels(&INDIRECT)),
        read(DisplayUniform),
        write(Output),
    ],
    dispatch: Dispatch::Pixels,
};
