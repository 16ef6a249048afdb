//! ReSTIR PT temporal reuse (pt/temporal.wgsl): reprojection and G-buffer validation, the
//! previous pixel's path shifted here and this pixel's path shifted back, merged under
//! pairwise MIS with the history's confidence capped at `pt_m_cap`.

use super::initial::{PT_OUTPUTS, PT_RESERVOIRS};
use crate::passes::pass::{Dispatch, PassDef, concat, read};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "pt temporal",
    shader: "pt/temporal.wgsl",
    group: &concat::<4, 5, 9>(
        [
            read(Surfaces),
            read(PrevSurfaces),
            read(Chain(&PT_RESERVOIRS, Role::In)),
            read(Chain(&PT_RESERVOIRS, Role::History)),
        ],
        PT_OUTPUTS,
    ),
    dispatch: Dispatch::Pixels,
};
