//! What ReSTIR PT makes of the settings: its fields of the `Params` uniform (its rows are
//! in `rows.rs`, its fields' struct in `params.rs`). Its switch is the settings' `pt`, read
//! on the host: PT has no `Params.flags` bits.

use super::params::GpuPtParams;
use crate::settings::Settings;
use crate::shader_constants::MAX_SPATIAL_NEIGHBOURS;

/// PT's fields for an image `height` pixels high (pixel-unit parameters follow the height).
pub fn gpu_params(s: &Settings, height: u32) -> GpuPtParams {
    GpuPtParams {
        shift: s.pt_shift.gpu(),
        rough_threshold: s.pt_rough_threshold,
        min_distance: s.pt_min_distance,
        spatial_neighbours: s.pt_spatial_neighbours.min(MAX_SPATIAL_NEIGHBOURS),
        spatial_radius: s.effective_pt_spatial_radius(height),
        m_cap: s.pt_m_cap,
        // Off at 0; otherwise a window [1/c, c] with c ≥ 1.
        jacobian_clamp: if s.pt_jacobian_clamp > 0.0 {
            s.pt_jacobian_clamp.max(1.0)
        } else {
            0.0
        },
        _pad: 0,
    }
}
