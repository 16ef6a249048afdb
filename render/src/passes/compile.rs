//! From a pass declaration to the GPU: its bind group layout (derived from what each
//! binding names), its shader module and pipeline for one set of defines, and its
//! dispatch.

use std::collections::{BTreeSet, HashMap};

use super::pass::{Access, Binding, Dispatch, PassDef};
use super::resources::Resource;
use super::{ALL, display};
use crate::gpu::timing::FrameRecorder;
use crate::gpu::{Gpu, GpuError};
use crate::gpu_scene::layout::SceneLayouts;
use crate::shader_source;
use crate::tracing::RayBackend;

/// The 2-D workgroup of `Dispatch::Pixels` passes (their `@workgroup_size(8, 8)`).
pub const WORKGROUP: u32 = 8;

pub use crate::gpu::bindings::{buffer_bind_group, buffer_entries, storage, uniform};
pub use crate::gpu_types::{PASS_INFO_SLOTS, PASS_INFO_STRIDE};

/// The layout entry of group-2 binding `index`: its kind follows from the resource (a
/// uniform, a texture, or a storage buffer read-only unless written).
pub fn layout_entry(index: u32, binding: &Binding) -> wgpu::BindGroupLayoutEntry {
    let compute = wgpu::ShaderStages::COMPUTE;
    let ty = match binding.resource {
        // One slot picked per dispatch by dynamic offset.
        Resource::PassInfo => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: true,
            min_binding_size: wgpu::BufferSize::new(
                std::mem::size_of::<crate::gpu_types::GpuPassInfo>() as u64,
            ),
        },
        Resource::DisplayUniform => return uniform(index, compute),
        Resource::Visibility => wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        Resource::Output => wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: display::OUTPUT_FORMAT,
            view_dimension: wgpu::TextureViewDimension::D2,
        },
        _ => return storage(index, binding.access == Access::Read),
    };
    wgpu::BindGroupLayoutEntry {
        binding: index,
        visibility: compute,
        ty,
        count: None,
    }
}

fn layout(gpu: &Gpu, label: &str, entries: &[wgpu::BindGroupLayoutEntry]) -> wgpu::BindGroupLayout {
    gpu.device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries,
        })
}

/// Every bind group layout, created once: group 0 (frame, params, stats), group 1
/// (scene, one layout per tracing backend) and each pass's group 2. Pipeline variants of
/// different effect sets share them, so cached bind groups work with every variant.
pub struct PassLayouts {
    pub frame: wgpu::BindGroupLayout,
    pub scene: SceneLayouts,
    group2: HashMap<&'static str, wgpu::BindGroupLayout>,
}

impl PassLayouts {
    pub fn new(gpu: &Gpu) -> PassLayouts {
        let all =
            wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
        let group2 = ALL
            .iter()
            .map(|pass| {
                let entries: Vec<_> = (0..)
                    .zip(pass.group)
                    .map(|(i, b)| layout_entry(i, b))
                    .collect();
                (pass.name, layout(gpu, pass.name, &entries))
            })
            .collect();
        PassLayouts {
            frame: layout(
                gpu,
                "frame",
                &[uniform(0, all), uniform(1, all), storage(2, false)],
            ),
            scene: SceneLayouts::new(gpu),
            group2,
        }
    }

    /// The group-2 layout of `pass` (every pass is in `passes::ALL`).
    pub fn group2(&self, pass: &PassDef) -> &wgpu::BindGroupLayout {
        self.group2
            .get(pass.name)
            .unwrap_or_else(|| panic!("pass {} is missing from passes::ALL", pass.name))
    }

    /// Groups 0 and 1 of a pipeline compiled with `defines` (group 1 follows the tracing
    /// backend the defines select).
    pub fn frame_and_scene(
        &self,
        defines: &BTreeSet<String>,
    ) -> [Option<&wgpu::BindGroupLayout>; 2] {
        let scene = self.scene.for_backend(RayBackend::of_defines(defines));
        [Some(&self.frame), Some(scene)]
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

/// The compute pipeline of `module`'s `main` over `layout`, with validation errors as a
/// `GpuError` instead of wgpu's panic.
pub fn compute_pipeline(
    gpu: &Gpu,
    label: &str,
    layout: &wgpu::PipelineLayout,
    module: &wgpu::ShaderModule,
) -> Result<wgpu::ComputePipeline, GpuError> {
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let pipeline = gpu
        .device
        .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(layout),
            module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
    match pollster::block_on(scope.pop()) {
        Some(e) => Err(GpuError::Validation(format!("{label}: {e}"))),
        None => Ok(pipeline),
    }
}

/// A compute pass: one pipeline compiled for one set of defines.
pub struct ComputePass {
    pub name: &'static str,
    dispatch: Dispatch,
    pipeline: wgpu::ComputePipeline,
}

impl ComputePass {
    pub fn new(
        gpu: &Gpu,
        layouts: &PassLayouts,
        pass: &'static PassDef,
        defines: &BTreeSet<String>,
    ) -> Result<ComputePass, GpuError> {
        let module = shader_module(gpu, pass.shader, defines)?;
        let frame_and_scene = layouts.frame_and_scene(defines);
        let pipeline_layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(pass.name),
                bind_group_layouts: &[
                    frame_and_scene[0],
                    frame_and_scene[1],
                    Some(layouts.group2(pass)),
                ],
                immediate_size: 0,
            });
        let pipeline = compute_pipeline(gpu, pass.name, &pipeline_layout, &module)?;
        Ok(ComputePass {
            name: pass.name,
            dispatch: pass.dispatch,
            pipeline,
        })
    }

    /// Records the pass as one timed compute pass over an image of `size` pixels: one
    /// dispatch, or one per dynamic offset of group 2 (`PassInfo` slots); wgpu orders the
    /// dispatches' storage accesses. `threads` dispatches fewer invocations than a
    /// `Dispatch::Threads` pass's maximum.
    pub fn record(
        &self,
        rec: &mut FrameRecorder,
        groups: [&wgpu::BindGroup; 3],
        dynamic_offsets: &[u32],
        size: (u32, u32),
        threads: Option<u32>,
    ) {
        let workgroups = match self.dispatch {
            Dispatch::Threads {
                invocations,
                workgroup,
            } => (
                threads
                    .unwrap_or(invocations)
                    .min(invocations)
                    .div_ceil(workgroup),
                1,
            ),
            _ => (size.0.div_ceil(WORKGROUP), size.1.div_ceil(WORKGROUP)),
        };
        rec.compute_pass(self.name, |pass| {
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, groups[0], &[]);
            pass.set_bind_group(1, groups[1], &[]);
            if dynamic_offsets.is_empty() {
                pass.set_bind_group(2, groups[2], &[]);
                pass.dispatch_workgroups(workgroups.0, workgroups.1, 1);
            }
            for offset in dynamic_offsets {
                pass.set_bind_group(2, groups[2], &[*offset]);
                pass.dispatch_workgroups(workgroups.0, workgroups.1, 1);
            }
        });
    }
}
