//! ReSTIR PT's passes: multi-bounce indirect light with path reuse through shift mappings (docs/src/restir-pt.md). Each module owns its shader (shaders/pt/) and the
//! declaration of its bindings; `initial` also declares the buffers the family shares.

pub mod initial;
pub mod shade;
pub mod spatial;
pub mod temporal;
pub mod view;
