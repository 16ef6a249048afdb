//! The renderer's state, grouped by what it is for: the frame's buffers, the compiled
//! pipelines, the history a frame hands to the next, and the readbacks in flight. The
//! `Renderer` (mod.rs) holds one of each beside the scene and the settings.

use std::collections::{BTreeSet, HashMap};
use std::sync::Arc;

use glam::Mat4;

use super::PixelInspection;
use super::stats::FrameCounters;
use super::{CompileWatcher, PipelineVariant, inspect, pipelines, record, resolve};
use crate::effects::EffectSet;
use crate::gpu::readback::ReadbackRing;
use crate::gpu::timing::{PassTimer, TimingMode};
use crate::scene::Camera;

/// The uniform buffers every pass reads, the stats buffer and the frame bind group (groups 0 of every pass).
pub(super) struct FrameBuffers {
    pub frame_uniform: wgpu::Buffer,
    pub params_uniform: wgpu::Buffer,
    pub display_uniform: wgpu::Buffer,
    pub pass_info: wgpu::Buffer,
    /// The light samplers' data: placeholders until the first frame that uses each.
    pub light_sampler: crate::light_sampler::LightSamplerBuffers,
    pub stats_buffer: wgpu::Buffer,
    pub frame_bind_group: wgpu::BindGroup,
}

impl FrameBuffers {
    /// The buffers some groups bind besides the size-dependent targets.
    pub fn uniforms(&self) -> super::bind_groups::Uniforms<'_> {
        super::bind_groups::Uniforms {
            pass_info: &self.pass_info,
            display: &self.display_uniform,
            light_sampler: &self.light_sampler,
        }
    }
}

/// Compiled pipeline variants (one per effect set), what their compiles took and who hears them.
pub(super) struct Pipelines {
    pub variants: HashMap<String, PipelineVariant>,
    /// Every pipeline compiled so far and how long it took (`pipelines.rs`).
    pub pipeline_compiles: Vec<pipelines::PipelineCompile>,
    /// The first frame's pipelines as one load phase (`None` before the first frame).
    pub first_frame_pipelines: Option<crate::load_phases::Phase>,
    /// The scene's first frame, from recording to finished on the device, less the
    /// pipelines' phase (`None` before it).
    pub first_frame: Option<crate::load_phases::Phase>,
    /// Hears pipeline compiles (headless `render` prints them, the viewer shows progress).
    pub compile_watcher: Option<CompileWatcher>,
    /// The effect set of the last frame (reused while its inputs stay the same).
    pub last_effects: Option<Arc<record::ActiveEffects>>,
    /// `Some` forces an effect set (`--effects`); `None` derives it from the scene.
    pub forced_effects: Option<EffectSet>,
    /// Test-only `PLANTED_*` defines added to whatever effect set the frame uses.
    pub planted: BTreeSet<String>,
}

/// What the next frame takes over from this one: last frame's camera and where its reservoirs and surfaces are.
pub(super) struct History {
    pub prev_camera: Option<Camera>,
    pub prev_view_proj: Option<Mat4>,
    pub prev_jitter: glam::Vec2,
    /// Where last frame's reservoirs and surfaces are (the ping-pong).
    pub carried: resolve::Carried,
    pub history_valid: bool,
    pub cut_requested: bool,
    pub last_final: Option<usize>,
}

/// Counters, pass times and pixel inspections on their way back from the GPU, matched by frame index (reports.rs).
pub(super) struct Readbacks {
    pub timer: PassTimer,
    pub stats_ring: ReadbackRing,
    pub inspect_ring: ReadbackRing,
    pub inspect_staging: wgpu::Buffer,
    pub pending_inspections: HashMap<u64, inspect::PendingInspection>,
    /// Inspections read back, waiting for their frame's counters (a separate readback).
    pub arrived_inspections: HashMap<u64, PixelInspection>,
    pub pending_counters: HashMap<u64, FrameCounters>,
    pub pending_times: HashMap<u64, Vec<(&'static str, f64)>>,
    pub timing_mode: TimingMode,
}

impl History {
    /// No history yet (a new renderer, or a scene just swapped in).
    pub fn new() -> History {
        History {
            prev_camera: None,
            prev_view_proj: None,
            prev_jitter: glam::Vec2::ZERO,
            carried: Default::default(),
            history_valid: false,
            cut_requested: false,
            last_final: None,
        }
    }

    /// This frame's outputs become the next frame's history: the reservoir chains it used
    /// (`finals`, by chain name: only those carry over), its surfaces, its camera.
    pub fn hand_over(
        &mut self,
        frame: resolve::Resolved,
        surface_buffers: usize,
        realtime: bool,
        camera: Camera,
        view_proj: Mat4,
        jitter: glam::Vec2,
    ) {
        let final_reservoirs = frame
            .finals
            .get(crate::passes::resources::RESERVOIRS.name)
            .copied();
        self.carried.history = frame.finals;
        self.carried.surfaces = frame.surfaces;
        self.carried.surface_buffers = surface_buffers;
        self.history_valid = realtime;
        self.last_final = if realtime { final_reservoirs } else { None };
        self.prev_camera = Some(camera);
        self.prev_view_proj = Some(view_proj);
        self.prev_jitter = jitter;
    }

    /// The next frame reuses nothing from the last (a camera cut, a resize, a new scene):
    /// its previous surfaces are invalid and it has no previous camera.
    pub fn invalidate(&mut self) {
        self.history_valid = false;
        self.prev_camera = None;
        self.prev_view_proj = None;
        self.last_final = None;
    }

    /// Whether this frame starts without history: a cut was requested, or the camera
    /// jumped further than `cut_distance` in one frame. Clears the request.
    pub fn take_cut(&mut self, camera: Camera, cut_distance: f32) -> bool {
        let jump = self
            .prev_camera
            .map_or(0.0, |p| (p.position - camera.position).length());
        let cut = self.cut_requested || jump > cut_distance;
        self.cut_requested = false;
        if cut {
            self.history_valid = false;
        }
        cut
    }
}
