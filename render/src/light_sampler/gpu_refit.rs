//! The light BVH's refit on the GPU (docs/src/light-samplers.md, "Moving lights"): the CPU
//! finds the nodes above the changed lights (a climb with early stop, the cheap part) and
//! lists them by level; shaders/lights/light_bvh_refit.wgsl rewrites them, one dispatch per
//! level, the changed leaves first and then the interior nodes from the deepest up (wgpu
//! orders the dispatches' storage accesses). The unions and the record encoding, the
//! CPU refit's cost, run on the device. Full-precision bounds live beside the records on
//! the GPU, since a union of quantised records would widen a little at every refit.

use super::storage;
use crate::gpu::{Gpu, GpuError, bindings};
use crate::gpu_types::{GpuLightBounds, GpuRefitLevel};
use crate::light_bvh::{EmissiveTriangle, LightBounds, LightBvh, NO_NODE};
use crate::passes::compile::{compute_pipeline, shader_module};
use crate::shader_constants::{LIGHT_BVH_REFIT_WORKGROUP, MAX_LIGHT_BVH_LEVELS};

pub fn gpu_bounds(b: &LightBounds) -> GpuLightBounds {
    GpuLightBounds {
        min: b.min.into(),
        phi: b.phi,
        max: b.max.into(),
        cos_theta_o: b.normals.cos_theta,
        w: b.normals.w.into(),
        cos_theta_e: b.cos_theta_e,
    }
}

pub struct GpuRefit {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    /// Per node, its bounds in full precision.
    bounds: wgpu::Buffer,
    /// The nodes to rewrite, level after level; the changed leaves' new bounds.
    work: wgpu::Buffer,
    leaf_bounds: wgpu::Buffer,
    /// One `GpuRefitLevel` per dynamic-offset slot.
    levels: wgpu::Buffer,
    level_stride: u32,
    /// Per node, its depth (the root 0).
    depth: Vec<u8>,
    /// The lists a refit builds, kept between refits so a frame of moving lights
    /// allocates nothing once they have grown to its size.
    scratch: Scratch,
    /// The bind group of the last refit and the records buffer it binds: rebuilt only when
    /// that buffer (the sampler's, replaced at every build) or one of ours is replaced.
    group: Option<(wgpu::Buffer, wgpu::BindGroup)>,
}

#[derive(Default)]
struct Scratch {
    marks: Vec<bool>,
    above: Vec<usize>,
    by_depth: Vec<Vec<u32>>,
    work: Vec<u32>,
    leaf_bounds: Vec<GpuLightBounds>,
    levels: Vec<GpuRefitLevel>,
    slots: Vec<u8>,
}

