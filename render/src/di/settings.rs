//! What ReSTIR DI makes of the settings: its fields of the `Params` uniform and its
//! `PARAM_FLAG_*` bits (its rows are in `rows.rs`, its fields' struct in `params.rs`).

use super::constants::*;
use super::params::GpuDiParams;
use crate::settings::{BiasCorrection, Settings, flag_bits};
use crate::shader_constants::{MAX_MUTATIONS, MAX_SPATIAL_NEIGHBOURS};

/// DI's fields for an image `height` pixels high (pixel-unit parameters follow the height).
pub fn gpu_params(s: &Settings, height: u32) -> GpuDiParams {
    GpuDiParams {
        light_candidates: s.light_candidates,
        bsdf_candidates: s.bsdf_candidates,
        m_cap: s.m_cap,
        target_ratio_clamp: if s.check_target_ratio {
            s.target_ratio_clamp
        } else {
            0.0
        },
        spatial_neighbours: s.spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS),
        spatial_radius: s.effective_spatial_radius(height),
        boiling_filter: s.boiling_filter,
        mutations: s.mutations.min(MAX_MUTATIONS),
        mutation_step: s.mutation_step,
        _pad: [0; 3],
    }
}

/// DI's bits of `GpuParams::flags`. The gradient-only mode is DI's temporal pass running
/// for the denoiser's gradients alone (docs/src/denoiser.md).
pub fn flags(s: &Settings) -> u32 {
    flag_bits(&[
        (s.permutation, PARAM_FLAG_PERMUTATION),
        (
            s.bias_correction == BiasCorrection::Pairwise,
            PARAM_FLAG_PAIRWISE,
        ),
        (s.visibility_in_target(), PARAM_FLAG_MIS_VISIBILITY),
        (s.traces_initial_visibility(), PARAM_FLAG_INITIAL_VISIBILITY),
        (s.previous_lights, PARAM_FLAG_PREVIOUS_LIGHTS),
        (s.previous_geometry, PARAM_FLAG_PREVIOUS_GEOMETRY),
        (
            s.denoise_gradients_on() && !s.temporal,
            PARAM_FLAG_GRADIENT_ONLY,
        ),
    ])
}
