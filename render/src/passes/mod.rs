//! The passes of a frame, one module each, in the order they run:
//! G-buffer (raster + resolve) → initial → temporal → spatial × P → shade → display,
//! or reference → display. Each module owns its bind group layout (group 2), next to
//! the shader that reads it; groups 0 (frame) and 1 (scene) are shared.

pub mod display;
pub mod gbuffer;
pub mod initial;
pub mod presample;
pub mod reference;
pub mod shade;
pub mod spatial;
pub mod temporal;

use std::collections::BTreeSet;

use crate::gpu::timing::FrameRecorder;
use crate::gpu::{Gpu, GpuError};
use crate::shader_source;

pub const WORKGROUP: u32 = 8;

pub fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

pub fn uniform(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Distance between the `PassInfo` slots of the pass-info buffer (the uniform offset
/// alignment), and how many slots it has.
pub const PASS_INFO_STRIDE: u32 = 256;
pub const PASS_INFO_SLOTS: u32 = 256;

/// A `PassInfo` uniform picked per dispatch by dynamic offset (spatial pass index,
/// reference sample chunk).
pub fn pass_info_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: true,
            min_binding_size: wgpu::BufferSize::new(
                std::mem::size_of::<crate::gpu_types::GpuPassInfo>() as u64,
            ),
        },
        count: None,
    }
}

/// Whole-buffer entries in binding order 0, 1, 2, ...
pub fn buffer_entries<'a>(buffers: &[&'a wgpu::Buffer]) -> Vec<wgpu::BindGroupEntry<'a>> {
    buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect()
}

/// A bind group whose entries are whole buffers, in binding order 0, 1, 2, ...
pub fn buffer_bind_group(
    gpu: &Gpu,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries = buffer_entries(buffers);
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

fn layout(gpu: &Gpu, label: &str, entries: &[wgpu::BindGroupLayoutEntry]) -> wgpu::BindGroupLayout {
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries,
        })
}

/// Every bind group layout, created once: group 0 (frame, params, stats), group 1
/// (scene) and each pass's group 2. Pipeline variants of different effect sets share
/// them, so cached bind groups work with every variant.
pub struct PassLayouts {
    pub frame: wgpu::BindGroupLayout,
    pub scene: wgpu::BindGroupLayout,
    pub resolve: wgpu::BindGroupLayout,
    pub presample: wgpu::BindGroupLayout,
    pub initial: wgpu::BindGroupLayout,
    pub temporal: wgpu::BindGroupLayout,
    pub spatial: wgpu::BindGroupLayout,
    pub shade: wgpu::BindGroupLayout,
    pub reference: wgpu::BindGroupLayout,
    pub display: wgpu::BindGroupLayout,
}

impl PassLayouts {
    pub fn new(gpu: &Gpu) -> PassLayouts {
        let all =
            wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
        let mut scene_entries: Vec<_> = (0..crate::gpu_scene::SCENE_STORAGE_BINDINGS)
            .map(|i| wgpu::BindGroupLayoutEntry {
                visibility: all,
                ..storage(i, true)
            })
            .collect();
        scene_entries.extend(crate::environment::upload::layout_entries(all));
        PassLayouts {
            frame: layout(
                gpu,
                "frame",
                &[uniform(0, all), uniform(1, all), storage(2, false)],
            ),
            scene: layout(gpu, "scene", &scene_entries),
            resolve: layout(gpu, "gbuffer resolve", &gbuffer::resolve_entries()),
            presample: layout(gpu, "presample lights", &presample::entries()),
            initial: layout(gpu, "initial", &initial::entries()),
            temporal: layout(gpu, "temporal", &temporal::entries()),
            spatial: layout(gpu, "spatial", &spatial::entries()),
            shade: layout(gpu, "shade", &shade::entries()),
            reference: layout(gpu, "reference", &reference::entries()),
            display: layout(gpu, "display", &display::entries()),
        }
    }
}

/// Compiles `shader` (composed with `defines`) and reports WGSL or validation errors as a
/// `GpuError` instead of wgpu's panic.
pub fn shader_module(
    gpu: &Gpu,
    shader: &str,
    defines: &BTreeSet<String>,
) -> Result<wgpu::ShaderModule, GpuError> {
    let source =
        shader_source::compose(shader, defines).map_err(|e| GpuError::Validation(e.to_string()))?;
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(shader),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
    match pollster::block_on(scope.pop()) {
        Some(e) => Err(GpuError::Validation(format!("{shader}: {e}"))),
        None => Ok(module),
    }
}

/// A compute pass over the image: one pipeline compiled for one set of defines.
pub struct ComputePass {
    pub name: &'static str,
    pub pipeline: wgpu::ComputePipeline,
}

impl ComputePass {
    pub fn new(
        gpu: &Gpu,
        layouts: &PassLayouts,
        name: &'static str,
        shader: &str,
        defines: &BTreeSet<String>,
        pass_layout: &wgpu::BindGroupLayout,
    ) -> Result<ComputePass, GpuError> {
        let module = shader_module(gpu, shader, defines)?;
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipeline_layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(name),
                bind_group_layouts: &[
                    Some(&layouts.frame),
                    Some(&layouts.scene),
                    Some(pass_layout),
                ],
                immediate_size: 0,
            });
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            });
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation(format!("{name}: {e}")));
        }
        Ok(ComputePass { name, pipeline })
    }

    /// Records one dispatch covering `size` pixels as a timed pass.
    pub fn record(&self, rec: &mut FrameRecorder, groups: [&wgpu::BindGroup; 3], size: (u32, u32)) {
        self.record_repeated(rec, groups, &[], size);
    }

    /// Records one dispatch of `workgroups` (x, y) groups as a timed pass (1-D passes).
    pub fn record_workgroups(
        &self,
        rec: &mut FrameRecorder,
        groups: [&wgpu::BindGroup; 3],
        workgroups: (u32, u32),
    ) {
        rec.compute_pass(self.name, |pass| {
            pass.set_pipeline(&self.pipeline);
            for (i, g) in groups.iter().enumerate() {
                pass.set_bind_group(i as u32, *g, &[]);
            }
            pass.dispatch_workgroups(workgroups.0, workgroups.1, 1);
        });
    }

    /// Records one dispatch per dynamic offset of group 2 (reference chunks) inside one
    /// timed compute pass; wgpu orders the dispatches' storage accesses.
    pub fn record_repeated(
        &self,
        rec: &mut FrameRecorder,
        groups: [&wgpu::BindGroup; 3],
        dynamic_offsets: &[u32],
        size: (u32, u32),
    ) {
        rec.compute_pass(self.name, |pass| {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, groups[0], &[]);
            pass.set_bind_group(1, groups[1], &[]);
            let (x, y) = (size.0.div_ceil(WORKGROUP), size.1.div_ceil(WORKGROUP));
            if dynamic_offsets.is_empty() {
                pass.set_bind_group(2, groups[2], &[]);
                pass.dispatch_workgroups(x, y, 1);
            }
            for offset in dynamic_offsets {
                pass.set_bind_group(2, groups[2], &[*offset]);
                pass.dispatch_workgroups(x, y, 1);
            }
        });
    }
}
