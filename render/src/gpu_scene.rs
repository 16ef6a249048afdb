//! Uploading a CPU `Scene`: BVH build, triangle reordering, light table, materials and
//! textures, into the storage buffers of bind group 1 (scene_bindings.wgsl, numbered in
//! `layout.rs`): eight for the current frame, four for the previous one (animated scenes),
//! the environment, and where the device has ray queries the acceleration structures
//! (`accel.rs`). `update.rs` rewrites them in place when an animated scene changes.

pub mod accel;
pub mod environment;
pub mod layout;
pub mod light_changes;
mod rebuild;
#[cfg(test)]
mod rebuild_tests;
mod records;
mod update;

pub use rebuild::BVH_REBUILD_FACTOR;
pub use records::oct_encode;
pub use update::SceneUpdateTimes;

use records::{
    LightShape, geometry_kind, gpu_materials, light_areas, light_geometry, light_shapes,
    light_slots, texture_records, triangle_records,
};

use std::time::Instant;

use glam::Vec3;
use wgpu::util::DeviceExt;

use crate::gpu::Gpu;
use crate::gpu_types::*;
use crate::scene::bvh::Bvh;
use crate::scene::bvh::split::MovingPart;
use crate::scene::lights::LightTable;
use crate::scene::{Aabb, Scene};
use crate::tracing::RayBackend;
use accel::{AccelInfo, AccelStructures};
use environment::EnvironmentResources;
use layout::SceneLayouts;
use light_changes::LightChangeLog;

pub use layout::SCENE_STORAGE_BINDINGS;

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
    /// Triangles in the tree's moving part, kept apart from the static ones
    /// (`scene::bvh::split`); 0 for a single tree.
    pub bvh_moving_triangles: usize,
    /// The phases from file to uploaded scene (loader's, then upload's; `load_phases.rs`).
    /// `render --stats` writes them, with the pipelines', as its own `load` block.
    #[serde(skip)]
    pub load: crate::load_phases::LoadPhases,
    pub bounds_min: [f32; 3],
    pub bounds_max: [f32; 3],
    /// The environment: name, size, strength, rotation, share of the light power and
    /// the time its distribution took to build; `None` without one.
    pub environment: Option<EnvironmentInfo>,
    /// What the loader did with each extension the file lists (`Scene::extensions`).
    pub extensions: Vec<crate::scene::ExtensionUse>,
    /// The file has no camera: the start camera frames the bounds (`Camera::framing`).
    pub camera_automatic: bool,
    /// The ray-query backend's acceleration structures (`None` on a device without ray
    /// queries).
    pub accel: Option<AccelInfo>,
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
    /// Group 1 for the software backend.
    bind_group: wgpu::BindGroup,
    /// Group 1 for the ray-query backend, one per TLAS slot (`AccelStructures::current_slot`);
    /// empty on a device without ray queries.
    ray_query_groups: Vec<wgpu::BindGroup>,
    /// The ray-query backend's acceleration structures (devices with ray queries).
    accel: Option<AccelStructures>,
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
    /// The light table's `(kind_prim, power)` entries, and the environment share it was
    /// last written with (`set_environment_share`).
    light_entries: Vec<(u32, f64)>,
    environment_share: f32,
    buffers: SceneBuffers,
    /// Last frame's triangles (object motion vectors, the pairwise MIS canonical term at
    /// the previous pixel). For a static scene this is the triangle buffer itself:
    /// previous = current, at no cost; so are the two below.
    pub prev_triangles: wgpu::Buffer,
    /// Last frame's materials (their emission) and punctual lights, same slots.
    prev_materials: wgpu::Buffer,
    prev_punctual: wgpu::Buffer,
    /// Last frame's BVH boxes: this frame's tree refitted to last frame's triangles (the
    /// software backend's previous geometry; the node buffer itself for a static scene).
    prev_bvh_nodes: wgpu::Buffer,
    /// Materials whose triangles keep a light-table slot at zero power (see
    /// `LightTable::build_with_slots`); empty for a static scene.
    kept_materials: Vec<bool>,
    keep_punctual: bool,
    /// False when no light has power (every light of a dynamic scene off): the shaders
    /// then sample no light (`frame.light_count` is 0) although the table has entries.
    sampleable: bool,
    /// The scene has an animation: the fields below are in use.
    pub dynamic: bool,
    /// Per triangle in BVH order, its light entry (fixed for the scene's lifetime).
    triangle_light: Vec<u32>,
    /// An update happened since the last `begin_frame`.
    updated_since_frame: bool,
    /// `prev_triangles` holds other positions than the current triangles.
    prev_differs: bool,
    /// Per light entry, its select_pdf as uploaded (tests and the inspector).
    light_pdfs: Vec<f32>,
    /// Per light entry, for a triangle: (source triangle, area at the last table build),
    /// to tell rigid emitter motion (table still valid) from a change of area (dynamic
    /// scenes).
    light_areas: Vec<Option<(u32, f32)>>,
    /// Per light entry: (is a triangle, BVH triangle or punctual index); `None` for the
    /// environment, which has no geometry.
    light_geometry_kinds: Vec<Option<(bool, u32)>>,
    /// A directional light's power depends on the scene's size: any motion rebuilds.
    directional: bool,
    /// Per light entry, what a light sampler needs beside its geometry (`LightShape`).
    light_shapes: Vec<LightShape>,
    /// Σ select_pdf over the lights with a position (not the environment, not directional):
    /// what the light BVH's PDF is scaled by (docs/src/light-samplers.md).
    finite_light_share: f32,
    /// Bumped when the lights' powers change (the light table is rebuilt) and when they
    /// move: a light BVH rebuilds on the first, refits on the second.
    pub light_power_generation: u64,
    pub light_motion_generation: u64,
    /// Dynamic scenes (`rebuild.rs`): the BVH order light slots were assigned in at upload
    /// (a slot is its triangle's identity for the animation, whatever the tree's order
    /// now), the SAH cost of the tree when last built, and CPU mirrors of the current and
    /// previous triangle records (a rebuild reorders the previous ones too).
    slot_order: Vec<u32>,
    built_sah: f64,
    /// The tree's moving part (`scene::bvh::split`), `None` for a single tree: what a
    /// rebuild rebuilds and `built_sah` measures.
    moving_part: Option<MovingPart>,
    triangle_records: Vec<GpuTriangle>,
    prev_triangle_records: Vec<GpuTriangle>,
    shading_records: Vec<GpuTriangleShading>,
    /// What an update of a few moved meshes needs (`update.rs`), made on the first such
    /// update and dropped when the tree is rebuilt.
    motion_index: Option<update::MotionIndex>,
    /// The light entries each recent update changed, for the light BVH's refit.
    pub light_changes: LightChangeLog,
    /// Refitted SAH over built SAH above which the tree is rebuilt (`BVH_REBUILD_FACTOR`;
    /// infinite: refit only).
    pub bvh_rebuild_factor: f64,
    /// Parts of a rebuild left out (tests only; `RebuildPlant::default()` otherwise).
    rebuild_plant: rebuild::RebuildPlant,
}

