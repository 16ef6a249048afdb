//! Path reuse (ReSTIR PT; GRIS, Lin et al. 2022) in plain Rust: paths, the three shift mappings
//! that move a path found at one pixel to another, their Jacobians, and one pairwise-MIS reuse step
//! over them, checked against exact integrals and finite differences (docs/src/restir-pt.md, "The
//! CPU model"). The WGSL passes are to mirror this module the way `shaders/common/reservoir.wgsl`
//! mirrors `reservoir.rs`.
//!
//! # Paths and their measure
//! A path starts at a pixel's primary surface `x_1` (the G-buffer's point) and bounces
//! `n` times, `x_1 → x_2 → … → x_{n+1}`, ending on an emitter. Its coordinates are the
//! directions sampled at each bounce, `ω_b = dir(x_b → x_{b+1})`, so its measure is the
//! product of solid angles and its contribution
//!
//! ```text
//! f(x̄) = L_e(x_{n+1} → x_n) · Π_b f_s(x_b; ω_in,b, ω_b) · |n_b · ω_b|
//! ```
//!
//! The random numbers each bounce drew (`u_b`, two per bounce) travel with the path:
//! random replay reuses them.
//!
//! # Shift mappings (`shift.rs`)
//! - **Reconnection**: keep `x_2 … x_{n+1}`, connect the new primary `y_1` to `x_2`.
//!   `|J| = (|cos θ_2'| / |y_1 − x_2|²) / (|cos θ_2| / |x_1 − x_2|²)`, the GI reconnection
//!   Jacobian. Poor where `x_2` (or `x_1`) is glossy: the new angle misses its lobe.
//! - **Random replay**: trace from `y_1` with the same random numbers.
//!   `|J| = Π_b p(ω_b | x_b) / p(ω'_b | y_b)` (each direction is its lobe's inverse CDF of the
//!   same numbers). Fails when the replayed path does not end on an emitter at the same
//!   bounce.
//! - **Hybrid**: replay up to the first bounce `k` whose two ends are both rough (roughness
//!   ≥ `rough_threshold`) and at least `min_distance` apart, then reconnect `y_k → x_{k+1}`;
//!   pure replay when there is no such bounce. The shifted path must reconnect at the same
//!   `k` (checked), which keeps the shift a bijection.
//!
//! A shift that cannot be made is a zero-target domain in the MIS (`pairwise.rs`): its
//! neighbour still counts in the confidence sum and its term is still there, with target 0.

pub mod experiment;
pub mod lobe;
pub mod pairwise;
pub mod path;
pub mod shift;
pub mod toy_scene;

#[cfg(test)]
mod fixtures;
#[cfg(test)]
mod jacobian_tests;
#[cfg(test)]
mod shift_tests;
#[cfg(test)]
mod unbiased_tests;
