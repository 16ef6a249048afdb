//! The renderer: owns the device resources of one scene at one size and renders frames.
//! `setup.rs` creates it; `frame_plan.rs` lists a frame's passes in order (reading it top
//! to bottom is reading the algorithm); `resolve.rs` maps each pass's bindings to buffers
//! (the ping-pong); `record.rs` records the plan; `uniforms.rs` fills the per-frame
//! uniforms; `bind_groups.rs` caches the bind groups; `reports.rs` gathers each
//! frame's counters, times and inspected pixel; `readback.rs` brings images and per-pixel
//! records back to the CPU; `inspect.rs` is the pixel inspector's capture; `prepare.rs`
//! readies a new scene off the window thread; `depth_probe.rs` runs the denoiser's depth
//! probe between frames.

mod bind_groups;
mod comparison;
mod depth_probe;
pub mod frame_plan;
mod inspect;
mod inspect_pt;
mod pipelines;
mod prepare;
mod ray_bench;
mod readback;
mod record;
mod reports;
pub mod resolve;
mod setup;
mod state;
pub mod stats;
#[cfg(feature = "test-hooks")]
mod test_hooks;
mod uniforms;
mod window;

pub use inspect::{
    DenoiseInspection, GiInspection, GiStageReservoir, PixelInspection, StageReservoir,
};
pub use inspect_pt::{PtInspection, PtStagePath, PtVertex};
pub use prepare::{PreparedScene, ScenePreparer};
pub use ray_bench::{RayKind, RayRate};
pub use setup::check_size;
pub use uniforms::{JITTER_PERIOD, jitter_offset, jitter_phase};
pub use window::TemporalWindow;

use std::collections::HashMap;

use crate::effects::{EffectSet, SceneFeatures};
use crate::frame_targets::FrameTargets;
use crate::gpu::timing::TimingMode;
use crate::gpu::{Gpu, GpuError};
use crate::gpu_scene::{GpuScene, SceneInfo, SceneUpdateTimes};
use crate::passes::resources::{ACCUMULATION, MOMENTS, REFERENCE};
use crate::passes::{ComputePass, PassLayouts, gbuffer::RasterPass};
use crate::scene::animation::SceneChange;
use crate::scene::{Camera, Scene};
use crate::settings::Settings;
use crate::view::{Mode, ViewSettings};

use bind_groups::BindGroupCache;
pub use pipelines::PipelineCompile;

/// What `Renderer::set_compile_watcher` takes: told as each pipeline compile finishes.
pub type CompileWatcher = std::sync::Arc<dyn Fn(crate::load_phases::LoadEvent) + Send + Sync>;

/// Largest output the renderer accepts (each side).
pub const MAX_SIZE: u32 = 8192;

/// Pipelines compiled for one set of defines, built on first use.
#[derive(Default)]
struct PipelineVariant {
    raster: Option<RasterPass>,
    passes: HashMap<&'static str, ComputePass>,
}

pub struct Renderer {
    /// The uniform buffers every pass reads, the stats buffer and the frame bind group.
    buffers: state::FrameBuffers,
    /// Compiled pipeline variants and what their compiles took.
    pipelines: state::Pipelines,
    /// What the next frame takes over from this one.
    history: state::History,
    /// Counters, pass times and inspections on their way back from the GPU.
    readbacks: state::Readbacks,
    gpu: Gpu,
    layouts: PassLayouts,
    scene: GpuScene,
    features: SceneFeatures,
    targets: FrameTargets,
    bind_groups: BindGroupCache,
    inspected_pixel: Option<(u32, u32)>,

    mode: Mode,
    settings: Settings,
    view: ViewSettings,
    camera: Camera,
    frame_index: u64,
    seed: u32,
    accumulated_frames: u32,
    last_passes: Vec<&'static str>,
    /// Radiance scale of the comparison image (1/N of an accumulated other side).
    comparison_scale: f32,
    /// The uploaded reference's own luma RMSE (the bias view counts it as noise).
    reference_noise: f32,
    last_update: SceneUpdateTimes,
    /// The temporal window of the boiling views: whether it holds a continuous run.
    window: window::WindowState,
    /// Every frame draws frame 0's random numbers (`freeze_noise`).
    frozen_noise: bool,
    /// `Mode::Reference` rasterises at this jitter phase's offset (`set_reference_phase`).
    reference_phase: Option<u32>,
    /// `denoise_auto_depth`'s warm-up count and choice.
    depth_probe: depth_probe::DepthProbeState,
}

impl Renderer {
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    pub fn scene_info(&self) -> &SceneInfo {
        &self.scene.info
    }