/// What a test reads back of the buffers an update rewrites (and of the light BVH's).
#[cfg(feature = "test-hooks")]
#[derive(Debug, PartialEq)]
pub struct SceneBufferContents {
    pub triangles: Vec<GpuTriangle>,
    pub shading: Vec<GpuTriangleShading>,
    pub bvh_nodes: Vec<GpuBvhNode>,
    pub light_bvh_nodes: Vec<GpuLightBvhNode>,
}

/// The storage buffers an update rewrites (bind group 1 holds them all).
struct SceneBuffers {
    triangles: wgpu::Buffer,
    shading: wgpu::Buffer,
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    punctual: wgpu::Buffer,
    bvh_nodes: wgpu::Buffer,
}

/// The BVH nodes to upload: for an animated scene padded to the most nodes any tree over
/// its triangles can have (2n − 1: every leaf holds one or more), so a rebuilt tree
/// (`rebuild.rs`) fits the buffer the bind group holds. Nodes past the tree are never
/// reached from the root.
fn node_capacity(scene: &Scene, bvh: &Bvh) -> Vec<GpuBvhNode> {
    let mut nodes = bvh.nodes.clone();
    if scene.animation.is_some() {
        let most = (2 * scene.triangles.len()).saturating_sub(1);
        nodes.resize(most.max(nodes.len()), GpuBvhNode::default());
    }
    nodes
}

/// The SAH cost the rebuild policy watches (`rebuild.rs`): the moving part's for a split
/// tree (the static part never degrades), the whole tree's otherwise.
fn tree_quality(bvh: &Bvh, moving_part: Option<MovingPart>) -> f64 {
    match moving_part {
        Some(part) => bvh.moving_sah_cost(part),
        None => bvh.sah_cost(),
    }
}

