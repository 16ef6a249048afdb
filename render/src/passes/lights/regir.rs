//! ReGIR's fill (lights/regir_fill.wgsl): every slot of every cell around the camera resampled
//! toward its cell's lights, once per frame before the initial pass reads them
//! (docs/src/light-samplers.md, "ReGIR").

use crate::passes::pass::{Dispatch, PassDef, read, write};
use crate::passes::resources::{LightData, Resource::*};
use crate::shader_constants::MAX_REGIR_SLOTS_TOTAL;

pub const FILL: PassDef = PassDef {
    name: "regir fill",
    shader: "lights/regir_fill.wgsl",
    group: &[
        write(Lights(LightData::Presampled)),
        read(Lights(LightData::BvhNodes)),
        read(Lights(LightData::BvhTrails)),
    ],
    // At most this many slots; the step dispatches the frame's cells × slots
    // (`Step::threads`).
    dispatch: Dispatch::Threads {
        invocations: MAX_REGIR_SLOTS_TOTAL,
        // The shader's @workgroup_size.
        workgroup: 64,
    },
};
