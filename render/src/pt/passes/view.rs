//! The ReSTIR PT debug views (pt/view.wgsl), drawn over the display's output when one is
//! selected and PT runs: path length, reconnection depth, shift outcomes, log |J|, and the
//! indirect light alone.

use super::initial::{PT_DEBUG, PT_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::INDIRECT;
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt view",
    shader: "pt/view.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&PT_RESERVOIRS, Role::In)),
        read(Pixels(&PT_DEBUG)),
        read(Pixels(&INDIRECT)),
        read(DisplayUniform),
        write(Output),
    ],
    dispatch: Dispatch::Pixels,
};
