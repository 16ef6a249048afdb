//! The renderer: owns the device resources of one scene at one size and renders frames.
//! `record.rs` records a frame's passes in order (reading it top to bottom is reading
//! the algorithm); `bind_groups.rs` caches the bind groups the ping-pong needs;
//! `readback.rs` brings images and per-pixel records back to the CPU.

mod bind_groups;
mod inspect;
mod readback;
mod record;

pub use inspect::{PixelInspection, StageReservoir};

use std::collections::HashMap;

use glam::Mat4;
use wgpu::util::DeviceExt;

use crate::effects::{EffectSet, SceneFeatures};
use crate::frame_targets::FrameTargets;
use crate::gpu::readback::ReadbackRing;
use crate::gpu::timing::{PassTimer, TimingMode};
use crate::gpu::{Gpu, GpuError};
use crate::gpu_scene::{GpuScene, SceneInfo};
use crate::gpu_types::*;
use crate::passes::{
    ComputePass, PASS_INFO_SLOTS, PASS_INFO_STRIDE, PassLayouts, gbuffer::GBufferPass,
};
use crate::scene::{Camera, Scene};
use crate::settings::Settings;
use crate::shader_constants::{LIGHT_TILE_COUNT, LIGHT_TILE_SIZE, STAT_COUNT};
use crate::stats::{FrameCounters, FrameReport};
use crate::view::{Mode, ViewSettings};

use bind_groups::BindGroupCache;

/// Largest output the renderer accepts (each side), and the smallest.
pub const MAX_SIZE: u32 = 8192;

/// Pipelines compiled for one set of defines, built on first use.
#[derive(Default)]
struct PipelineVariant {
    gbuffer: Option<GBufferPass>,
    passes: HashMap<&'static str, ComputePass>,
}

/// Where the reservoirs of the last frame ended up, and which surfaces are current.
#[derive(Clone, Copy, Debug, Default)]
struct PingPong {
    /// Index of the reservoir buffer holding the last frame's final reservoirs.
    history: usize,
    /// Index of the surface buffer written by the last frame.
    surfaces: usize,
}

pub struct Renderer {
    gpu: Gpu,
    layouts: PassLayouts,
    variants: HashMap<String, PipelineVariant>,
    scene: GpuScene,
    features: SceneFeatures,
    targets: FrameTargets,
    bind_groups: BindGroupCache,
    frame_uniform: wgpu::Buffer,
    params_uniform: wgpu::Buffer,
    display_uniform: wgpu::Buffer,
    pass_info: wgpu::Buffer,
    /// Light tiles: a one-element placeholder until the first frame that uses them.
    light_tiles: wgpu::Buffer,
    stats_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    timer: PassTimer,
    stats_ring: ReadbackRing,
    inspect_ring: ReadbackRing,
    inspected_pixel: Option<(u32, u32)>,
    pending_inspections: HashMap<u64, inspect::PendingInspection>,
    /// Inspections read back, waiting for their frame's counters (a separate readback).
    arrived_inspections: HashMap<u64, PixelInspection>,
    timing_mode: TimingMode,
    pending_counters: HashMap<u64, FrameCounters>,
    pending_times: HashMap<u64, Vec<(&'static str, f64)>>,

    mode: Mode,
    settings: Settings,
    view: ViewSettings,
    /// `Some` forces an effect set (`--effects`); `None` derives it from the scene.
    forced_effects: Option<EffectSet>,
    camera: Camera,
    prev_camera: Option<Camera>,
    prev_view_proj: Option<Mat4>,
    prev_jitter: glam::Vec2,
    frame_index: u64,
    seed: u32,
    ping_pong: PingPong,
    history_valid: bool,
    cut_requested: bool,
    accumulated_frames: u32,
    last_final: Option<usize>,
    last_effects: Option<EffectSet>,
    last_passes: Vec<&'static str>,
}

fn tile_buffer(gpu: &Gpu, entries: u64) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("light tiles"),
        size: entries * std::mem::size_of::<GpuTileSample>() as u64,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    })
}

/// Replaces the placeholder by the full light-tile buffer on first use.
fn ensure_light_tiles(gpu: &Gpu, tiles: &mut wgpu::Buffer) {
    let full = (LIGHT_TILE_COUNT * LIGHT_TILE_SIZE) as u64;
    if tiles.size() < full * std::mem::size_of::<GpuTileSample>() as u64 {
        *tiles = tile_buffer(gpu, full);
    }
}

