//! ReSTIR DI, direct light by reservoir resampling (docs/src/ris.md,
//! docs/src/temporal-reuse.md, docs/src/spatial-reuse.md, docs/src/mcmc-mutation.md), in one
//! folder: its CPU model and its passes (whose shaders are under shaders/di/). The streaming
//! reservoir all three techniques build on is `reservoir.rs`, below them.
//!
//! A technique folder holds one file or folder per floor of docs/src/source-layout.md
//! ("Layers"), the same names in `di/`, `gi/`, `pt/` and `denoise/`: `model` is a CPU model,
//! `passes` stands with the frame's other passes.

pub mod constants;
pub mod model;
pub mod params;
pub mod passes;
pub mod rows;
pub mod settings;
