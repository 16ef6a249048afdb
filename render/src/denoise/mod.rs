//! The denoiser's computation in plain Rust (`model`), pass for pass as the WGSL under
//! `shaders/denoise/` does it, and its tests. The passes themselves are declared in
//! `passes::denoise` (docs/src/denoiser.md).

pub mod model;

#[cfg(test)]
mod tests;