/// Σ select_pdf over the lights with a position.
fn finite_share(pdfs: &[f32], shapes: &[LightShape]) -> f32 {
    pdfs.iter()
        .zip(shapes)
        .filter(|(_, shape)| **shape != LightShape::Infinite)
        .map(|(pdf, _)| f64::from(*pdf))
        .sum::<f64>() as f32
}

/// A storage buffer with at least one element (WebGPU forbids empty bindings).
fn storage_buffer<T: bytemuck::Pod + Default>(gpu: &Gpu, label: &str, data: &[T]) -> wgpu::Buffer {
    let fallback = [T::default()];
    let contents: &[T] = if data.is_empty() { &fallback } else { data };
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(contents),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
        })
}

impl GpuScene {
    pub fn upload(gpu: &Gpu, scene: &Scene, layouts: &SceneLayouts) -> anyhow::Result<GpuScene> {
        let positions: Vec<[Vec3; 3]> = (0..scene.triangles.len())
            .map(|t| scene.triangle_positions(t))
            .collect();
        let start = Instant::now();
        // An animated scene keeps its moving meshes' triangles apart from the static ones,
        // so their motion refits and rebuilds their part of the tree only (bvh/split.rs).
        let (mut bvh, moving_part) = Bvh::build_split(&positions, &scene.moving_triangles());
        if bvh.nodes.is_empty() {
            // No triangles (the loaders refuse this, but stay safe): one empty-handed leaf
            // over the zero fallback triangle, so traversal ends at once.
            bvh.nodes.push(GpuBvhNode {
                count: 1,
                ..Default::default()
            });
        }
        let bvh_build_ms = start.elapsed().as_secs_f64() * 1e3;
        // The loader's phases, then the upload's (load_phases.rs).
        let mut load = scene.load_phases.clone();
        let quiet = &crate::load_phases::unwatched;
        load.record(
            quiet,
            "BVH build",
            bvh_build_ms,
            match moving_part {
                Some(part) => format!(
                    "{} triangles ({} moving, in their own subtree), {} nodes",
                    positions.len(),
                    positions.len() - part.first_slot,
                    bvh.nodes.len()
                ),
                None => format!("{} triangles, {} nodes", positions.len(), bvh.nodes.len()),
            },
        );
        let start = Instant::now();
        let (kept_materials, keep_punctual) = light_slots(scene);
        let lights = LightTable::build_with_slots(
            scene,
            &bvh.triangle_order,
            &kept_materials,
            keep_punctual,
        );
        load.record(
            quiet,
            "light table",
            start.elapsed().as_secs_f64() * 1e3,
            format!("{} entries (alias table included)", lights.lights.len()),
        );
        let start = Instant::now();
        let (triangles, shading) = triangle_records(
            scene,
            &bvh.triangle_order,
            &positions,
            &lights.triangle_light,
        );

        let (textures, texels) = texture_records(scene);
        let materials = gpu_materials(scene);
        let light_geometry = light_geometry(&lights, &triangles);
        let light_shapes = light_shapes(&lights, &triangles, &materials);
        let finite_light_share = finite_share(
            &lights
                .lights
                .iter()
                .map(|l| l.select_pdf)
                .collect::<Vec<_>>(),
            &light_shapes,
        );
        let buffers = SceneBuffers {
            triangles: storage_buffer(gpu, "triangles", &triangles),
            shading: storage_buffer(gpu, "triangle shading", &shading),
            materials: storage_buffer(gpu, "materials", &materials),
            lights: storage_buffer(gpu, "lights", &lights.lights),
            punctual: storage_buffer(gpu, "punctual lights", &lights.punctual),
            bvh_nodes: storage_buffer(gpu, "bvh nodes", &node_capacity(scene, &bvh)),
        };
        let (prev_triangles, prev_materials, prev_punctual, prev_bvh_nodes) =
            if scene.animation.is_some() {
                (
                    storage_buffer(gpu, "previous triangles", &triangles),
                    storage_buffer(gpu, "previous materials", &materials),
                    storage_buffer(gpu, "previous punctual lights", &lights.punctual),
                    storage_buffer(gpu, "previous bvh nodes", &node_capacity(scene, &bvh)),
                )
            } else {
                (
                    buffers.triangles.clone(),
                    buffers.materials.clone(),
                    buffers.punctual.clone(),
                    buffers.bvh_nodes.clone(),
                )
            };
        let refs = [
            &buffers.triangles,
            &buffers.shading,
            &buffers.materials,
            &storage_buffer(gpu, "textures", &textures),
            &storage_buffer(gpu, "texels", &texels),
            &buffers.lights,
            &buffers.punctual,
            &buffers.bvh_nodes,
            &prev_triangles,
            &prev_materials,
            &prev_punctual,
        ];
        debug_assert_eq!(refs.len() as u32, SCENE_STORAGE_BINDINGS);
        let environment = EnvironmentResources::upload(
            gpu,
            scene.environment.as_deref(),
            lights.environment_light,
        );
        let entries = layout::software_entries(&refs, &environment, &prev_bvh_nodes);
        let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene"),
            layout: &layouts.software,
            entries: &entries,
        });
        let texel_bytes = texels.len() * 4;
        load.record(
            quiet,
            "records and upload",
            start.elapsed().as_secs_f64() * 1e3,
            format!(
                "{} textures, {:.1} MiB of texels",
                scene.textures.len(),
                texel_bytes as f64 / (1 << 20) as f64
            ),
        );
        let start = Instant::now();
        let accel = match &layouts.ray_query {
            Some(_) => Some(AccelStructures::build(gpu, scene, &bvh.triangle_order)?),
            None => None,
        };
        if accel.is_some() {
            load.record(
                quiet,
                "acceleration structures",
                start.elapsed().as_secs_f64() * 1e3,
                "ray-query BLAS and TLAS built".into(),
            );
        }
        let ray_query_groups = match (&accel, &layouts.ray_query) {
            (Some(accel), Some(rq_layout)) => accel
                .tlas_pairs()
                .into_iter()
                .map(|(current, previous)| {
                    let mut e = entries.clone();
                    e.extend(layout::ray_query_entries(current, previous, accel.map()));
                    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("scene (ray queries)"),
                        layout: rq_layout,
                        entries: &e,
                    })
                })
                .collect(),
            _ => Vec::new(),
        };
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
            bvh_moving_triangles: moving_part.map_or(0, |p| positions.len() - p.first_slot),
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
            extensions: scene.extensions.clone(),
            camera_automatic: scene.camera_is_automatic(),
            accel: accel.as_ref().map(|a| a.info),
            load,
        };
        let light_areas = if scene.animation.is_some() {
            light_areas(scene, &bvh.triangle_order, &lights)
        } else {
            Vec::new()
        };
        let light_geometry_kinds = lights.lights.iter().map(geometry_kind).collect();
        let dynamic = scene.animation.is_some();
        let directional = scene
            .punctual_lights
            .iter()
            .any(|p| p.kind == crate::scene::PunctualKind::Directional);
        Ok(GpuScene {
            bind_group,
            ray_query_groups,
            accel,
            triangle_count: triangles.len() as u32,
            light_count: lights.lights.len() as u32,
            punctual_count: lights.punctual.len() as u32,
            bounds,
            scale,
            info,
            light_geometry,
            environment_light: lights.environment_light,
            environment_rotation: scene
                .environment
                .as_ref()
                .map_or([1.0, 0.0], |e| e.rotation_cos_sin()),
            environment_share: 0.0,
            buffers,
            prev_triangles,
            prev_materials,
            prev_punctual,
            prev_bvh_nodes,
            kept_materials,
            keep_punctual,
            sampleable: lights.sampleable(),
            dynamic: scene.animation.is_some(),
            triangle_light: if scene.animation.is_some() {
                lights.triangle_light
            } else {
                Vec::new()
            },
            updated_since_frame: false,
            prev_differs: false,
            light_pdfs: lights.lights.iter().map(|l| l.select_pdf).collect(),
            light_areas,
            light_geometry_kinds,
            directional,
            light_shapes,
            finite_light_share,
            light_power_generation: 0,
            light_motion_generation: 0,
            light_entries: lights.entries,
            slot_order: bvh.triangle_order.clone(),
            built_sah: tree_quality(&bvh, moving_part),
            moving_part,
            triangle_records: if dynamic {
                triangles.clone()
            } else {
                Vec::new()
            },
            prev_triangle_records: if dynamic { triangles } else { Vec::new() },
            shading_records: if dynamic { shading } else { Vec::new() },
            motion_index: None,
            light_changes: LightChangeLog::new(lights.lights.len()),
            bvh_rebuild_factor: BVH_REBUILD_FACTOR,
            rebuild_plant: Default::default(),
            bvh,
        })
    }

    /// Group 1 for pipelines of `backend` (the ray-query one binds this frame's TLAS and
    /// last frame's). The renderer resolves the backend against the device first.
    pub fn bind_group(&self, backend: RayBackend) -> &wgpu::BindGroup {
        match (backend, &self.accel) {
            (RayBackend::RayQuery, Some(accel)) => &self.ray_query_groups[accel.current_slot()],
            _ => &self.bind_group,
        }
    }

    /// The light count the shaders sample from (0 while no light has power).
    pub fn sampled_light_count(&self) -> u32 {
        if self.sampleable { self.light_count } else { 0 }
    }

    /// The current selection probability of light entry `light` (0 while it is off).
    pub fn light_select_pdf(&self, light: u32) -> Option<f32> {
        self.light_pdfs.get(light as usize).copied()
    }

    /// Rebuilds the light table with the environment picked with probability `share` (0:
    /// by power; the `environment_share` setting) when it differs from the last one. Same
    /// size, so the buffer is rewritten in place and every bind group stays valid.
    pub fn set_environment_share(&mut self, gpu: &Gpu, share: f32) {
        if share == self.environment_share || self.environment_light == NO_LIGHT {
            return;
        }
        self.environment_share = share;
        self.write_light_table(gpu);
    }

    /// Writes the light table from `light_entries` with the current environment share.
    fn write_light_table(&mut self, gpu: &Gpu) {
        let table = crate::scene::lights::with_environment_share(
            &self.light_entries,
            self.environment_light,
            self.environment_share,
        );
        gpu.queue
            .write_buffer(&self.buffers.lights, 0, bytemuck::cast_slice(&table));
        self.light_pdfs = table.iter().map(|l| l.select_pdf).collect();
        self.finite_light_share = finite_share(&self.light_pdfs, &self.light_shapes);
        if let Some(info) = self.info.environment.as_mut() {
            info.light_share = table
                .get(self.environment_light as usize)
                .map_or(0.0, |l| l.select_pdf);
        }
    }

    /// The direction of environment sample (light, uv), as `env_uv_to_direction` in
    /// environment.wgsl; `None` when `light` is not the environment.
    pub fn environment_direction(&self, light: u32, uv: [f32; 2]) -> Option<[f32; 3]> {
        (light == self.environment_light && light != NO_LIGHT)
            .then(|| crate::environment::uv_to_direction(uv, self.environment_rotation).into())
    }

    /// Σ select_pdf over the lights with a position (`finite_light_share` of the frame).
    pub fn finite_light_share(&self) -> f32 {
        self.finite_light_share
    }

    /// Each light entry as a light sampler's structure sees it (`light_sampler.rs`): its
    /// corners (a punctual light's position three times), power and sidedness, or `None`
    /// for an infinite light (the environment, a directional light).
    pub fn light_sampler_lights(&self) -> Vec<Option<crate::light_bvh::EmissiveTriangle>> {
        (0..self.light_entries.len() as u32)
            .map(|entry| self.light_sampler_light(entry))
            .collect()
    }

    #[cfg(feature = "test-hooks")]
    pub fn buffer_contents_for_tests(&self, gpu: &Gpu) -> SceneBufferContents {
        use crate::gpu::readback::read_buffer;
        let b = &self.buffers;
        SceneBufferContents {
            triangles: read_buffer(gpu, &b.triangles, 0, b.triangles.size()),
            shading: read_buffer(gpu, &b.shading, 0, b.shading.size()),
            bvh_nodes: read_buffer(gpu, &b.bvh_nodes, 0, b.bvh_nodes.size()),
            light_bvh_nodes: Vec::new(),
        }
    }

    /// Light entry `entry` as the light samplers see it (`None` without a position).
    pub fn light_sampler_light(&self, entry: u32) -> Option<crate::light_bvh::EmissiveTriangle> {
        let e = entry as usize;
        let p = (*self.light_geometry.get(e)?)?;
        let two_sided = match self.light_shapes.get(e)? {
            LightShape::Infinite => return None,
            LightShape::OneSided => false,
            LightShape::TwoSided => true,
        };
        Some(crate::light_bvh::EmissiveTriangle {
            p,
            power: self.light_entries.get(e)?.1 as f32,
            two_sided,
        })
    }

    /// The world position of light sample (light, uv), as `light_point` in lights.wgsl.
    pub fn sample_point(&self, light: u32, uv: [f32; 2]) -> Option<[f32; 3]> {
        let [p0, p1, p2] = (*self.light_geometry.get(light as usize)?)?;
        Some((p0 * (1.0 - uv[0] - uv[1]) + p1 * uv[0] + p2 * uv[1]).into())
    }
}
