//! The ReSTIR lab renderer: glTF and built-in scenes, a CPU-built BVH (or hardware ray
//! queries), and a wgpu ReSTIR pipeline: direct light by ReSTIR DI (G-buffer → initial RIS →
//! temporal → spatial → shade), indirect light by ReSTIR GI (one bounce, its own reservoirs)
//! or by ReSTIR PT (multi-bounce path reuse), with a brute-force (multi-bounce) reference,
//! debug buffers and metrics (docs/src/frame.md walks the frame pass by pass). Usable
//! headless; the viewer drives it too.

#[macro_use]
pub mod wgsl_constants;
pub mod alias;
pub mod denoise;
pub mod di;
pub mod effects;
pub mod environment;
pub mod flicker;
pub mod fnv;
pub mod frame_targets;
pub mod gi;
pub mod gpu;
pub mod gpu_scene;
pub mod gpu_types;
pub mod image;
pub mod light_bvh;
pub mod light_probe;
pub mod light_sampler;
pub mod load_phases;
pub mod metrics;
pub mod passes;
pub mod phase_references;
pub mod planted;
pub mod pt;
pub mod reference_cache;
pub mod renderer;
pub mod reservoir;
pub mod scene;
pub mod settings;
pub mod shader_constants;
pub mod shader_source;
mod test_hash;
pub mod timeline;
pub mod tracing;
pub mod view;

/// What a frame reports (counters, pass times, the inspected pixel): the renderer's output,
/// also at the crate root, where the app and the tests read it.
pub use renderer::stats;

pub use environment::{Environment, load_environment};
pub use gpu::{Gpu, GpuError};
pub use image::LinearImage;
pub use renderer::{PipelineCompile, PreparedScene, Renderer, ScenePreparer};
pub use scene::{Camera, Scene, load_scene, load_scene_watched};
pub use settings::Settings;
pub use view::{DebugView, Mode, Tonemapper, ViewSettings};
