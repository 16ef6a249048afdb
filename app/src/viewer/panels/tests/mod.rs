//! Panel behaviour, driven through egui_kittest's accessibility tree: no GPU, no window.
//! Each test edits the plain `ViewerState` through the widgets a user would touch.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use glam::Vec3;
use restir_render::gpu_types::{
    GpuGiPixelDebug, GpuGiReservoir, GpuPixelDebug, GpuReservoir, GpuSurface, NO_LIGHT,
};
use restir_render::renderer::{GiInspection, GiStageReservoir, PixelInspection, StageReservoir};
use restir_render::scene::Aabb;
use restir_render::settings::preset;
use restir_render::shader_constants::*;
use restir_render::stats::{FrameCounters, FrameReport};
use restir_render::{Camera, DebugView, Settings};

use super::*;
use crate::viewer::camera::CameraState;
use crate::viewer::state::DisplayOptions;

fn state() -> ViewerState {
    let bounds = Aabb {
        min: Vec3::splat(-1.0),
        max: Vec3::splat(1.0),
    };
    let camera = CameraState::new(
        Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8),
        bounds,
    );
    ViewerState::new(
        Settings::default(),
        camera,
        DisplayOptions::for_adapter(true),
    )
}

/// A harness showing one panel, tall enough that nothing needs scrolling.
fn harness<'a>(
    panel: impl FnMut(&mut egui::Ui, &mut ViewerState) + 'a,
    state: ViewerState,
) -> Harness<'a, ViewerState> {
    Harness::builder()
        .with_size(egui::vec2(520.0, 1600.0))
        .build_ui_state(panel, state)
}

fn temp_file(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("restir-viewer-{}-{name}", std::process::id()))
}

fn shows(h: &Harness<'_, ViewerState>, text: &str) -> bool {
    h.query_all_by_label_contains(text).next().is_some()
}

mod accuracy_panel;
mod inspector_panel;
mod other_panels;
mod pipeline_panel;
mod side_panel;
mod time_panel;
mod tour_panel;
