//! Uploading a CPU `Scene`: BVH build, triangle reordering, light table, materials and
//! textures, into the eight storage buffers of bind group 1 (scene_bindings.wgsl).

use std::time::Instant;

use glam::Vec3;
use wgpu::util::DeviceExt;

use crate::environment::upload::EnvironmentResources;
use crate::gpu::Gpu;
use crate::gpu_types::*;
use crate::scene::bvh::Bvh;
use crate::scene::lights::LightTable;
use crate::scene::{Aabb, AlphaMode, Scene, Wrap};

/// Facts about an uploaded scene (the viewer's Scene panel, `--stats`).
#[derive(Clone, Debug, serde::Serialize)]
pub struct SceneInfo {
    pub name: String,
    pub triangles: usize,
    pub emissive_triangles: usize,
    pub punctual_lights: usize,
    pub light_table_entries: usize,
    /// Smallest and largest light power in the table (W·sr-ish luminance units).
    pub power_range: Option<(f32, f32)>,
    pub total_power: f64,
    pub bvh_nodes: usize,
    pub bvh_depth: usize,
    pub bvh_build_ms: f64,
    pub bounds_min: [f32; 3],
    pub bounds_max: [f32; 3],
    /// The environment: name, size, strength, rotation, share of the light power and
    /// the time its distribution took to build; `None` without one.
    pub environment: Option<EnvironmentInfo>,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct EnvironmentInfo {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub strength: f32,
    pub rotation_deg: f32,
    /// Probability that a light sample is an environment direction (its power share).
    pub light_share: f32,
    pub distribution_build_ms: f64,
}

pub struct GpuScene {
    pub bind_group: wgpu::BindGroup,
    pub triangle_count: u32,
    pub light_count: u32,
    pub punctual_count: u32,
    pub bounds: Aabb,
    /// Length of the bounds' diagonal (the unit of scale-relative thresholds).
    pub scale: f32,
    pub info: SceneInfo,
    pub bvh: Bvh,
    /// Per light-table entry: its triangle (or the punctual position three times; `None`
    /// for the environment), so the CPU can turn a reservoir's (light, uv) into a point
    /// for the inspector.
    light_geometry: Vec<Option<[Vec3; 3]>>,
    /// The environment's light-table index, `NO_LIGHT` when there is none.
    pub environment_light: u32,
    /// (cos, sin) of the environment's rotation, to turn a sample's uv into a direction.
    environment_rotation: [f32; 2],
    /// The light table's `(kind_prim, power)` entries and buffer, and the environment
    /// share it was last built with (`set_environment_share`).
    light_entries: Vec<(u32, f64)>,
    lights_buffer: wgpu::Buffer,
    environment_share: f32,
}

/// Octahedral encoding into two snorm16, bit-identical to `oct_encode` in math.wgsl.
pub fn oct_encode(n: Vec3) -> u32 {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    let mut p = glam::Vec2::new(n.x, n.y) / l1.max(1e-20);
    if n.z < 0.0 {
        let s = glam::Vec2::new(
            if p.x >= 0.0 { 1.0 } else { -1.0 },
            if p.y >= 0.0 { 1.0 } else { -1.0 },
        );
        p = (glam::Vec2::ONE - glam::Vec2::new(p.y.abs(), p.x.abs())) * s;
    }
    let snorm = |x: f32| ((x.clamp(-1.0, 1.0) * 32767.0).round() as i16) as u16 as u32;
    snorm(p.x) | (snorm(p.y) << 16)
}

fn wrap_code(w: Wrap) -> u32 {
    match w {
        Wrap::Repeat => 0,
        Wrap::ClampToEdge => 1,
        Wrap::MirroredRepeat => 2,
    }
}

/// A storage buffer with at least one element (WebGPU forbids empty bindings).
fn storage_buffer<T: bytemuck::Pod + Default>(gpu: &Gpu, label: &str, data: &[T]) -> wgpu::Buffer {
    let fallback = [T::default()];
    let contents: &[T] = if data.is_empty() { &fallback } else { data };
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(contents),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        })
}

