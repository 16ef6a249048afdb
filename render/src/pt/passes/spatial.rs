//! ReSTIR PT spatial reuse (pt/spatial.wgsl): neighbours' paths shifted here by the chosen
//! shift mapping, merged under pairwise MIS.

use super::initial::{PT_OUTPUTS, PT_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, concat, read};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt spatial",
    shader: "pt/spatial.wgsl",
    group: &concat::<2, 5, 7>(
        [read(Surfaces), read(Chain(&PT_RESERVOIRS, Role::In))],
        PT_OUTPUTS,
    ),
    dispatch: Dispatch::Pixels,
};
