// ReSTIR PT's fields of the Params uniform (`params.pt`; the twin of
// render/src/pt/params.rs; docs/src/restir-pt.md): setting `pt_x` is field `x`.
struct PtParams {
    shift: u32,                   // PT_SHIFT_*
    rough_threshold: f32,
    min_distance: f32,            // fraction of frame.scene_scale (bounds diagonal)
    spatial_neighbours: u32,
    spatial_radius: f32,          // pixels of this image
    m_cap: f32,
    jacobian_clamp: f32,          // biased: |J| clamped into [1/c, c]; 0 = off
    _pad0: u32,
}
