//! The display pass (display.wgsl): tonemapped image or a debug view into an RGBA8
//! storage texture that the viewer shows and PNG export reads.

use super::pass::{Dispatch, PassDef, read, write};
use super::resources::{COMPARISON, DEBUG, REFERENCE, RESERVOIRS, Resource::*, Role};

pub const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

pub const PASS: PassDef = PassDef {
    name: "display",
    shader: "display.wgsl",
    group: &[
        read(ShownImage),
        read(Surfaces),
        read(Pixels(&DEBUG)),
        read(Chain(&RESERVOIRS, Role::In)),
        read(Pixels(&REFERENCE)),
        read(DisplayUniform),
        write(Output),
        read(Pixels(&COMPARISON)),
    ],
    dispatch: Dispatch::Pixels,
};