    /// The phases from file to first frame: the loader's and the upload's (the scene's
    /// info), then the first frame's pipelines once it has been rendered.
    pub fn load_phases(&self) -> crate::load_phases::LoadPhases {
        let mut phases = self.scene.info.load.clone();
        phases
            .phases
            .extend(self.pipelines.first_frame_pipelines.clone());
        phases.phases.extend(self.pipelines.first_frame.clone());
        phases
    }

    /// How many phases `load_phases` has (cheap: the viewer polls it every frame).
    pub fn load_phase_count(&self) -> usize {
        self.scene.info.load.phases.len()
            + self.pipelines.first_frame_pipelines.is_some() as usize
            + self.pipelines.first_frame.is_some() as usize
    }

    /// Every pipeline compiled so far, with its compile time.
    pub fn pipeline_compiles(&self) -> &[PipelineCompile] {
        &self.pipelines.pipeline_compiles
    }

    /// Who hears pipeline compiles from now on (`None`: nobody).
    pub fn set_compile_watcher(&mut self, watcher: Option<CompileWatcher>) {
        self.pipelines.compile_watcher = watcher;
    }

    pub fn scene_scale(&self) -> f32 {
        self.scene.scale
    }

    pub fn scene_bounds(&self) -> crate::scene::Aabb {
        self.scene.bounds
    }

    /// Replaces the scene (history and accumulation restart; the camera moves to the
    /// new scene's camera).
    /// The upload runs here, on the caller's thread; the viewer prepares scenes in the
    /// background instead (`preparer`, `set_prepared_scene`).
    pub fn set_scene(&mut self, scene: &Scene) -> anyhow::Result<()> {
        let prepared = self
            .preparer()
            .without_warm_up()
            .prepare(scene, &crate::load_phases::unwatched)?;
        self.set_prepared_scene(prepared);
        Ok(())
    }

    /// Brings an animated scene, posed by `SceneAnimation::pose`, to the GPU: what
    /// `change` names is rewritten in place (no re-upload, history kept: reuse across
    /// the change is what dynamic scenes are for). Returns the update's CPU cost.
    pub fn update_scene(&mut self, scene: &Scene, change: SceneChange) -> SceneUpdateTimes {
        let times = self.scene.update(&self.gpu, scene, change);
        self.last_update = times;
        times
    }

    /// The current selection probability of a light entry (0 while the light is off).
    pub fn light_select_pdf(&self, light: u32) -> Option<f32> {
        self.scene.light_select_pdf(light)
    }

    /// The SAH cost of the BVH as it is now (after refits), see `Bvh::sah_cost`.
    pub fn bvh_sah_cost(&self) -> f64 {
        self.scene.bvh.sah_cost()
    }

    /// What `light_sampler=auto` decided from: the load-time probe of the scene's lights
    /// (`light_probe.rs`; `None` without lights with a position).
    pub fn light_probe(&self) -> Option<crate::light_probe::LightProbe> {
        self.features.light_probe
    }

    /// What the light samplers' structures cost: BVH build and refit, memory.
    pub fn light_sampler_stats(&self) -> crate::light_sampler::LightSamplerStats {
        self.buffers.light_sampler.stats
    }

    /// The cost of the last `update_scene`.
    pub fn last_scene_update(&self) -> SceneUpdateTimes {
        self.last_update
    }

    pub fn size(&self) -> (u32, u32) {
        (self.targets.width, self.targets.height)
    }

    /// Re-creates the size-dependent buffers; a no-op for the current size.
    pub fn resize(&mut self, width: u32, height: u32) -> Result<(), GpuError> {
        check_size(width, height)?;
        if (width, height) == self.size() {
            return Ok(());
        }
        self.targets = FrameTargets::new(&self.gpu, width, height);
        self.bind_groups.clear();
        self.forget_depth_choice();
        // The new targets start without history buffers.
        self.history.carried = resolve::Carried::default();
        self.invalidate_history();
        self.reset_accumulation();
        Ok(())
    }

    pub fn mode(&self) -> Mode {
        self.mode
    }

