//! The ReSTIR GI debug views (gi_view.wgsl), drawn over the display's output when one
//! is selected and GI runs.

use super::gi_initial::{GI_DEBUG, GI_RESERVOIRS, INDIRECT};
use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "gi view",
    shader: "gi_view.wgsl",
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
