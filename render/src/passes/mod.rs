//! The passes of a frame, one module each: a module owns its shader's name, what each of
//! its group-2 bindings reads or writes (a `PassDef`), and anything only it needs (the
//! raster pipeline, an output format). Layouts, bind groups and dispatches follow from the
//! declaration (`compile.rs`, `renderer/bind_groups.rs`); the order they run in is the
//! frame plan (`renderer/frame_plan.rs`). Groups 0 (frame) and 1 (scene) are shared.

pub mod compile;
pub mod pass;
pub mod resources;

pub mod bias_view;
pub mod denoise;
pub mod di;
pub mod display;
pub mod gbuffer;
pub mod gi;
pub mod lights;
pub mod moments;
pub mod pt;
pub mod ray_bench;
pub mod reference;
pub mod temporal_window;
pub mod window_view;

pub use compile::{
    ComputePass, PASS_INFO_SLOTS, PASS_INFO_STRIDE, PassLayouts, WORKGROUP, buffer_bind_group,
    buffer_entries, shader_module, storage, uniform,
};
pub use pass::PassDef;

/// Every pass, in pipeline order (a layout is created for each; tests validate each).
pub const ALL: [&PassDef; 32] = [
    &gbuffer::RASTER,
    &gbuffer::RESOLVE,
    &lights::presample::PASS,
    &lights::regir::FILL,
    &di::initial::PASS,
    &di::temporal::PASS,
    &di::spatial::PASS,
    &di::mutation::PASS,
    &di::shade::PASS,
    &gi::initial::PASS,
    &gi::temporal::PASS,
    &gi::spatial::PASS,
    &gi::shade::PASS,
    &pt::initial::PASS,
    &pt::temporal::PASS,
    &pt::spatial::PASS,
    &pt::shade::PASS,
    &denoise::gradient::PASS,
    &denoise::temporal::PASS,
    &denoise::variance::PASS,
    &denoise::atrous::PASS,
    &denoise::modulate::PASS,
    &reference::PASS,
    &moments::PASS,
    &temporal_window::PASS,
    &display::PASS,
    &gi::view::PASS,
    &pt::view::PASS,
    &denoise::view::PASS,
    &bias_view::PASS,
    &window_view::PASS,
    &ray_bench::PASS,
];
