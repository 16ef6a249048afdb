//! MCMC mutation of DI's samples (di/mutation.wgsl; docs/src/mcmc-mutation.md): after the
//! last reuse pass, a few Metropolis–Hastings steps move each pixel's light sample toward
//! its own target, and W follows, so neighbours and frames stop sharing one sample.

use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "mutation",
    shader: "di/mutation.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&RESERVOIRS, Role::In)),
        write(Chain(&RESERVOIRS, Role::Out)),
    ],
    dispatch: Dispatch::Pixels,
};
