//! The ray-query backend's acceleration structures (render/src/tracing.rs): one BLAS for
//! every triangle that never moves (in world space), one BLAS per distinct moving mesh in
//! its node's space (meshes with the same local geometry share one: the 65,536 orbiting
//! quads of `dynamic:many-lights:65536` are one BLAS), and a TLAS of their instances,
//! rebuilt when something moves. Rigid motion — all the animation glTF and the built-ins
//! have: skins and morph targets load at rest — moves instances only, so no BLAS is
//! rebuilt or refitted after load; wgpu 30 could not refit one anyway (its
//! `PreferUpdate` rebuilds, in wgpu-core's ray-tracing commands). The software BVH's refit
//! and rebuild policy (`rebuild.rs`) answers a question this structure does not have.
//!
//! Last frame's geometry for temporal visibility is last frame's TLAS: two TLASes take
//! turns (`tlas[current]` this frame's, the other last frame's), the same BLASes at last
//! frame's transforms, as Bevy Solari keeps its previous TLAS for temporal shadows.
//!
//! Each BLAS has up to two geometries: triangles whose material needs no test (OPAQUE,
//! committed by the hardware) and those that do (alpha mask, transparency: every hit comes
//! back to the shader, trace_ray_query.wgsl). A hit names (instance, geometry, primitive);
//! the map buffer turns that into the triangle's slot in BVH order, which every other
//! scene buffer is indexed by. A rebuild of the software BVH reorders slots and rewrites
//! the map (`rewrite_map`); the acceleration structures stay.

use std::collections::HashMap;
use std::time::Instant;

use glam::{Mat4, Vec3};
use wgpu::util::DeviceExt;

use crate::gpu::Gpu;
use crate::scene::{AlphaMode, Scene};

/// Facts about the acceleration structures (Scene panel, `--stats`).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct AccelInfo {
    pub blas_count: usize,
    pub instance_count: usize,
    /// Triangles the hardware commits without asking the shader.
    pub opaque_triangles: usize,
    /// Building the BLASes and the first TLAS (CPU time to record and wait for them).
    pub build_ms: f64,
}

/// One TLAS instance: its BLAS and the moving mesh that places it (none: the static scene,
/// at the identity).
#[derive(Clone, Copy, Debug)]
struct Instance {
    blas: usize,
    mesh: Option<usize>,
    transform: [f32; 12],
}

/// A BLAS's triangles in primitive order: opaque ones first, then those the shader tests.
struct BlasPlan {
    opaque: usize,
    tested: usize,
    /// 3 vertices per triangle, primitive order.
    positions: Vec<[f32; 3]>,
}

pub struct AccelStructures {
    /// The instances hold them alive; kept for clarity of ownership.
    _blases: Vec<wgpu::Blas>,
    instances: Vec<Instance>,
    /// One TLAS for a static scene; two taking turns for an animated one.
    tlas: Vec<wgpu::Tlas>,
    current: usize,
    /// Whether the other TLAS holds the current transforms too (nothing moved last frame).
    previous_is_current: bool,
    map: wgpu::Buffer,
    /// Per instance, the source triangles (scene order) of its primitives, concatenated in
    /// the order of the map's slot part: map[header + k] is the BVH slot of sources[k].
    sources: Vec<u32>,
    pub info: AccelInfo,
}

/// glam's column-major matrix as the 3 × 4 row-major affine transform of a TLAS instance.
fn affine_rows(m: Mat4) -> [f32; 12] {
    let c = m.to_cols_array_2d();
    std::array::from_fn(|i| c[i % 4][i / 4])
}

/// A triangle whose hits the shader must see: alpha-tested or letting light through.
fn needs_test(scene: &Scene, triangle: usize) -> bool {
    scene
        .materials
        .get(scene.triangles[triangle].material as usize)
        .is_none_or(|m| matches!(m.alpha_mode, AlphaMode::Mask(_)) || m.is_transparent())
}

/// For each triangle (scene order), the animation mesh binding whose vertices it uses.
fn triangle_meshes(scene: &Scene) -> Vec<Option<usize>> {
    match &scene.animation {
        Some(anim) => anim.triangle_bindings(&scene.triangles),
        None => vec![None; scene.triangles.len()],
    }
}

