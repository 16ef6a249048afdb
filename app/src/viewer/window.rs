//! One window's viewer: the `Viewer` struct (the window, the device, the renderer, the UI
//! and the plain state it edits, the loads in flight) and what the event loop asks of it
//! between frames (size, visibility, input, when to draw next).
//!
//! What a viewer does is split by job, each file an `impl Viewer` of its own: `frame.rs`
//! (opening it, then one frame in order), `actions.rs` (the UI's requests and finished
//! loads), `clock.rs` (scene time), `tour/driver.rs` (the teaching tools). The struct sits
//! here, below all of them, so that none of them has to import another to reach it.

use std::sync::Arc;
use std::time::{Duration, Instant};

use restir_render::effects::EffectSet;
use restir_render::timeline::AnimatedScene;
use restir_render::{Gpu, PipelineCompile, Renderer, Scene};
use winit::dpi::PhysicalSize;
use winit::window::Window;

use super::accuracy::tracker::AccuracyTracker;
use super::compare_side::CompareSide;
use super::egui_layer::EguiLayer;
use super::gpu_surface::GpuSurface;
use super::scene_loader::SceneLoader;
use super::screenshot;
use super::state::ViewerState;
use super::tour::teaching::Teaching;

pub struct Viewer {
    pub(super) window: Arc<Window>,
    pub(super) gpu: Gpu,
    pub(super) surface: GpuSurface,
    pub(super) renderer: Renderer,
    pub(super) egui: EguiLayer,
    pub state: ViewerState,
    /// The scene shown, kept for the accuracy panel's reference jobs.
    pub(super) scene: Arc<Scene>,
    /// An animated scene's clock (its own posed copy of the scene); `None` when static.
    pub(super) clock: Option<AnimatedScene>,
    pub(super) accuracy: AccuracyTracker,
    /// Configuration B of the split screen, while the Compare section has it on.
    pub(super) compare: Option<CompareSide>,
    pub(super) loader: SceneLoader,
    pub(super) startup: Startup,
    /// A change's pipelines warming beside the window (CPU adapters): the effect set and
    /// the job (`Viewer::pipelines_ready`).
    pub(super) warming: Option<(EffectSet, WarmJob)>,
    /// A prepared scene was just swapped in: its load warmed the next frame's pipelines.
    pub(super) just_prepared: bool,
    pub(super) screenshots: screenshot::Schedule,
    pub(super) exit_after_screenshot: bool,
    pub(super) frames_rendered: u64,
    /// Set the exposure automatically once this many frames have rendered (after a
    /// scene load, when the first frames have something to measure).
    pub(super) auto_exposure_at: Option<u64>,
    pub(super) last_redraw: Option<Instant>,
    /// When the last frame was rendered (frozen: redraw a little longer, until its report
    /// and inspection have come back).
    pub(super) last_render: Option<Instant>,
    /// When egui asked to run again.
    pub(super) ui_wakeup: Option<Instant>,
    /// Hidden behind other windows or on another workspace (where the platform says so).
    pub(super) occluded: bool,
    /// The pixel history's frame facts and a recording (`tour/driver.rs`).
    pub(super) teaching: Teaching,
}

/// A change's pipelines compiling on a sibling device (`ScenePreparer::warm_effects`).
pub(super) type WarmJob = std::thread::JoinHandle<Result<Vec<PipelineCompile>, String>>;

/// Where the viewer's start is: its first frame waits for the warm-up (`Viewer::started`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Startup {
    NotStarted,
    Warming,
    Done,
}

/// How long a frozen viewer keeps redrawing after rendering a frame, so the frame's
/// report and pixel inspection (read back asynchronously) reach the panels.
const REPORT_GRACE: Duration = Duration::from_millis(500);

/// Frames rendered before the automatic exposure of a new scene is measured.
pub(super) const AUTO_EXPOSURE_FRAMES: u64 = 3;

impl Viewer {
    pub fn window(&self) -> &Window {
        &self.window
    }

    pub fn frames_rendered(&self) -> u64 {
        self.frames_rendered
    }

    /// The surface size in physical pixels (0×0 while minimised).
    pub fn surface_size(&self) -> (u32, u32) {
        if self.surface.is_drawable() {
            self.surface.size()
        } else {
            (0, 0)
        }
    }

    /// Whether frames should be drawn now (false while minimised or occluded).
    pub fn is_drawable(&self) -> bool {
        self.surface.is_drawable() && !self.occluded
    }

    pub fn set_occluded(&mut self, occluded: bool) {
        self.occluded = occluded;
        self.window.request_redraw();
    }

    /// When the next frame should be drawn: `now` while rendering (progressive frames
    /// never stop), when egui asks while frozen, never while minimised.
    pub fn next_redraw(&self, now: Instant) -> Option<Instant> {
        if !self.is_drawable() {
            return None;
        }
        let inspector = &self.state.inspector;
        let rendering = !inspector.frozen
            || inspector.step
            || self.loader.loading().is_some()
            || self.last_render.is_some_and(|t| now - t < REPORT_GRACE);
        if rendering { Some(now) } else { self.ui_wakeup }
    }

    /// Feeds a window event to egui (all keyboard and pointer input goes through egui);
    /// input egui cares about draws a frame even while frozen.
    pub fn egui_event(&mut self, event: &winit::event::WindowEvent) {
        // (egui-winit asks to repaint on RedrawRequested itself: that would never idle.)
        let repaint = self.egui.on_window_event(&self.window, event);
        if repaint && !matches!(event, winit::event::WindowEvent::RedrawRequested) {
            self.window.request_redraw();
        }
    }

    /// A new window size; 0×0 (minimised) pauses drawing until the next real size.
    pub fn resized(&mut self, size: PhysicalSize<u32>) {
        self.surface.resize(&self.gpu, size.width, size.height);
        if self.surface.is_drawable() {
            self.window.request_redraw();
        }
    }

    /// Holds the `--screenshot-after` shot (while the resize test script runs).
    pub fn hold_screenshot(&mut self, hold: bool) {
        self.screenshots.hold = hold;
    }
}

/// The window's title: the scene's name.
pub(super) fn title(state: &ViewerState) -> String {
    let name = state
        .scene
        .info
        .as_ref()
        .map_or(state.scene.spec.as_str(), |i| i.name.as_str());
    format!("ReSTIR lab — {name}")
}
