//! ReSTIR DI's passes: direct light by reservoir resampling (docs/src/ris.md,
//! docs/src/temporal-reuse.md, docs/src/spatial-reuse.md, docs/src/mcmc-mutation.md). Each module
//! owns its shader (shaders/di/) and the declaration of its bindings; the reservoirs they
//! share are declared with the frame's other buffers (`resources`).

pub mod initial;
pub mod mutation;
pub mod shade;
pub mod spatial;
pub mod temporal;
