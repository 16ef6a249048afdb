//! ReSTIR DI's reuse in plain Rust, on top of the streaming reservoir (`reservoir.rs`), each
//! part checked against exact integrals by its tests: the WGSL under shaders/di/ follows it.

/// One pairwise-MIS reuse step of direct light with the rules of the shaders: which
/// candidates take part, windows and visibility in the targets (docs/src/mis-and-bias.md,
/// "The two rules of unbiased reuse").
pub mod pairwise_reuse;

/// MCMC mutation of a resampled light sample (decorrelation): shaders/di/mutation.wgsl's mirror.
pub mod mcmc;