/// Validated output size.
pub fn check_size(width: u32, height: u32) -> Result<(), GpuError> {
    if width == 0 || height == 0 || width > MAX_SIZE || height > MAX_SIZE {
        return Err(GpuError::Unsupported {
            adapter: "renderer".into(),
            problem: format!("output size {width}x{height} is outside 1..={MAX_SIZE} per side"),
        });
    }
    Ok(())
}

impl Renderer {
    pub fn new(
        gpu: Gpu,
        scene: &Scene,
        width: u32,
        height: u32,
        settings: Settings,
    ) -> anyhow::Result<Renderer> {
        check_size(width, height)?;
        let layouts = PassLayouts::new(&gpu);
        let gpu_scene = GpuScene::upload(&gpu, scene, &layouts.scene)?;
        let targets = FrameTargets::new(&gpu, width, height);
        let uniform = |label: &str, size: usize| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let frame_uniform = uniform("frame", std::mem::size_of::<GpuFrame>());
        let params_uniform = uniform("params", std::mem::size_of::<GpuParams>());
        let display_uniform = uniform("display", std::mem::size_of::<GpuDisplay>());
        let pass_info_data: Vec<u8> = (0..PASS_INFO_SLOTS)
            .flat_map(|i| {
                let mut slot = vec![0u8; PASS_INFO_STRIDE as usize];
                let info = GpuPassInfo {
                    pass_index: i,
                    is_last: 0,
                    _pad: [0; 2],
                };
                slot[..16].copy_from_slice(bytemuck::bytes_of(&info));
                slot
            })
            .collect();
        let pass_info = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("pass info"),
                contents: &pass_info_data,
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let light_tiles = tile_buffer(&gpu, 1);
        let stats_size = STAT_COUNT as u64 * 4;
        let stats_buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stats"),
            size: stats_size,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_bind_group = crate::passes::buffer_bind_group(
            &gpu,
            "frame",
            &layouts.frame,
            &[&frame_uniform, &params_uniform, &stats_buffer],
        );
        let timer = PassTimer::new(&gpu);
        // lavapipe's compute timestamps do not bracket the dispatch: time CPU adapters by
        // the clock, one pass per submission (see TimingMode::WallClock).
        let timing_mode = if gpu.is_cpu() {
            TimingMode::WallClock
        } else if gpu.timestamps {
            TimingMode::Timestamps
        } else {
            TimingMode::Off
        };
        let stats_ring = ReadbackRing::new(&gpu.device, stats_size, 4, "stats readback");
        let camera = scene.default_camera();
        Ok(Renderer {
            layouts,
            variants: HashMap::new(),
            scene: gpu_scene,
            features: SceneFeatures::of(scene),
            bind_groups: BindGroupCache::default(),
            targets,
            frame_uniform,
            params_uniform,
            display_uniform,
            pass_info,
            light_tiles,
            stats_buffer,
            frame_bind_group,
            timer,
            stats_ring,
            inspect_ring: ReadbackRing::new(
                &gpu.device,
                inspect::INSPECT_BYTES,
                3,
                "inspect readback",
            ),
            inspected_pixel: None,
            pending_inspections: HashMap::new(),
            arrived_inspections: HashMap::new(),
            timing_mode,
            pending_counters: HashMap::new(),
            pending_times: HashMap::new(),
            mode: Mode::Restir,
            settings,
            view: ViewSettings::default(),
            forced_effects: None,
            camera,
            prev_camera: None,
            prev_view_proj: None,
            frame_index: 0,
            seed: 0,
            ping_pong: PingPong::default(),
            history_valid: false,
            cut_requested: false,
            accumulated_frames: 0,
            prev_jitter: glam::Vec2::ZERO,
            last_final: None,
            last_effects: None,
            last_passes: Vec::new(),
            gpu,
        })
    }

    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    pub fn scene_info(&self) -> &SceneInfo {
        &self.scene.info
    }

    pub fn scene_scale(&self) -> f32 {
        self.scene.scale
    }

    pub fn scene_bounds(&self) -> crate::scene::Aabb {
        self.scene.bounds
    }

    /// Replaces the scene (history and accumulation restart; the camera moves to the
    /// new scene's camera).
    pub fn set_scene(&mut self, scene: &Scene) -> anyhow::Result<()> {
        self.scene = GpuScene::upload(&self.gpu, scene, &self.layouts.scene)?;
        self.features = SceneFeatures::of(scene);
        self.camera = scene.default_camera();
        self.invalidate_history();
        self.reset_accumulation();
        Ok(())
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
        // The new targets start without history buffers.
        self.ping_pong = PingPong::default();
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
        self.forced_effects = effects;
    }

    /// The effect set of the last rendered frame and the passes it dispatched.
    pub fn last_effects(&self) -> Option<&EffectSet> {
        self.last_effects.as_ref()
    }