    pub fn set_mode(&mut self, mode: Mode) {
        if mode != self.mode {
            self.mode = mode;
            self.forget_depth_choice();
            self.invalidate_history();
            self.reset_accumulation();
        }
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// New pipeline parameters. The accumulation restarts (a new estimator); history is
    /// kept, so toggling a stage shows its effect on a warm pipeline.
    pub fn set_settings(&mut self, settings: Settings) {
        if settings != self.settings {
            self.settings = settings;
            self.forget_depth_choice();
            self.reset_accumulation();
        }
    }

    pub fn view(&self) -> &ViewSettings {
        &self.view
    }

    pub fn set_view(&mut self, view: ViewSettings) {
        self.view = view;
    }

    /// Forces an effect set (`--effects all|LIST`), or `None` for the scene-derived one.
    pub fn force_effects(&mut self, effects: Option<EffectSet>) {
        self.pipelines.forced_effects = effects;
    }

    /// The effect set of the last rendered frame and the passes it dispatched.
    pub fn last_effects(&self) -> Option<&EffectSet> {
        self.pipelines.last_effects.as_ref().map(|e| &e.set)
    }

    pub fn last_passes(&self) -> &[&'static str] {
        &self.last_passes
    }

    /// What traced the last frame's rays (`ray_backend` resolved on this device).
    pub fn last_ray_backend(&self) -> Option<crate::tracing::RayBackend> {
        self.pipelines.last_effects.as_ref().map(|e| e.backend)
    }

    pub fn camera(&self) -> Camera {
        self.camera
    }

    pub fn set_camera(&mut self, camera: Camera) {
        self.camera = camera;
    }

    /// The random seed of every stream (`--seed`).
    pub fn set_seed(&mut self, seed: u32) {
        self.seed = seed;
    }

    pub fn frame_index(&self) -> u64 {
        self.frame_index
    }

    /// `Mode::Reference` with jitter off shades the surfaces rasterised at this jitter
    /// phase's sub-pixel offset (`None`: the pixel centres), the reference the frames of that
    /// phase are scored against (docs/src/viewer.md, "Accuracy with jitter on").
    pub fn set_reference_phase(&mut self, phase: Option<u32>) {
        self.reference_phase = phase;
    }

    /// Treats the next frame as a camera cut: the previous surfaces are invalid.
    pub fn request_cut(&mut self) {
        self.history.cut_requested = true;
    }

    fn invalidate_history(&mut self) {
        self.history.invalidate();
        self.window.restart();
    }

    /// Restarts the running average (on any change that makes old frames stale).
    pub fn reset_accumulation(&mut self) {
        self.accumulated_frames = 0;
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        encoder.clear_buffer(self.targets.pixels(&ACCUMULATION), 0, None);
        encoder.clear_buffer(self.targets.pixels(&MOMENTS), 0, None);
        self.gpu.queue.submit([encoder.finish()]);
    }

    /// Whether the previous-frame surfaces and history reservoirs exist (they are allocated
    /// the first time temporal reuse runs).
    pub fn history_allocated(&self) -> bool {
        self.targets.has_history()
    }

    pub fn accumulated_frames(&self) -> u32 {
        self.accumulated_frames
    }

    /// The display texture as sRGB (what the viewer samples and shows).
    pub fn display_view_srgb(&self) -> &wgpu::TextureView {
        &self.targets.display_srgb_view
    }

    /// The display texture as stored: sRGB-encoded values read as plain `Rgba8Unorm`.
    /// egui-wgpu blends in gamma space and wants exactly this (the sRGB view would decode
    /// to linear and show the image too dark).
    pub fn display_view(&self) -> &wgpu::TextureView {
        &self.targets.display_view
    }

    /// Uploads a reference image (linear radiance, same size) for the error and bias views,
    /// with its own noise (luma RMSE against the truth; 0 if unknown), which the bias view
    /// adds to the running average's when it decides what is within noise.
    pub fn set_reference_image(
        &mut self,
        image: &crate::image::LinearImage,
        noise_luma_rmse: f32,
    ) -> anyhow::Result<()> {
        anyhow::ensure!(
            (image.width, image.height) == self.size(),
            "reference is {}x{}, the output is {}x{}",
            image.width,
            image.height,
            self.targets.width,
            self.targets.height
        );
        self.gpu.queue.write_buffer(
            self.targets.pixels(&REFERENCE),
            0,
            bytemuck::cast_slice(&image.pixels),
        );
        self.reference_noise = if noise_luma_rmse.is_finite() {
            noise_luma_rmse.max(0.0)
        } else {
            0.0
        };
        Ok(())
    }

    /// How passes are timed (wall clock on CPU adapters, timestamps on GPUs).
    pub fn timing_mode(&self) -> TimingMode {
        self.readbacks.timing_mode
    }

    /// `Off` stops timing (fastest); `WallClock` forces per-pass submissions.
    pub fn set_timing_mode(&mut self, mode: TimingMode) {
        self.readbacks.timing_mode = if mode == TimingMode::Timestamps && !self.gpu.timestamps {
            TimingMode::Off
        } else {
            mode
        };
    }

    /// Selects the pixel whose reservoirs every following frame captures (None stops).
    pub fn set_inspected_pixel(&mut self, pixel: Option<(u32, u32)>) {
        self.inspected_pixel = pixel;
    }

    pub fn inspected_pixel(&self) -> Option<(u32, u32)> {
        self.inspected_pixel
    }
}
