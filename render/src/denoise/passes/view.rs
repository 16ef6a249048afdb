//! The denoiser's debug views (denoise/view.wgsl), drawn over the display's output when
//! one is selected and the denoiser runs.

use super::{GRADIENT, HISTORY, INPUT};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "denoise view",
    shader: "denoise/view.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&HISTORY, Role::In)),
        read(Pixels(&INPUT)),
        read(Pixels(&GRADIENT)),
        read(DisplayUniform),
        write(Output),
    ],
    dispatch: Dispatch::Pixels,
};
