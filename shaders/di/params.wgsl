// ReSTIR DI's fields of the Params uniform (`params.di`; the twin of
// render/src/di/params.rs). Names are the settings table's.
struct DiParams {
    light_candidates: u32,
    bsdf_candidates: u32,
    m_cap: f32,
    target_ratio_clamp: f32,      // 0 = test off
    spatial_neighbours: u32,
    spatial_radius: f32,          // pixels of this image
    boiling_filter: f32,          // 0 = off
    // MCMC mutation of DI's samples (docs/src/mcmc-mutation.md)
    mutations: u32,               // steps per pixel (0 = off)
    mutation_step: f32,           // largest local slide, barycentric units
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}