impl GpuRefit {
    /// The pipeline and the full-precision bounds of `tree` as it is now.
    pub fn new(gpu: &Gpu, tree: &LightBvh) -> Result<GpuRefit, GpuError> {
        let module = shader_module(gpu, "lights/light_bvh_refit.wgsl", &Default::default())?;
        let layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("light bvh refit"),
                entries: &[
                    bindings::storage(0, false),
                    bindings::storage(1, false),
                    bindings::storage(2, true),
                    bindings::storage(3, true),
                    wgpu::BindGroupLayoutEntry {
                        binding: 4,
                        visibility: wgpu::ShaderStages::COMPUTE,
                        ty: wgpu::BindingType::Buffer {
                            ty: wgpu::BufferBindingType::Uniform,
                            has_dynamic_offset: true,
                            min_binding_size: wgpu::BufferSize::new(
                                std::mem::size_of::<GpuRefitLevel>() as u64,
                            ),
                        },
                        count: None,
                    },
                ],
            });
        let pipeline_layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("light bvh refit"),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        let pipeline = compute_pipeline(gpu, "light bvh refit", &pipeline_layout, &module)?;
        let records: Vec<GpuLightBounds> =
            tree.nodes.iter().map(|n| gpu_bounds(n.bounds())).collect();
        let bounds = storage(
            gpu,
            "light bvh bounds",
            (records.len() * std::mem::size_of::<GpuLightBounds>()) as u64,
        );
        gpu.queue
            .write_buffer(&bounds, 0, bytemuck::cast_slice(&records));
        let level_stride = gpu
            .device
            .limits()
            .min_uniform_buffer_offset_alignment
            .max(16);
        let levels = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("light bvh refit levels"),
            size: (MAX_LIGHT_BVH_LEVELS * level_stride) as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        // Preorder: a parent comes before its children.
        let mut depth = vec![0u8; tree.nodes.len()];
        for i in 1..tree.nodes.len() {
            let parent = tree.parents[i];
            if parent != NO_NODE {
                depth[i] = depth[parent as usize].saturating_add(1);
            }
        }
        Ok(GpuRefit {
            pipeline,
            layout,
            bounds,
            work: storage(gpu, "light bvh refit work", 16),
            leaf_bounds: storage(gpu, "light bvh refit leaves", 16),
            levels,
            level_stride,
            depth,
            scratch: Scratch::default(),
            group: None,
        })
    }

    /// Refits the nodes above the `changed` lights (their leaves take `lights`' bounds) in
    /// `nodes`, the records buffer the walk reads: uploads the work and submits one
    /// dispatch per level. Returns how many nodes it rewrites.
    pub fn refit(
        &mut self,
        gpu: &Gpu,
        tree: &LightBvh,
        lights: &[EmissiveTriangle],
        changed: &[usize],
        nodes: &wgpu::Buffer,
    ) -> usize {
        let s = &mut self.scratch;
        tree.nodes_above_into(changed, &mut s.marks, &mut s.above);
        if s.above.is_empty() {
            return 0;
        }
        // The changed leaves first, then interior nodes by depth, deepest first.
        s.work.clear();
        s.leaf_bounds.clear();
        let max_depth = s.above.iter().map(|&n| self.depth[n]).max().unwrap_or(0) as usize;
        s.by_depth.iter_mut().for_each(Vec::clear);
        if s.by_depth.len() <= max_depth {
            s.by_depth.resize_with(max_depth + 1, Vec::new);
        }
        for &n in &s.above {
            match &tree.nodes[n] {
                crate::light_bvh::Node::Leaf { light, .. } => {
                    s.work.push(n as u32);
                    s.leaf_bounds.push(gpu_bounds(&lights[*light].bounds()));
                }
                crate::light_bvh::Node::Interior { .. } => {
                    s.by_depth[self.depth[n] as usize].push(n as u32)
                }
            }
        }
        s.levels.clear();
        s.levels.push(GpuRefitLevel {
            first: 0,
            count: s.work.len() as u32,
            leaves: 1,
            _pad: 0,
        });
        for level in s.by_depth.iter().rev().filter(|l| !l.is_empty()) {
            s.levels.push(GpuRefitLevel {
                first: s.work.len() as u32,
                count: level.len() as u32,
                leaves: 0,
                _pad: 0,
            });
            s.work.extend_from_slice(level);
        }
        // A tree deeper than the levels uniform holds (never: depth ≤ 64) is refitted in
        // part; say so rather than index past the buffer.
        if s.levels.len() > MAX_LIGHT_BVH_LEVELS as usize {
            log::error!(
                "light BVH refit: {} levels, more than {MAX_LIGHT_BVH_LEVELS}; the top is left",
                s.levels.len()
            );
            s.levels.truncate(MAX_LIGHT_BVH_LEVELS as usize);
        }
        self.upload(gpu, nodes);
        let group = &self.group.as_ref().expect("upload binds the group").1;
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("light bvh refit"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            for (i, level) in self.scratch.levels.iter().enumerate() {
                pass.set_bind_group(0, group, &[i as u32 * self.level_stride]);
                pass.dispatch_workgroups(level.count.div_ceil(LIGHT_BVH_REFIT_WORKGROUP), 1, 1);
            }
        }
        gpu.queue.submit([encoder.finish()]);
        self.scratch.above.len()
    }

    /// Uploads the scratch lists and makes sure `group` binds `nodes` and our buffers.
    fn upload(&mut self, gpu: &Gpu, nodes: &wgpu::Buffer) {
        let s = &mut self.scratch;
        let work_bytes = std::mem::size_of_val(s.work.as_slice()) as u64;
        let leaf_bytes = std::mem::size_of_val(s.leaf_bounds.as_slice()) as u64;
        if self.work.size() < work_bytes {
            self.work = storage(gpu, "light bvh refit work", work_bytes.next_power_of_two());
            self.group = None;
        }
        if self.leaf_bounds.size() < leaf_bytes {
            self.leaf_bounds = storage(
                gpu,
                "light bvh refit leaves",
                leaf_bytes.next_power_of_two(),
            );
            self.group = None;
        }
        gpu.queue
            .write_buffer(&self.work, 0, bytemuck::cast_slice(&s.work));
        gpu.queue
            .write_buffer(&self.leaf_bounds, 0, bytemuck::cast_slice(&s.leaf_bounds));
        s.slots.clear();
        s.slots
            .resize(s.levels.len() * self.level_stride as usize, 0);
        for (i, level) in s.levels.iter().enumerate() {
            let at = i * self.level_stride as usize;
            s.slots[at..at + std::mem::size_of::<GpuRefitLevel>()]
                .copy_from_slice(bytemuck::bytes_of(level));
        }
        gpu.queue.write_buffer(&self.levels, 0, &s.slots);
        if self.group.as_ref().is_some_and(|(bound, _)| bound == nodes) {
            return;
        }
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("light bvh refit"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: nodes.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.bounds.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: self.work.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: self.leaf_bounds.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &self.levels,
                        offset: 0,
                        size: wgpu::BufferSize::new(std::mem::size_of::<GpuRefitLevel>() as u64),
                    }),
                },
            ],
        });
        self.group = Some((nodes.clone(), group));
    }
}
