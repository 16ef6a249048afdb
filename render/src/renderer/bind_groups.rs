//! Group-2 bind groups for every buffer arrangement the ping-pong produces, created on
//! first use and kept until the targets are re-created (resize).

use std::collections::HashMap;

use crate::frame_targets::FrameTargets;
use crate::gpu::Gpu;
use crate::gpu_types::GpuPassInfo;
use crate::passes::{PassLayouts, buffer_bind_group, buffer_entries};

/// A pass and the indices of the surface / reservoir buffers it reads and writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    Resolve {
        surfaces: usize,
    },
    Initial {
        surfaces: usize,
        out: usize,
        /// Whether `light_tiles` is the full tile buffer (it is re-created once).
        tiles: bool,
    },
    Temporal {
        surfaces: usize,
        input: usize,
        prev: usize,
        out: usize,
    },
    Spatial {
        surfaces: usize,
        input: usize,
        out: usize,
    },
    Shade {
        surfaces: usize,
        input: usize,
    },
    Presample,
    Reference {
        surfaces: usize,
    },
    Display {
        surfaces: usize,
        reservoirs: usize,
        accumulated: bool,
    },
}

/// Buffers some groups bind besides the size-dependent targets.
pub struct Uniforms<'a> {
    pub pass_info: &'a wgpu::Buffer,
    pub display: &'a wgpu::Buffer,
    /// The presampled light tiles (a one-element placeholder until tiles are used).
    pub light_tiles: &'a wgpu::Buffer,
    /// The scene's previous-frame triangles (the triangle buffer itself when static).
    pub prev_triangles: &'a wgpu::Buffer,
}

#[derive(Default)]
pub struct BindGroupCache {
    groups: HashMap<Key, wgpu::BindGroup>,
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
        key: Key,
    ) -> wgpu::BindGroup {
        self.groups
            .entry(key)
            .or_insert_with(|| create(gpu, layouts, t, u, key))
            .clone()
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
    layouts: &PassLayouts,
    t: &FrameTargets,
    u: &Uniforms,
    key: Key,
) -> wgpu::BindGroup {
    let prev_of = |s: usize| 1 - s;
    match key {
        Key::Resolve { surfaces } => gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("gbuffer resolve"),
            layout: &layouts.resolve,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&t.visibility),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: t.surfaces[surfaces].as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: u.prev_triangles.as_entire_binding(),
                },
            ],
        }),
        Key::Initial { surfaces, out, .. } => buffer_bind_group(
            gpu,
            "initial",
            &layouts.initial,
            &[
                &t.surfaces[surfaces],
                &t.reservoirs[out],
                &t.debug,
                u.light_tiles,
            ],
        ),
        Key::Presample => buffer_bind_group(
            gpu,
            "presample lights",
            &layouts.presample,
            &[u.light_tiles],
        ),
        Key::Temporal {
            surfaces,
            input,
            prev,
            out,
        } => buffer_bind_group(
            gpu,
            "temporal",
            &layouts.temporal,
            &[
                &t.surfaces[surfaces],
                &t.surfaces[prev_of(surfaces)],
                &t.reservoirs[input],
                &t.reservoirs[prev],
                &t.reservoirs[out],
                &t.debug,
            ],
        ),
        Key::Spatial {
            surfaces,
            input,
            out,
        } => gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("spatial"),
            layout: &layouts.spatial,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: t.surfaces[surfaces].as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: t.reservoirs[input].as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: t.reservoirs[out].as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: t.debug.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: pass_info_binding(u.pass_info),
                },
            ],
        }),
        Key::Shade { surfaces, input } => buffer_bind_group(
            gpu,
            "shade",
            &layouts.shade,
            &[
                &t.surfaces[surfaces],
                &t.reservoirs[input],
                &t.debug,
                &t.radiance,
                &t.accumulation,
            ],
        ),
        Key::Reference { surfaces } => gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("reference"),
            layout: &layouts.reference,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: t.radiance.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: t.accumulation.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: pass_info_binding(u.pass_info),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: t.surfaces[surfaces].as_entire_binding(),
                },
            ],
        }),
        Key::Display {
            surfaces,
            reservoirs,
            accumulated,
        } => {
            let image = if accumulated {
                &t.accumulation
            } else {
                &t.radiance
            };
            let buffers = [
                image,
                &t.surfaces[surfaces],
                &t.debug,
                &t.reservoirs[reservoirs],
                &t.reference,
                u.display,
            ];
            let mut entries = buffer_entries(&buffers);
            entries.push(wgpu::BindGroupEntry {
                binding: 6,
                resource: wgpu::BindingResource::TextureView(&t.display_view),
            });
            entries.push(wgpu::BindGroupEntry {
                binding: 7,
                resource: t.comparison.as_entire_binding(),
            });
            gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("display"),
                layout: &layouts.display,
                entries: &entries,
            })
        }
    }
}
