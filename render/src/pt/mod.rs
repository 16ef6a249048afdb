//! ReSTIR PT, multi-bounce path reuse (GRIS, Lin et al. 2022; docs/src/restir-pt.md), in one
//! folder: its CPU model (paths, the three shifts and their Jacobians, pairwise MIS on a toy
//! scene) and its passes (shaders under shaders/pt/). The folder's files stand on the floors
//! `di/mod.rs` names.

pub mod constants;
pub mod model;
pub mod params;
pub mod passes;
pub mod rows;
pub mod settings;
