//! The running average's per-pixel statistics (moments.wgsl) for the `bias` view: the
//! luminance sum and batch means of the frames since the accumulation restarted.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{MOMENTS, RADIANCE, Resource::*};

pub const PASS: PassDef = PassDef {
    name: "moments",
    shader: "moments.wgsl",
    group: &[read(Pixels(&RADIANCE)), write(Pixels(&MOMENTS))],
    dispatch: Dispatch::Pixels,
};
