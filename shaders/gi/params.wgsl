// ReSTIR GI's fields of the Params uniform (`params.gi`; the twin of
// render/src/gi/params.rs): setting `gi_x` is field `x`. Its switches are the
// PARAM_FLAG_GI_* bits of `params.flags`.
struct GiParams {
    m_cap: f32,
    spatial_neighbours: u32,
    spatial_radius: f32,          // pixels of this image
    jacobian_max: f32,            // window [1/max, max]
    light_candidates: u32,        // RIS candidates at GI's secondary vertex
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}
