//! What ReSTIR GI makes of the settings: its fields of the `Params` uniform and its
//! `PARAM_FLAG_GI_*` bits (its rows are in `rows.rs`, its fields' struct in `params.rs`).

use super::constants::*;
use super::params::GpuGiParams;
use crate::settings::{BiasCorrection, Settings, flag_bits};
use crate::shader_constants::MAX_SPATIAL_NEIGHBOURS;

/// GI's fields for an image `height` pixels high (pixel-unit parameters follow the height).
pub fn gpu_params(s: &Settings, height: u32) -> GpuGiParams {
    GpuGiParams {
        m_cap: s.gi_m_cap,
        spatial_neighbours: s.gi_spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS),
        spatial_radius: s.effective_gi_spatial_radius(height),
        jacobian_max: s.gi_jacobian_max.max(1.0),
        // 0: DI's count.
        light_candidates: if s.gi_light_candidates == 0 {
            s.light_candidates
        } else {
            s.gi_light_candidates
        },
        _pad: [0; 3],
    }
}

/// The Indirect stage's `PARAM_FLAG_GI_*` bits of `GpuParams::flags`.
pub fn flags(s: &Settings) -> u32 {
    flag_bits(&[
        (s.gi, PARAM_FLAG_GI),
        (s.gi_temporal, PARAM_FLAG_GI_TEMPORAL),
        (s.gi_spatial, PARAM_FLAG_GI_SPATIAL),
        (s.gi_spatial_visibility, PARAM_FLAG_GI_SPATIAL_VISIBILITY),
        (s.gi_mis_visibility, PARAM_FLAG_GI_MIS_VISIBILITY),
        (
            s.gi_bias_correction == BiasCorrection::Pairwise,
            PARAM_FLAG_GI_PAIRWISE,
        ),
    ])
}
