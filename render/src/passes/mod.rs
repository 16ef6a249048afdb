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
pub mod gi_initial;
pub mod gi_shade;
pub mod gi_spatial;
pub mod gi_temporal;
pub mod gi_view;
pub mod initial;
pub mod moments;
pub mod presample;
pub mod pt_initial;
pub mod pt_shade;
pub mod pt_spatial;
pub mod pt_temporal;
pub mod pt_view;
pub mod ray_bench;
pub mod reference;
pub mod shade;
pub mod spatial;
pub mod temporal;
pub mod temporal_window;
pub mod window_view;

pub use compile::{
    ComputePass, PASS_INFO_SLOTS, PASS_INFO_STRIDE, PassLayouts, WORKGROUP, buffer_bind_group,
    buffer_entries, shader_module, storage, uniform,
};
pub use pass::PassDef;

/// Every pass, in pipeline order (a layout is created for each; tests validate each).
pub const ALL: [&PassDef; 24] = [
    &gbuffer::RASTER,
    &gbuffer::RESOLVE,
    &presample::PASS,
    &initial::PASS,
    &temporal::PASS,
    &spatial::PASS,
    &shade::PASS,
    &gi_initial::PASS,
    &gi_temporal::PASS,
    &gi_spatial::PASS,
    &gi_shade::PASS,
    &pt_initial::PASS,
    &pt_temporal::PASS,
    &pt_spatial::PASS,
    &pt_shade::PASS,
    &reference::PASS,
    &moments::PASS,
    &temporal_window::PASS,
    &display::PASS,
    &gi_view::PASS,
    &pt_view::PASS,
    &bias_view::PASS,
    &window_view::PASS,
    &ray_bench::PASS,
];
