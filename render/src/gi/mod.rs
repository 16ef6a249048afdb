//! ReSTIR GI, one-bounce indirect light with reservoir reuse through the reconnection
//! Jacobian (docs/src/restir-gi.md), in one folder: its CPU model (the GI reservoir, its
//! target, merges, one reuse step and the Jacobian) and its passes (shaders under
//! shaders/gi/). The folder's files stand on the floors `di/mod.rs` names.

pub mod constants;
pub mod model;
pub mod params;
pub mod passes;
pub mod rows;
pub mod settings;
