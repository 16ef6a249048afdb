//! Bind group 1, the scene: what each binding number holds (shaders/common/scene_bindings.wgsl
//! declares the same numbers) and the two layouts, without and with the ray-query backend's
//! acceleration structures. Pipelines of the software backend use the first, ray-query
//! pipelines the second (`SceneLayouts::for_backend`); passes never name a binding here.

use crate::gpu::Gpu;
use crate::gpu::bindings::{buffer_entries, storage, uniform};
use crate::tracing::RayBackend;

/// Storage bindings 0..: triangles, shading, materials, textures, texels, lights, punctual
/// lights, BVH nodes, then last frame's triangles, materials and punctual lights.
pub const SCENE_STORAGE_BINDINGS: u32 = 11;
/// The environment: table (storage), radiance (texture) and uniform from here on.
pub const ENVIRONMENT_FIRST_BINDING: u32 = SCENE_STORAGE_BINDINGS;
/// Last frame's BVH boxes (the current tree refitted to last frame's triangles).
pub const PREV_BVH_NODES_BINDING: u32 = ENVIRONMENT_FIRST_BINDING + 3;
/// Ray queries: this frame's TLAS, last frame's, and the triangle map (`accel.rs`).
pub const TLAS_BINDING: u32 = PREV_BVH_NODES_BINDING + 1;
pub const PREV_TLAS_BINDING: u32 = TLAS_BINDING + 1;
pub const ACCEL_MAP_BINDING: u32 = PREV_TLAS_BINDING + 1;

/// Every stage may read the scene (the raster pass's vertex and fragment shaders too).
fn all_stages() -> wgpu::ShaderStages {
    wgpu::ShaderStages::COMPUTE | wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT
}

fn read_only(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        visibility: all_stages(),
        ..storage(binding, true)
    }
}

fn acceleration_structure(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: all_stages(),
        ty: wgpu::BindingType::AccelerationStructure {
            vertex_return: false,
        },
        count: None,
    }
}

/// The entries of group 1 for one backend.
pub fn scene_layout_entries(backend: RayBackend) -> Vec<wgpu::BindGroupLayoutEntry> {
    let first = ENVIRONMENT_FIRST_BINDING;
    let mut entries: Vec<_> = (0..SCENE_STORAGE_BINDINGS).map(read_only).collect();
    entries.extend([
        read_only(first),
        wgpu::BindGroupLayoutEntry {
            binding: first + 1,
            visibility: all_stages(),
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        },
        uniform(first + 2, all_stages()),
        read_only(PREV_BVH_NODES_BINDING),
    ]);
    if backend == RayBackend::RayQuery {
        entries.extend([
            acceleration_structure(TLAS_BINDING),
            acceleration_structure(PREV_TLAS_BINDING),
            read_only(ACCEL_MAP_BINDING),
        ]);
    }
    entries
}

/// The scene group's layouts: the software backend's always, the ray-query one where the
/// device has ray queries.
#[derive(Clone)]
pub struct SceneLayouts {
    pub software: wgpu::BindGroupLayout,
    pub ray_query: Option<wgpu::BindGroupLayout>,
}

impl SceneLayouts {
    pub fn new(gpu: &Gpu) -> SceneLayouts {
        let layout = |backend: RayBackend| {
            gpu.device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(match backend {
                        RayBackend::Software => "scene",
                        RayBackend::RayQuery => "scene (ray queries)",
                    }),
                    entries: &scene_layout_entries(backend),
                })
        };
        SceneLayouts {
            software: layout(RayBackend::Software),
            ray_query: gpu.ray_query.then(|| layout(RayBackend::RayQuery)),
        }
    }

    /// The layout pipelines of `backend` use. The renderer resolves the backend against the
    /// device first (`tracing::resolve_for`), so a missing ray-query layout is a bug.
    pub fn for_backend(&self, backend: RayBackend) -> &wgpu::BindGroupLayout {
        match backend {
            RayBackend::Software => &self.software,
            RayBackend::RayQuery => self
                .ray_query
                .as_ref()
                .expect("ray-query pipelines are only built on devices with ray queries"),
        }
    }
}

/// The software backend's group-1 entries: the scene's storage buffers in binding order,
/// the environment and last frame's BVH boxes.
pub fn software_entries<'a>(
    storage: &[&'a wgpu::Buffer],
    environment: &'a super::environment::EnvironmentResources,
    prev_bvh_nodes: &'a wgpu::Buffer,
) -> Vec<wgpu::BindGroupEntry<'a>> {
    let first = ENVIRONMENT_FIRST_BINDING;
    let mut entries = buffer_entries(storage);
    entries.extend([
        wgpu::BindGroupEntry {
            binding: first,
            resource: environment.table.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: first + 1,
            resource: wgpu::BindingResource::TextureView(&environment.radiance),
        },
        wgpu::BindGroupEntry {
            binding: first + 2,
            resource: environment.uniform.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: PREV_BVH_NODES_BINDING,
            resource: prev_bvh_nodes.as_entire_binding(),
        },
    ]);
    entries
}

/// What the ray-query layout adds: this frame's TLAS, last frame's and the triangle map.
pub fn ray_query_entries<'a>(
    current: &'a wgpu::Tlas,
    previous: &'a wgpu::Tlas,
    map: &'a wgpu::Buffer,
) -> [wgpu::BindGroupEntry<'a>; 3] {
    [
        wgpu::BindGroupEntry {
            binding: TLAS_BINDING,
            resource: current.as_binding(),
        },
        wgpu::BindGroupEntry {
            binding: PREV_TLAS_BINDING,
            resource: previous.as_binding(),
        },
        wgpu::BindGroupEntry {
            binding: ACCEL_MAP_BINDING,
            resource: map.as_entire_binding(),
        },
    ]
}
