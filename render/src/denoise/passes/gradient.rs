//! The temporal gradient (denoise/gradient.wgsl): DI's temporal pass left each pixel the
//! history's sample shaded last frame and now; this pass sums both over a neighbourhood on
//! the same surfaces and writes the share that changed, λ, for the temporal blend.

use super::GRADIENT;
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{DEBUG, Resource::*};

pub const PASS: PassDef = PassDef {
    name: "denoise gradient",
    shader: "denoise/gradient.wgsl",
    group: &[
        read(Surfaces),
        read(Pixels(&DEBUG)),
        write(Pixels(&GRADIENT)),
    ],
    dispatch: Dispatch::Pixels,
};
