//! Creating a renderer: the layouts, the scene upload, the size-dependent targets and the
//! small uniform, stats and readback buffers every frame uses.

use std::collections::HashMap;

use wgpu::util::DeviceExt;

use super::{MAX_SIZE, Renderer};
use crate::effects::SceneFeatures;
use crate::frame_targets::FrameTargets;
use crate::gpu::readback::ReadbackRing;
use crate::gpu::timing::{PassTimer, TimingMode};
use crate::gpu::{Gpu, GpuError};
use crate::gpu_scene::GpuScene;
use crate::gpu_types::*;
use crate::passes::{PASS_INFO_SLOTS, PASS_INFO_STRIDE, PassLayouts};
use crate::scene::Scene;
use crate::settings::Settings;
use crate::shader_constants::STAT_COUNT;
use crate::view::{Mode, ViewSettings};

use super::bind_groups::BindGroupCache;
use super::{inspect, state};

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
        let light_sampler = crate::light_sampler::LightSamplerBuffers::new(&gpu);
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
            buffers: state::FrameBuffers {
                frame_uniform,
                params_uniform,
                display_uniform,
                pass_info,
                light_sampler,
                stats_buffer,
                frame_bind_group,
            },
            pipelines: state::Pipelines {
                variants: HashMap::new(),
                pipeline_compiles: Vec::new(),
                first_frame_pipelines: None,
                first_frame: None,
                compile_watcher: None,
                last_effects: None,
                forced_effects: None,
                planted: Default::default(),
            },
            history: state::History::new(),
            readbacks: state::Readbacks {
                timer,
                stats_ring,
                inspect_ring: ReadbackRing::new(
                    &gpu.device,
                    inspect::INSPECT_BYTES,
                    3,
                    "inspect readback",
                ),
                inspect_staging: inspect::InspectCapture::staging_buffer(&gpu.device),
                pending_inspections: HashMap::new(),
                arrived_inspections: HashMap::new(),
                pending_counters: HashMap::new(),
                pending_times: HashMap::new(),
                timing_mode,
            },
            layouts,
            scene: gpu_scene,
            features: SceneFeatures::of(scene),
            bind_groups: BindGroupCache::default(),
            targets,
            inspected_pixel: None,
            mode: Mode::Restir,
            settings,
            view: ViewSettings::default(),
            camera,
            frame_index: 0,
            seed: 0,
            accumulated_frames: 0,
            last_passes: Vec::new(),
            comparison_scale: 1.0,
            reference_noise: 0.0,
            last_update: Default::default(),
            window: Default::default(),
            frozen_noise: false,
            reference_phase: None,
            depth_probe: Default::default(),
            gpu,
        })
    }
}
