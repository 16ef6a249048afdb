//! MCMC mutation of DI's samples (mutation.wgsl; docs/src/mcmc-mutation.md): after the
//! last reuse pass, a few Metropolis–Hastings steps move each pixel's light sample toward
//! its own target, and W follows, so neighbours and frames stop sharing one sample.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{RESERVOIRS, Resource::*, Role};

pub const PASS: PassDef = PassDef {
    name: "mutation",
    shader: "mutation.wgsl",
    group: &[
        read(Surfaces),
        read(Chain(&RESERVOIRS, Role::In)),
        write(Chain(&RESERVOIRS, Role::Out)),
    ],
    dispatch: Dispatch::Pixels,
};
