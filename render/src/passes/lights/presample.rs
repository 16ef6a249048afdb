//! Light tiles (lights/presample_lights.wgsl): power-sampled lights packed into tiles once per
//! frame, before the initial pass reads them.

use crate::passes::pass::{Dispatch, PassDef, write};
use crate::passes::resources::{LightData, Resource::*};
use crate::shader_constants::{LIGHT_TILE_COUNT, LIGHT_TILE_SIZE};

pub const PASS: PassDef = PassDef {
    name: "presample lights",
    shader: "lights/presample_lights.wgsl",
    group: &[write(Lights(LightData::Presampled))],
    dispatch: Dispatch::Threads {
        invocations: LIGHT_TILE_COUNT * LIGHT_TILE_SIZE,
        // The shader's @workgroup_size.
        workgroup: 64,
    },
};