/// The world matrix of each moving mesh as posed (`Scene::mesh_transforms`), its node's
/// rest matrix where none was recorded or the pose is degenerate (as `pose` keeps a
/// vertex's last good position).
pub fn mesh_world_matrices(scene: &Scene) -> Vec<Mat4> {
    let Some(anim) = &scene.animation else {
        return Vec::new();
    };
    let rest = anim.nodes.world_matrices(&anim.nodes.rest_locals());
    anim.meshes
        .iter()
        .enumerate()
        .map(|(i, mesh)| {
            scene
                .mesh_transforms
                .get(i)
                .copied()
                .filter(|m| m.is_finite())
                .unwrap_or_else(|| rest.get(mesh.node).copied().unwrap_or(Mat4::IDENTITY))
        })
        .collect()
}

impl AccelStructures {
    /// Builds everything for `scene` (already uploaded: `triangle_order` is the BVH order
    /// its slots follow) and waits for the build.
    pub fn build(gpu: &Gpu, scene: &Scene, triangle_order: &[u32]) -> anyhow::Result<Self> {
        let start = Instant::now();
        let meshes = triangle_meshes(scene);
        let world = mesh_world_matrices(scene);
        // Primitive order inside a BLAS: opaque triangles, then tested ones, each in the
        // order of the software BVH's slots (its leaves depth first: spatially coherent).
        // Drivers sort primitives themselves, but lavapipe splits them at the median of
        // the order given (Mesa's lvp_acceleration_structure.c): in scene order the
        // scattered quads of builtin:many-lights:4096 made its tree nearly a list, and
        // its rays 50× slower than the BVH's; in slot order the tree is as good as ours.
        let mut slot = vec![0u32; triangle_order.len()];
        for (p, &source) in triangle_order.iter().enumerate() {
            slot[source as usize] = p as u32;
        }
        let partition = |tris: &mut Vec<usize>| {
            tris.sort_by_key(|&t| (needs_test(scene, t), slot[t]));
        };
        let mut static_tris: Vec<usize> = Vec::new();
        let mut mesh_tris: Vec<Vec<usize>> = match &scene.animation {
            Some(a) => vec![Vec::new(); a.meshes.len()],
            None => Vec::new(),
        };
        for (t, mesh) in meshes.iter().enumerate() {
            match mesh {
                Some(m) => mesh_tris[*m].push(t),
                None => static_tris.push(t),
            }
        }
        partition(&mut static_tris);
        mesh_tris.iter_mut().for_each(partition);
        // Instances in the order of their first slot, for the same reason (lavapipe builds
        // the TLAS by the same median split).
        let mut mesh_order: Vec<usize> = (0..mesh_tris.len()).collect();
        mesh_order.sort_by_key(|&m| mesh_tris[m].iter().map(|&t| slot[t]).min());

        let mut plans: Vec<BlasPlan> = Vec::new();
        let mut instances: Vec<Instance> = Vec::new();
        let mut sources: Vec<u32> = Vec::new();
        let plan_of = |tris: &[usize], position: &dyn Fn(u32) -> Vec3| {
            let tested = tris.iter().filter(|&&t| needs_test(scene, t)).count();
            BlasPlan {
                opaque: tris.len() - tested,
                tested,
                positions: tris
                    .iter()
                    .flat_map(|&t| scene.triangles[t].indices.map(|i| position(i).to_array()))
                    .collect(),
            }
        };
        if !static_tris.is_empty() {
            plans.push(plan_of(&static_tris, &|i| {
                scene.vertices[i as usize].position
            }));
            instances.push(Instance {
                blas: 0,
                mesh: None,
                transform: affine_rows(Mat4::IDENTITY),
            });
            sources.extend(static_tris.iter().map(|&t| t as u32));
        }
        // Moving meshes, one BLAS per distinct (local positions, test classes).
        let mut distinct: HashMap<Vec<u32>, usize> = HashMap::new();
        if let Some(anim) = &scene.animation {
            for &m in &mesh_order {
                let tris = &mesh_tris[m];
                if tris.is_empty() {
                    continue;
                }
                let mesh = &anim.meshes[m];
                let local = |i: u32| {
                    mesh.local
                        .get((i - mesh.first) as usize)
                        .map_or(Vec3::ZERO, |v| v.position)
                };
                let key: Vec<u32> = tris
                    .iter()
                    .flat_map(|&t| {
                        let tri = scene.triangles[t];
                        std::iter::once(needs_test(scene, t) as u32).chain(
                            tri.indices
                                .into_iter()
                                .flat_map(|i| local(i).to_array().map(f32::to_bits)),
                        )
                    })
                    .collect();
                let blas = *distinct.entry(key).or_insert_with(|| {
                    plans.push(plan_of(tris, &local));
                    plans.len() - 1
                });
                instances.push(Instance {
                    blas,
                    mesh: Some(m),
                    transform: affine_rows(world[m]),
                });
                sources.extend(tris.iter().map(|&t| t as u32));
            }
        }
        anyhow::ensure!(
            instances.len() < 1 << 24,
            "{} moving meshes: a TLAS instance's custom index has 24 bits",
            instances.len()
        );

        let blases = build_blases(gpu, &plans)?;
        let tlas_count = if scene.animation.is_some() { 2 } else { 1 };
        let mut structures = AccelStructures {
            tlas: (0..tlas_count)
                .map(|i| {
                    gpu.device.create_tlas(&wgpu::CreateTlasDescriptor {
                        label: Some(if i == 0 { "tlas a" } else { "tlas b" }),
                        max_instances: instances.len().max(1) as u32,
                        flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
                        update_mode: wgpu::AccelerationStructureUpdateMode::Build,
                    })
                })
                .collect(),
            map: map_buffer(
                gpu,
                &map_contents(&instances, &plans, &sources, triangle_order),
            ),
            info: AccelInfo {
                blas_count: plans.len(),
                instance_count: instances.len(),
                opaque_triangles: plans.iter().map(|p| p.opaque).sum(),
                build_ms: 0.0,
            },
            _blases: blases,
            instances,
            current: 0,
            previous_is_current: true,
            sources,
        };
        for slot in 0..tlas_count {
            structures.build_tlas(gpu, slot);
        }
        gpu.wait_idle();
        gpu.check()?;
        structures.info.build_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(structures)
    }

