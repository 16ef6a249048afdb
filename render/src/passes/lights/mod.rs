//! The light samplers' per-frame passes (docs/src/light-samplers.md): the light tiles drawn
//! from the power table, and ReGIR's grid filled around the camera. They feed DI's
//! candidates and the sampler at GI, PT and reference vertices alike, so they stand beside
//! the techniques rather than in one. Each owns its shader (shaders/lights/).

pub mod presample;
pub mod regir;
