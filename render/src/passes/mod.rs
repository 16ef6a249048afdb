//! The passes of a frame, one module each: a module owns its shader's name, what each of
//! its group-2 bindings reads or writes (a `PassDef`), and anything only it needs (the
//! raster pipeline, an output format). Layouts, bind groups and dispatches follow from the
//! declaration (`compile.rs`, `renderer/bind_groups.rs`); the order they run in is the
//! frame plan (`renderer/frame_plan.rs`). Groups 0 (frame) and 1 (scene) are shared.

pub mod compile;
pub mod pass;
pub mod resources;

pub mod bias_view;
pub mod display;
pub mod gbuffer;
pub mod lights;
pub mod moments;
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
    &crate::di::passes::initial::PASS,
    &crate::di::passes::temporal::PASS,
    &crate::di::passes::spatial::PASS,
    &crate::di::passes::mutation::PASS,
    &crate::di::passes::shade::PASS,
    &crate::gi::passes::initial::PASS,
    &crate::gi::passes::temporal::PASS,
    &crate::gi::passes::spatial::PASS,
    &crate::gi::passes::shade::PASS,
    &crate::pt::passes::initial::PASS,
    &crate::pt::passes::temporal::PASS,
    &crate::pt::passes::spatial::PASS,
    &crate::pt::passes::shade::PASS,
    &crate::denoise::passes::gradient::PASS,
    &crate::denoise::passes::temporal::PASS,
    &crate::denoise::passes::variance::PASS,
    &crate::denoise::passes::atrous::PASS,
    &crate::denoise::passes::modulate::PASS,
    &reference::PASS,
    &moments::PASS,
    &temporal_window::PASS,
    &display::PASS,
    &crate::gi::passes::view::PASS,
    &crate::pt::passes::view::PASS,
    &crate::denoise::passes::view::PASS,
    &bias_view::PASS,
    &window_view::PASS,
    &ray_bench::PASS,
];
