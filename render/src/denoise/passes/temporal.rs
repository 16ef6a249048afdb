//! Temporal accumulation (denoise/temporal.wgsl): this frame's demodulated illumination
//! blended into last frame's, reprojected through the motion vectors.

use super::{GRADIENT, HISTORY};
use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{RADIANCE, Resource::*, Role};

/// `PassInfo` slot of a frame whose history is valid (slot 0: start afresh).
pub use crate::denoise::constants::DENOISE_HISTORY_SLOT as WITH_HISTORY_SLOT;

pub const PASS: PassDef = PassDef {
    name: "denoise temporal",
    shader: "denoise/temporal.wgsl",
    group: &[
        read(Surfaces),
        read(PrevSurfaces),
        read(Pixels(&RADIANCE)),
        read(Chain(&HISTORY, Role::History)),
        read(PassInfo),
        read(Pixels(&GRADIENT)),
        write(Chain(&HISTORY, Role::Out)),
    ],
    dispatch: Dispatch::Pixels,
};
