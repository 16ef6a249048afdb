//! The temporal window (temporal_window.wgsl): each pixel's luminance over the last
//! `TEMPORAL_WINDOW_FRAMES` frames and in which of them its survivor's light changed, for
//! the boiling and survivor-change views (`window_view.rs` draws them). It runs only
//! while one of those views is shown, after the frame's radiance is final.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{PixelBuffer, RADIANCE, RESERVOIRS, Resource::*, Role};
use crate::gpu_types::GpuWindowPixel;

/// One `GpuWindowPixel` per pixel, allocated the first time a window view is shown and
/// cleared whenever the window restarts (renderer/window.rs).
pub const WINDOW: PixelBuffer =
    PixelBuffer::full("temporal window", std::mem::size_of::<GpuWindowPixel>());

/// `PassInfo` slot of a real-time frame (its reservoirs hold this frame's survivors); a
/// reference frame uses slot 0 and records no survivor change.
pub const REALTIME_SLOT: u32 = 1;

pub const PASS: PassDef = PassDef {
    name: "temporal window",
    shader: "temporal_window.wgsl",
    group: &[
        read(Pixels(&RADIANCE)),
        read(Chain(&RESERVOIRS, Role::In)),
        read(PassInfo),
        write(Pixels(&WINDOW)),
    ],
    dispatch: Dispatch::Pixels,
};
