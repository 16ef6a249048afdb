//! The variance estimate (denoise/variance.wgsl): from the temporal moments, or from the
//! neighbourhood where the history is short.

use super::{FILTERED, HISTORY};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "denoise variance",
    shader: "denoise/variance.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&HISTORY, Role::In)),
        write(Chain(&FILTERED, Role::Out)),
    ],
    dispatch: Dispatch::Pixels,
};
