//! Group-2 bind groups, one per pass and arrangement of resolved resources (the
//! ping-pong produces a few), created on first use and kept until a bound buffer is
//! re-created (resize, scene change, a placeholder grown to full size).

use std::collections::HashMap;

use super::resolve::Bound;
use crate::frame_targets::FrameTargets;
use crate::gpu::Gpu;
use crate::gpu_types::GpuPassInfo;
use crate::passes::resources::LightData;
use crate::passes::{PassDef, PassLayouts};

/// Buffers some groups bind besides the size-dependent targets.
pub struct Uniforms<'a> {
    pub pass_info: &'a wgpu::Buffer,
    pub display: &'a wgpu::Buffer,
    /// The light samplers' buffers (one-element placeholders until a sampler is used).
    pub light_sampler: &'a crate::light_sampler::LightSamplerBuffers,
}

/// Per pass, per arrangement (looked up by slice: the common frame allocates nothing).
#[derive(Default)]
pub struct BindGroupCache {
    groups: HashMap<&'static str, HashMap<Vec<Bound>, wgpu::BindGroup>>,
}

impl BindGroupCache {
    pub fn clear(&mut self) {
        self.groups.clear();
    }

    pub fn get(
        &mut self,
        gpu: &Gpu,
        layouts: &PassLayouts,
        t: &FrameTargets,
        u: &Uniforms,
        pass: &'static PassDef,
        bound: &[Bound],
    ) -> wgpu::BindGroup {
        let arrangements = self.groups.entry(pass.name).or_default();
        if let Some(group) = arrangements.get(bound) {
            return group.clone();
        }
        let group = create(gpu, layouts.group2(pass), pass.name, t, u, bound);
        arrangements.insert(bound.to_vec(), group.clone());
        group
    }
}

/// One `PassInfo` slot of the pass-info buffer; the dispatch picks it by dynamic offset.
fn pass_info_binding(buffer: &wgpu::Buffer) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset: 0,
        size: wgpu::BufferSize::new(std::mem::size_of::<GpuPassInfo>() as u64),
    })
}

fn create(
    gpu: &Gpu,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    t: &FrameTargets,
    u: &Uniforms,
    bound: &[Bound],
) -> wgpu::BindGroup {
    let entries: Vec<_> = (0..)
        .zip(bound)
        .map(|(binding, b)| wgpu::BindGroupEntry {
            binding,
            resource: match *b {
                Bound::Surfaces(i) => t.surfaces[i].as_entire_binding(),
                Bound::Pixels(name) => t.pixels_named(name).as_entire_binding(),
                Bound::Chain(name, i) => t.chain_named(name, i).as_entire_binding(),
                Bound::PassInfo => pass_info_binding(u.pass_info),
                Bound::DisplayUniform => u.display.as_entire_binding(),
                Bound::Lights(data) => {
                    let l = u.light_sampler;
                    match data {
                        LightData::Presampled => &l.presampled,
                        LightData::BvhNodes => &l.bvh_nodes,
                        LightData::BvhTrails => &l.bvh_trails,
                    }
                    .as_entire_binding()
                }
                Bound::Visibility => wgpu::BindingResource::TextureView(&t.visibility),
                Bound::Output => wgpu::BindingResource::TextureView(&t.display_view),
            },
        })
        .collect();
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}
