//! The denoiser, an SVGF-class filter after shading (docs/src/denoiser.md), in one folder:
//! its computation in plain Rust (`model`), pass for pass as the WGSL under
//! `shaders/denoise/` does it, with its tests, and its passes. The folder's files stand on
//! the floors `di/mod.rs` names.

pub mod constants;
pub mod depth_probe;
pub mod model;
pub mod params;
pub mod passes;
pub mod rows;
pub mod settings;

#[cfg(test)]
mod depth_probe_tests;
#[cfg(test)]
mod tests;
