//! ReSTIR GI's passes: one-bounce indirect light with reservoir reuse through the reconnection Jacobian (docs/src/restir-gi.md). Each module owns its shader (shaders/gi/) and the
//! declaration of its bindings; `initial` also declares the buffers the family shares.

pub mod initial;
pub mod shade;
pub mod spatial;
pub mod temporal;
pub mod view;