impl GpuScene {
    pub fn upload(
        gpu: &Gpu,
        scene: &Scene,
        layout: &wgpu::BindGroupLayout,
    ) -> anyhow::Result<GpuScene> {
        let positions: Vec<[Vec3; 3]> = (0..scene.triangles.len())
            .map(|t| scene.triangle_positions(t))
            .collect();
        let start = Instant::now();
        let mut bvh = Bvh::build(&positions);
        if bvh.nodes.is_empty() {
            // No triangles (the loaders refuse this, but stay safe): one empty-handed leaf
            // over the zero fallback triangle, so traversal ends at once.
            bvh.nodes.push(GpuBvhNode {
                count: 1,
                ..Default::default()
            });
        }
        let bvh_build_ms = start.elapsed().as_secs_f64() * 1e3;
        let lights = LightTable::build(scene, &bvh.triangle_order);

        let mut triangles = Vec::with_capacity(positions.len());
        let mut shading = Vec::with_capacity(positions.len());
        for (bvh_index, &source) in bvh.triangle_order.iter().enumerate() {
            let tri = &scene.triangles[source as usize];
            let [p0, p1, p2] = positions[source as usize];
            let verts = tri.indices.map(|i| scene.vertices[i as usize]);
            let has_normals = verts.iter().all(|v| v.normal.length_squared() > 0.0);
            triangles.push(GpuTriangle {
                p0: p0.into(),
                material: tri.material,
                p1: p1.into(),
                light: lights.triangle_light[bvh_index],
                p2: p2.into(),
                source_index: source,
            });
            shading.push(GpuTriangleShading {
                normals: verts.map(|v| {
                    if has_normals {
                        oct_encode(v.normal.normalize())
                    } else {
                        0
                    }
                }),
                has_normals: has_normals as u32,
                uvs: verts.map(|v| v.uv.into()),
            });
        }

        let mut texels: Vec<u32> = Vec::new();
        let mut textures = Vec::with_capacity(scene.textures.len());
        for t in &scene.textures {
            textures.push(GpuTexture {
                offset: texels.len() as u32,
                width: t.width,
                height: t.height,
                wrap: wrap_code(t.wrap_u) | (wrap_code(t.wrap_v) << 4),
            });
            texels.extend(t.texels.iter().map(|c| u32::from_le_bytes(*c)));
        }
        let tex_index = |r: Option<crate::scene::TextureRef>| r.map_or(NO_TEXTURE, |r| r.texture);
        let materials: Vec<GpuMaterial> = scene
            .materials
            .iter()
            .map(|m| {
                let mut flags = 0;
                if m.double_sided {
                    flags |= MATERIAL_DOUBLE_SIDED;
                }
                let mut alpha_cutoff = 0.0;
                if let AlphaMode::Mask(cutoff) = m.alpha_mode {
                    flags |= MATERIAL_ALPHA_MASK;
                    alpha_cutoff = cutoff;
                }
                GpuMaterial {
                    base_color: m.base_color.into(),
                    emission: m.emission.into(),
                    metallic: m.metallic,
                    roughness: m.roughness,
                    specular: m.specular,
                    alpha_cutoff,
                    flags,
                    base_color_texture: tex_index(m.base_color_texture),
                    metallic_roughness_texture: tex_index(m.metallic_roughness_texture),
                    emissive_texture: tex_index(m.emissive_texture),
                    _pad: 0,
                }
            })
            .collect();

        let light_geometry = lights
            .lights
            .iter()
            .map(|l| {
                let index = (l.kind_prim & LIGHT_PRIM_MASK) as usize;
                match l.kind_prim >> LIGHT_KIND_SHIFT {
                    LIGHT_KIND_TRIANGLE => {
                        let t = &triangles[index];
                        Some([t.p0, t.p1, t.p2].map(Vec3::from))
                    }
                    LIGHT_KIND_PUNCTUAL => Some([Vec3::from(lights.punctual[index].position); 3]),
                    // An environment sample is a direction: it has no point.
                    _ => None,
                }
            })
            .collect();
        let environment = EnvironmentResources::upload(
            gpu,
            scene.environment.as_deref(),
            lights.environment_light,
        );
        let buffers = [
            storage_buffer(gpu, "triangles", &triangles),
            storage_buffer(gpu, "triangle shading", &shading),
            storage_buffer(gpu, "materials", &materials),
            storage_buffer(gpu, "textures", &textures),
            storage_buffer(gpu, "texels", &texels),
            storage_buffer(gpu, "lights", &lights.lights),
            storage_buffer(gpu, "punctual lights", &lights.punctual),
            storage_buffer(gpu, "bvh nodes", &bvh.nodes),
        ];
        let lights_buffer = buffers[5].clone();
        let refs: Vec<&wgpu::Buffer> = buffers.iter().collect();
        let mut entries = crate::passes::buffer_entries(&refs);
        entries.extend([
            wgpu::BindGroupEntry {
                binding: 8,
                resource: environment.table.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 9,
                resource: wgpu::BindingResource::TextureView(&environment.radiance),
            },
            wgpu::BindGroupEntry {
                binding: 10,
                resource: environment.uniform.as_entire_binding(),
            },
        ]);
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout,
            entries: &entries,
        });
        gpu.check()?;

        let bounds = scene.bounds();
        let scale = bounds.extent().length().max(1e-30);
        let info = SceneInfo {
            name: scene.name.clone(),
            triangles: triangles.len(),
            emissive_triangles: scene.emissive_triangle_count(),
            punctual_lights: scene.punctual_lights.len(),
            light_table_entries: lights.lights.len(),
            power_range: lights.power_range,
            total_power: lights.total_power,
            bvh_nodes: bvh.nodes.len(),
            bvh_depth: bvh.depth(),
            bvh_build_ms,
            bounds_min: bounds.min.into(),
            bounds_max: bounds.max.into(),
            environment: scene.environment.as_deref().map(|e| EnvironmentInfo {
                name: e.name.clone(),
                width: e.width,
                height: e.height,
                strength: e.strength,
                rotation_deg: e.rotation_deg,
                light_share: lights
                    .lights
                    .get(lights.environment_light as usize)
                    .map_or(0.0, |l| l.select_pdf),
                distribution_build_ms: e.build_ms,
            }),
        };
        Ok(GpuScene {
            bind_group,
            triangle_count: triangles.len() as u32,
            light_count: lights.lights.len() as u32,
            punctual_count: lights.punctual.len() as u32,
            bounds,
            scale,
            info,
            bvh,
            light_geometry,
            environment_light: lights.environment_light,
            environment_rotation: scene
                .environment
                .as_ref()
                .map_or([1.0, 0.0], |e| e.rotation_cos_sin()),
            light_entries: lights.entries,
            lights_buffer,
            environment_share: 0.0,
        })
    }

    /// Rebuilds the light table with the environment picked with probability `share` (0:
    /// by power; the `environment_share` setting) when it differs from the last one. Same
    /// size, so the buffer is rewritten in place and every bind group stays valid.
    pub fn set_environment_share(&mut self, gpu: &Gpu, share: f32) {
        if share == self.environment_share || self.environment_light == NO_LIGHT {
            return;
        }
        self.environment_share = share;
        let table = crate::scene::lights::with_environment_share(
            &self.light_entries,
            self.environment_light,
            share,
        );
        gpu.queue
            .write_buffer(&self.lights_buffer, 0, bytemuck::cast_slice(&table));
        if let Some(info) = self.info.environment.as_mut() {
            info.light_share = table[self.environment_light as usize].select_pdf;
        }
    }

    /// The direction of environment sample (light, uv), as `env_uv_to_direction` in
    /// environment.wgsl; `None` when `light` is not the environment.
    pub fn environment_direction(&self, light: u32, uv: [f32; 2]) -> Option<[f32; 3]> {
        (light == self.environment_light && light != NO_LIGHT)
            .then(|| crate::environment::uv_to_direction(uv, self.environment_rotation).into())
    }

    /// The world position of light sample (light, uv), as `light_point` in lights.wgsl.
    pub fn sample_point(&self, light: u32, uv: [f32; 2]) -> Option<[f32; 3]> {
        let [p0, p1, p2] = (*self.light_geometry.get(light as usize)?)?;
        Some((p0 * (1.0 - uv[0] - uv[1]) + p1 * uv[0] + p2 * uv[1]).into())
    }
}
