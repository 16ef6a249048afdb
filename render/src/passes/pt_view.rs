//! The ReSTIR PT debug views (pt_view.wgsl), drawn over the display's output when one is
//! selected and PT runs: path length, reconnection depth, shift outcomes, log |J|, and the
//! indirect light alone.

use super::gi_initial::INDIRECT;
use super::pass::{Dispatch, PassDef, read, write};
use super::pt_initial::{PT_DEBUG, PT_RESERVOIRS};
use super::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt view",
    shader: "pt_view.wgsl",
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
