//! The tracing backends' throughput (ray_bench.wgsl): a fixed number of shadow or
//! closest-hit rays from every G-buffer surface, timed alone (`Renderer::bench_rays`,
//! `restir-viewer bench-rays`). Not part of any frame.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{PixelBuffer, Resource::*};

/// Per pixel: rays traced (low 16 bits) and rays that hit something (high 16 bits).
/// Allocated the first time the bench runs (frames never name it).
pub const RAY_COUNTS: PixelBuffer = PixelBuffer::full("ray bench counts", 4);

pub const PASS: PassDef = PassDef {
    name: "ray bench",
    shader: "ray_bench.wgsl",
    group: &[read(Surfaces), write(Pixels(&RAY_COUNTS)), read(PassInfo)],
    dispatch: Dispatch::Pixels,
};