    pub fn last_passes(&self) -> &[&'static str] {
        &self.last_passes
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

    /// Treats the next frame as a camera cut: the previous surfaces are invalid.
    pub fn request_cut(&mut self) {
        self.cut_requested = true;
    }

    fn invalidate_history(&mut self) {
        self.history_valid = false;
        self.prev_camera = None;
        self.prev_view_proj = None;
        self.last_final = None;
    }

    /// Fault injection for tests of the non-finite guard: overwrites the history
    /// reservoirs with NaN and infinite weights, as a driver bug or a bad upload might.
    /// The next frame's temporal pass must count them and treat them as null.
    #[doc(hidden)]
    pub fn poison_history_for_tests(&mut self) {
        let poisoned = GpuReservoir {
            light: 0,
            p_hat: f32::NAN,
            uv: [0.3, 0.3],
            w_sum: f32::INFINITY,
            weight: f32::NAN,
            m: f32::NAN,
            source: 1,
        };
        let data = vec![poisoned; self.targets.pixel_count() as usize];
        self.gpu.queue.write_buffer(
            &self.targets.reservoirs[self.ping_pong.history],
            0,
            bytemuck::cast_slice(&data),
        );
    }

    /// Restarts the running average (on any change that makes old frames stale).
    pub fn reset_accumulation(&mut self) {
        self.accumulated_frames = 0;
        let mut encoder = self.gpu.device.create_command_encoder(&Default::default());
        encoder.clear_buffer(&self.targets.accumulation, 0, None);
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

    /// Uploads a reference image (linear radiance, same size) for the error view.
    pub fn set_reference_image(&mut self, image: &crate::image::LinearImage) -> anyhow::Result<()> {
        anyhow::ensure!(
            (image.width, image.height) == self.size(),
            "reference is {}x{}, the output is {}x{}",
            image.width,
            image.height,
            self.targets.width,
            self.targets.height
        );
        self.gpu.queue.write_buffer(
            &self.targets.reference,
            0,
            bytemuck::cast_slice(&image.pixels),
        );
        Ok(())
    }

    /// How passes are timed (wall clock on CPU adapters, timestamps on GPUs).
    pub fn timing_mode(&self) -> TimingMode {
        self.timing_mode
    }

    /// `Off` stops timing (fastest); `WallClock` forces per-pass submissions.
    pub fn set_timing_mode(&mut self, mode: TimingMode) {
        self.timing_mode = if mode == TimingMode::Timestamps && !self.gpu.timestamps {
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

    /// Reports (counters and pass timings) of frames whose readbacks have arrived.
    /// With `wait`, blocks until every submitted frame's report is in.
    pub fn collect_reports(&mut self, wait: bool) -> Vec<FrameReport> {
        if wait {
            self.gpu.wait_idle();
        } else {
            let _ = self.gpu.device.poll(wgpu::PollType::Poll);
        }
        for (frame, bytes) in self.stats_ring.collect() {
            self.pending_counters
                .insert(frame, FrameCounters(bytemuck::pod_collect_to_vec(&bytes)));
        }
        self.pending_times.extend(self.timer.collect());
        for (frame, bytes) in self.inspect_ring.collect() {
            if let Some(pending) = self.pending_inspections.remove(&frame) {
                let scene = &self.scene;
                if let Some(i) =
                    pending.finish(frame, &bytes, |light, uv| scene.sample_point(light, uv))
                {
                    self.arrived_inspections.insert(frame, i);
                }
            }
        }
        // Counters, timings and the inspection of a frame travel in the same submission
        // but come back separately: a report is complete when all are in (timings only
        // when timestamps are on).
        let mut ready: Vec<u64> = self
            .pending_counters
            .keys()
            .copied()
            .filter(|f| !self.timer.enabled() || wait || self.pending_times.contains_key(f))
            .filter(|f| !self.pending_inspections.contains_key(f))
            .collect();
        ready.sort_unstable();
        let reports = ready
            .into_iter()
            .map(|frame| FrameReport {
                frame,
                counters: self.pending_counters.remove(&frame).unwrap_or_default(),
                pass_ms: self.pending_times.remove(&frame).unwrap_or_default(),
                inspection: self.arrived_inspections.remove(&frame),
            })
            .collect();
        // Timings whose counters were dropped (ring full) would otherwise pile up.
        let oldest = self.frame_index.saturating_sub(16);
        self.pending_times.retain(|f, _| *f >= oldest);
        self.pending_inspections.retain(|f, _| *f >= oldest);
        self.arrived_inspections.retain(|f, _| *f >= oldest);
        reports
    }
}