    /// Whether two TLASes take turns (animated scenes).
    pub fn has_previous(&self) -> bool {
        self.tlas.len() == 2
    }

    /// This frame's TLAS and last frame's (the same one for a static scene).
    pub fn current_and_previous(&self) -> (&wgpu::Tlas, &wgpu::Tlas) {
        let previous = (self.current + 1) % self.tlas.len();
        (&self.tlas[self.current], &self.tlas[previous])
    }

    /// Which TLAS is this frame's (the bind group that binds it as current is chosen by it).
    pub fn current_slot(&self) -> usize {
        self.current
    }

    /// The TLASes as (current, previous) pairs for each value of `current_slot`.
    pub fn tlas_pairs(&self) -> Vec<(&wgpu::Tlas, &wgpu::Tlas)> {
        let n = self.tlas.len();
        (0..n)
            .map(|c| (&self.tlas[c], &self.tlas[(c + 1) % n]))
            .collect()
    }

    pub fn map(&self) -> &wgpu::Buffer {
        &self.map
    }

    /// The scene moved: the instances take `scene`'s mesh transforms. `new_frame` (the
    /// first move since the last frame) builds them into the other TLAS, which becomes this
    /// frame's while the old one stays as last frame's; a second move before the next frame
    /// rebuilds this frame's again.
    pub fn moved(&mut self, gpu: &Gpu, scene: &Scene, new_frame: bool) {
        if !self.has_previous() {
            return;
        }
        let world = mesh_world_matrices(scene);
        for instance in &mut self.instances {
            if let Some(m) = instance.mesh
                && let Some(w) = world.get(m)
            {
                instance.transform = affine_rows(*w);
            }
        }
        if new_frame {
            self.current = 1 - self.current;
        }
        self.build_tlas(gpu, self.current);
        self.previous_is_current = false;
    }

    /// A frame in which nothing moved: last frame's TLAS becomes this frame's too (as the
    /// previous-frame triangles do in `begin_frame`).
    pub fn settle(&mut self, gpu: &Gpu) {
        if self.has_previous() && !self.previous_is_current {
            self.build_tlas(gpu, 1 - self.current);
            self.previous_is_current = true;
        }
    }

