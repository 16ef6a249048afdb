//! What a pass binds, by name. Per-pixel buffers and reservoir chains are declared as
//! constants (the common ones here; a pass that adds its own declares them next to its
//! shader), so a pass module names what it reads and writes and `FrameTargets` allocates
//! whatever a frame's plan names.

use crate::gpu_types::{GpuPixelDebug, GpuReservoir};

/// How much of a per-pixel buffer exists before a frame asks for it at full size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Allocation {
    /// Full size from the start.
    Full,
    /// A 16-byte placeholder until `FrameTargets::ensure_full` (the comparison image:
    /// 16 bytes per pixel that only a split screen needs).
    Placeholder,
    /// This many records of `stride` bytes, whatever the image size (the PT path probe).
    Fixed(u64),
}

/// One buffer of `stride` bytes per pixel.
#[derive(Debug)]
pub struct PixelBuffer {
    pub name: &'static str,
    pub stride: usize,
    pub allocation: Allocation,
}

impl PixelBuffer {
    /// A buffer of `stride` bytes per pixel, allocated at the output's size.
    pub const fn full(name: &'static str, stride: usize) -> PixelBuffer {
        PixelBuffer {
            name,
            stride,
            allocation: Allocation::Full,
        }
    }

    /// A one-element placeholder until something fills it (`Allocation::Placeholder`).
    pub const fn placeholder(name: &'static str, stride: usize) -> PixelBuffer {
        PixelBuffer {
            name,
            stride,
            allocation: Allocation::Placeholder,
        }
    }
}

/// Per-pixel buffers handed from stage to stage (docs/src/frame.md, "History between frames":
/// ping-pong). A stage reads
/// the chain's current buffer (`Role::In`), last frame's final one (`Role::History`),
/// and writes a buffer neither occupies (`Role::Out`), which becomes the current one.
#[derive(Debug)]
pub struct Chain {
    pub name: &'static str,
    pub stride: usize,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    In,
    Out,
    History,
}

#[derive(Clone, Copy, Debug)]
pub enum Resource {
    /// This frame's G-buffer surfaces.
    Surfaces,
    /// Last frame's surfaces (a second buffer, allocated the first time one is read).
    PrevSurfaces,
    Pixels(&'static PixelBuffer),
    Chain(&'static Chain, Role),
    /// What the display shows: this frame's radiance or the running average.
    ShownImage,
    /// A `PassInfo` slot picked by dynamic offset (spatial pass index, reference chunk).
    PassInfo,
    DisplayUniform,
    /// A light sampler's data (owned by the renderer, `light_sampler.rs`).
    Lights(LightData),
    /// The rasterised visibility buffer (triangle id + barycentrics), sampled as a texture.
    Visibility,
    /// The display's RGBA8 output, a write-only storage texture.
    Output,
}

/// The light samplers' buffers (docs/src/light-samplers.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LightData {
    /// Presampled lights: the light tiles or ReGIR's cells of slots (never both in a frame).
    Presampled,
    /// The light BVH's nodes and its per-light trails.
    BvhNodes,
    BvhTrails,
}

impl LightData {
    /// The record size of the buffer (`GpuPresampledLight`, `GpuLightBvhNode`, ...).
    pub fn stride(self) -> usize {
        use crate::gpu_types::*;
        match self {
            LightData::Presampled => std::mem::size_of::<GpuPresampledLight>(),
            LightData::BvhNodes => std::mem::size_of::<GpuLightBvhNode>(),
            LightData::BvhTrails => std::mem::size_of::<GpuLightBvhTrail>(),
        }
    }
}

pub const DEBUG: PixelBuffer =
    PixelBuffer::full("pixel debug", std::mem::size_of::<GpuPixelDebug>());
pub const RADIANCE: PixelBuffer = PixelBuffer::full("radiance", 16);
pub const ACCUMULATION: PixelBuffer = PixelBuffer::full("accumulation", 16);
/// This frame's indirect radiance alone, whichever technique made it (ReSTIR GI or PT;
/// the `indirect` view).
pub const INDIRECT: PixelBuffer = PixelBuffer::full("indirect", 16);
/// A reference image for the error view (zeros until one is uploaded).
pub const REFERENCE: PixelBuffer = PixelBuffer::full("reference", 16);
/// The other side of a split-screen comparison, for the difference view.
pub const COMPARISON: PixelBuffer = PixelBuffer::placeholder("comparison", 16);
/// The running average's luminance statistics for the bias view (moments.wgsl), cleared
/// with the accumulation.
pub const MOMENTS: PixelBuffer = PixelBuffer::full("moments", 16);
/// The buffers every frame has from the start (readbacks and uploads may come first).
pub const STANDARD: [&PixelBuffer; 6] = [
    &DEBUG,
    &RADIANCE,
    &ACCUMULATION,
    &MOMENTS,
    &REFERENCE,
    &COMPARISON,
];

/// ReSTIR DI reservoirs.
pub const RESERVOIRS: Chain = Chain {
    name: "reservoirs",
    stride: std::mem::size_of::<GpuReservoir>(),
};