    /// After the software BVH was rebuilt (its slots reordered): the map points at the
    /// triangles' new slots.
    pub fn rewrite_map(&self, gpu: &Gpu, triangle_order: &[u32]) {
        let header = 2 * self.instances.len();
        let slots = slots_of(&self.sources, triangle_order);
        gpu.queue
            .write_buffer(&self.map, (header * 4) as u64, bytemuck::cast_slice(&slots));
    }

    fn build_tlas(&mut self, gpu: &Gpu, slot: usize) {
        let tlas = &mut self.tlas[slot];
        for (i, instance) in self.instances.iter().enumerate() {
            tlas[i] = Some(wgpu::TlasInstance::new(
                &self._blases[instance.blas],
                instance.transform,
                i as u32,
                0xff,
            ));
        }
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.build_acceleration_structures(std::iter::empty(), [&*tlas]);
        gpu.queue.submit([encoder.finish()]);
    }
}

/// The BVH slot of each source triangle.
fn slots_of(sources: &[u32], triangle_order: &[u32]) -> Vec<u32> {
    let mut slot = vec![0u32; triangle_order.len()];
    for (p, &source) in triangle_order.iter().enumerate() {
        slot[source as usize] = p as u32;
    }
    sources.iter().map(|&s| slot[s as usize]).collect()
}

/// The map: per instance (index of its first slot entry, opaque primitives of its BLAS),
/// then the slots of every instance's primitives.
fn map_contents(
    instances: &[Instance],
    plans: &[BlasPlan],
    sources: &[u32],
    triangle_order: &[u32],
) -> Vec<u32> {
    let header = 2 * instances.len();
    let mut out = Vec::with_capacity(header + sources.len());
    let mut first = header as u32;
    for instance in instances {
        let plan = &plans[instance.blas];
        out.extend([first, plan.opaque as u32]);
        first += (plan.opaque + plan.tested) as u32;
    }
    out.extend(slots_of(sources, triangle_order));
    if out.is_empty() {
        out.push(0); // WebGPU forbids empty bindings
    }
    out
}

fn map_buffer(gpu: &Gpu, contents: &[u32]) -> wgpu::Buffer {
    gpu.device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("accel map"),
            contents: bytemuck::cast_slice(contents),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        })
}

/// Creates and builds one BLAS per plan from one vertex buffer (dropped once built).
fn build_blases(gpu: &Gpu, plans: &[BlasPlan]) -> anyhow::Result<Vec<wgpu::Blas>> {
    let limit = gpu.device.limits().max_blas_primitive_count as usize;
    if let Some(p) = plans.iter().find(|p| p.opaque + p.tested > limit) {
        anyhow::bail!(
            "{} triangles in one BLAS, the device allows {limit}",
            p.opaque + p.tested
        );
    }
    let positions: Vec<[f32; 3]> = plans.iter().flat_map(|p| p.positions.clone()).collect();
    if positions.is_empty() {
        return Ok(Vec::new());
    }
    let vertices = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("blas vertices"),
            contents: bytemuck::cast_slice(&positions),
            usage: wgpu::BufferUsages::BLAS_INPUT,
        });
    let size = |count: usize, opaque: bool| wgpu::BlasTriangleGeometrySizeDescriptor {
        vertex_format: wgpu::VertexFormat::Float32x3,
        vertex_count: (3 * count) as u32,
        index_format: None,
        index_count: None,
        flags: if opaque {
            wgpu::AccelerationStructureGeometryFlags::OPAQUE
        } else {
            // A layer reported twice would count its transmittance twice.
            wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION
        },
    };
    // (size, first vertex) of each geometry, opaque first, per plan.
    let mut first_vertex = 0u32;
    let geometries: Vec<Vec<(wgpu::BlasTriangleGeometrySizeDescriptor, u32)>> = plans
        .iter()
        .map(|p| {
            let mut g = Vec::new();
            for (count, opaque) in [(p.opaque, true), (p.tested, false)] {
                if count > 0 {
                    g.push((size(count, opaque), first_vertex));
                    first_vertex += 3 * count as u32;
                }
            }
            g
        })
        .collect();
    let blases: Vec<wgpu::Blas> = geometries
        .iter()
        .map(|g| {
            gpu.device.create_blas(
                &wgpu::CreateBlasDescriptor {
                    label: Some("blas"),
                    flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
                    update_mode: wgpu::AccelerationStructureUpdateMode::Build,
                },
                wgpu::BlasGeometrySizeDescriptors::Triangles {
                    descriptors: g.iter().map(|(s, _)| s.clone()).collect(),
                },
            )
        })
        .collect();
    let entries: Vec<wgpu::BlasBuildEntry> = blases
        .iter()
        .zip(&geometries)
        .map(|(blas, g)| wgpu::BlasBuildEntry {
            blas,
            geometry: wgpu::BlasGeometries::TriangleGeometries(
                g.iter()
                    .map(|(size, first)| wgpu::BlasTriangleGeometry {
                        size,
                        vertex_buffer: &vertices,
                        first_vertex: *first,
                        vertex_stride: 12,
                        index_buffer: None,
                        first_index: None,
                        transform_buffer: None,
                        transform_buffer_offset: None,
                    })
                    .collect(),
            ),
        })
        .collect();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.build_acceleration_structures(&entries, std::iter::empty());
    gpu.queue.submit([encoder.finish()]);
    Ok(blases)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instance_transforms_are_rows_of_the_affine_part() {
        let m = Mat4::from_cols_array_2d(&[
            [1.0, 2.0, 3.0, 0.0],
            [4.0, 5.0, 6.0, 0.0],
            [7.0, 8.0, 9.0, 0.0],
            [10.0, 11.0, 12.0, 1.0],
        ]);
        // Row 0 is (m00 m01 m02 m03) = x of each column.
        assert_eq!(
            affine_rows(m),
            [
                1.0, 4.0, 7.0, 10.0, 2.0, 5.0, 8.0, 11.0, 3.0, 6.0, 9.0, 12.0
            ]
        );
        let p = Vec3::new(0.5, -2.0, 3.0);
        let r = affine_rows(m);
        let by_rows = Vec3::new(
            r[0] * p.x + r[1] * p.y + r[2] * p.z + r[3],
            r[4] * p.x + r[5] * p.y + r[6] * p.z + r[7],
            r[8] * p.x + r[9] * p.y + r[10] * p.z + r[11],
        );
        assert_eq!(by_rows, m.transform_point3(p));
    }

    #[test]
    fn mesh_transforms_place_every_moving_vertex_where_the_pose_put_it() {
        for name in [
            "builtin:dynamic:moving-occluder",
            "builtin:dynamic:many-lights:16",
        ] {
            let mut scene = crate::scene::load_scene(name).unwrap();
            scene.pose(1.3, crate::scene::animation::ClipChoice::All);
            let anim = scene.animation.as_ref().unwrap();
            let world = mesh_world_matrices(&scene);
            for (m, mesh) in anim.meshes.iter().enumerate() {
                for (i, v) in mesh.local.iter().enumerate() {
                    let placed = world[m].transform_point3(v.position);
                    let posed = scene.vertices[mesh.first as usize + i].position;
                    assert!(
                        (placed - posed).length() < 1e-5,
                        "{name} mesh {m}: {placed} vs {posed}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_map_sends_every_primitive_to_its_slot() {
        // Two instances of one BLAS (1 opaque + 1 tested) and the static one (2 opaque).
        let plans = [
            BlasPlan {
                opaque: 2,
                tested: 0,
                positions: vec![],
            },
            BlasPlan {
                opaque: 1,
                tested: 1,
                positions: vec![],
            },
        ];
        let instance = |blas, mesh| Instance {
            blas,
            mesh,
            transform: affine_rows(Mat4::IDENTITY),
        };
        let instances = [
            instance(0, None),
            instance(1, Some(0)),
            instance(1, Some(1)),
        ];
        // Source triangles of the primitives, instance by instance.
        let sources = [4, 5, 0, 1, 2, 3];
        // BVH order: slot p holds source triangle order[p].
        let order = [3, 0, 5, 1, 4, 2];
        let map = map_contents(&instances, &plans, &sources, &order);
        let slot_of_hit = |instance: usize, geometry: u32, primitive: u32| {
            let first = map[2 * instance];
            let opaque = map[2 * instance + 1];
            let slot = map[(first + if geometry == 1 { opaque } else { 0 } + primitive) as usize];
            order[slot as usize]
        };
        assert_eq!(slot_of_hit(0, 0, 1), 5);
        assert_eq!(slot_of_hit(1, 0, 0), 0);
        assert_eq!(slot_of_hit(1, 1, 0), 1);
        assert_eq!(slot_of_hit(2, 1, 0), 3);
    }
}
