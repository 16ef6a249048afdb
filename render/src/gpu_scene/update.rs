//! Per-frame scene update for animated scenes: triangles and the BVH when geometry moved
//! (a refit: same tree, new boxes, of the moving part only since that part is kept apart,
//! `scene::bvh::split`; a rebuild of that part once it has degraded, see `rebuild.rs` and
//! docs/src/measured/dynamic-scenes.md) and the TLAS of the ray-query backend (`accel.rs`), the
//! light
//! table, punctual lights and materials only when lights changed. Buffers are rewritten in
//! place, so bind groups stay valid, and light-table indices stay the light's identity
//! (fixed slots, see `LightTable::build_with_slots`): the previous → current light map is
//! the identity and temporal reuse needs no remap pass.

use std::ops::Range;
use std::time::Instant;

use glam::Vec3;

use super::GpuScene;
use super::rebuild::repoint_triangle_entries;
use super::records::{gpu_materials, light_areas, triangle_record, triangle_records};
use crate::gpu::{Gpu, write_runs};
use crate::gpu_types::NO_LIGHT;
use crate::scene::Scene;
use crate::scene::animation::SceneChange;
use crate::scene::bvh::{Bvh, RefitLinks};
use crate::scene::lights::LightTable;

/// Rewritten records closer than this go to the GPU in one write with those between.
const UPLOAD_GAP: usize = 64;

/// What an update of a few moved meshes needs to find their triangles in the tree.
pub(super) struct MotionIndex {
    /// Every triangle by its lowest vertex index, (vertex, scene triangle), sorted: the
    /// triangles of a moved vertex range are one slice of it.
    by_vertex: Vec<(u32, u32)>,
    /// Per scene triangle, its place in BVH order.
    slot: Vec<u32>,
    links: RefitLinks,
}

impl MotionIndex {
    fn new(scene: &Scene, bvh: &Bvh) -> MotionIndex {
        let mut by_vertex: Vec<(u32, u32)> = scene
            .triangles
            .iter()
            .enumerate()
            .map(|(t, tri)| (tri.indices.into_iter().min().unwrap_or(0), t as u32))
            .collect();
        by_vertex.sort_unstable();
        let mut slot = vec![0u32; scene.triangles.len()];
        for (p, &source) in bvh.triangle_order.iter().enumerate() {
            slot[source as usize] = p as u32;
        }
        MotionIndex {
            by_vertex,
            slot,
            links: bvh.refit_links(),
        }
    }

    /// The triangles (BVH order, ascending) whose vertices lie in `ranges`: a mesh's
    /// triangles use its own vertices only, so the lowest one tells.
    fn moved(&self, ranges: &[Range<u32>]) -> Vec<usize> {
        let mut out = Vec::new();
        for range in ranges {
            let from = self.by_vertex.partition_point(|&(v, _)| v < range.start);
            let to = self.by_vertex.partition_point(|&(v, _)| v < range.end);
            out.extend(
                self.by_vertex[from..to]
                    .iter()
                    .map(|&(_, t)| self.slot[t as usize] as usize),
            );
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// What one update cost on the CPU (milliseconds), for `--stats` and
/// docs/src/measured/many-lights.md.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct SceneUpdateTimes {
    /// Refitting the BVH to the new positions (and rebuilding it when due).
    pub bvh_ms: f64,
    /// Whether the refitted tree had degraded past `BVH_REBUILD_FACTOR` and was rebuilt.
    pub bvh_rebuilt: bool,
    /// Rebuilding the light table (alias table included).
    pub lights_ms: f64,
    /// Building the GPU records and queueing their upload.
    pub upload_ms: f64,
    /// Whether the light table was rebuilt (not for rigid emitter motion).
    pub light_table_rebuilt: bool,
    /// Triangles whose records were rewritten: those of the moved meshes when the
    /// update knows them, otherwise all.
    pub triangles_rewritten: usize,
}

impl SceneUpdateTimes {
    pub fn total_ms(&self) -> f64 {
        self.bvh_ms + self.lights_ms + self.upload_ms
    }
}

impl GpuScene {
    /// Brings the GPU copy up to `scene` (already posed) for what `change` says changed.
    pub fn update(&mut self, gpu: &Gpu, scene: &Scene, change: SceneChange) -> SceneUpdateTimes {
        let mut times = SceneUpdateTimes::default();
        if !change.geometry && !change.lights {
            return times;
        }
        let start = Instant::now();
        let first_update_of_frame = !self.updated_since_frame;
        // Before any write: last frame's data becomes the previous frame's.
        self.keep_previous_frame(gpu);
        // The moved triangles (BVH order), when posing named the moved meshes.
        let moved = change
            .moved_vertices
            .as_deref()
            .filter(|_| change.geometry && self.dynamic)
            .map(|ranges| {
                self.motion_index
                    .get_or_insert_with(|| MotionIndex::new(scene, &self.bvh))
                    .moved(ranges)
            });
        // Rigid emitter motion keeps every power: the table (alias probabilities) stays
        // valid, only the geometry it points at moved (the shader reads that from the
        // triangles). Rebuild only when emission changed or some emitter's area did.
        let rebuild_table = change.lights
            && (change.emission
                || self.directional
                || !self.light_areas_match(scene, moved.as_deref()));
        let lights = if rebuild_table {
            let t = Instant::now();
            // Over the slot order: slots stay where they were at upload, whatever the
            // tree's order is now (rebuild.rs); entries are repointed before the write.
            let table = LightTable::build_with_slots(
                scene,
                &self.slot_order,
                &self.kept_materials,
                self.keep_punctual,
            );
            times.lights_ms = t.elapsed().as_secs_f64() * 1e3;
            times.light_table_rebuilt = true;
            Some(table)
        } else {
            None
        };
        // The light entries this update changes; `None` once some change cannot name them.
        let mut changed_lights: Option<Vec<u32>> = Some(Vec::new());
        if change.geometry {
            let partial = moved.is_some_and(|moved| {
                self.update_moved(gpu, scene, moved, first_update_of_frame, &mut times)
                    .map(|lights| {
                        if let Some(changed) = &mut changed_lights {
                            changed.extend(lights);
                        }
                    })
                    .is_some()
            });
            if !partial {
                self.update_all_geometry(gpu, scene, first_update_of_frame, &mut times);
                changed_lights = None;
            }
            self.light_motion_generation += 1;
            self.bounds = scene.bounds();
            self.info.bounds_min = self.bounds.min.into();
            self.info.bounds_max = self.bounds.max.into();
        }
        if change.lights && !scene.punctual_lights.is_empty() {
            // Moved or changed punctual lights: their records, whether or not the table is.
            let punctual: Vec<_> = scene
                .punctual_lights
                .iter()
                .map(crate::scene::lights::gpu_punctual)
                .collect();
            gpu.queue
                .write_buffer(&self.buffers.punctual, 0, bytemuck::cast_slice(&punctual));
            for (entry, (g, kind)) in self
                .light_geometry
                .iter_mut()
                .zip(&self.light_geometry_kinds)
                .enumerate()
            {
                if let Some((false, index)) = *kind {
                    let now = Some([scene.punctual_lights[index as usize].position; 3]);
                    if *g != now
                        && let Some(changed) = &mut changed_lights
                    {
                        changed.push(entry as u32);
                    }
                    *g = now;
                }
            }
            self.light_motion_generation += 1;
        }
        if change.emission {
            let materials = gpu_materials(scene);
            gpu.queue
                .write_buffer(&self.buffers.materials, 0, bytemuck::cast_slice(&materials));
        }
        if let Some(table) = lights {
            if table.lights.len() as u32 != self.light_count {
                // Cannot happen with fixed slots; refusing beats a buffer overrun.
                log::error!(
                    "light table changed size ({} → {}); lights not updated",
                    self.light_count,
                    table.lights.len()
                );
            } else {
                self.sampleable = table.sampleable();
                self.light_areas = light_areas(scene, &self.slot_order, &table);
                let mut entries = table.entries;
                repoint_triangle_entries(&mut entries, &self.slot_order, &self.bvh.triangle_order);
                if let Some(changed) = &mut changed_lights {
                    // A new power (a light switched on or off, or its colour changed).
                    changed
                        .extend((0..entries.len() as u32).filter(|&e| {
                            entries[e as usize].1 != self.light_entries[e as usize].1
                        }));
                }
                self.light_entries = entries;
                // Through the environment share, as at upload (it also sets light_pdfs).
                self.write_light_table(gpu);
                self.light_power_generation += 1;
                self.info.power_range = table.power_range;
                self.info.total_power = table.total_power;
            }
        }
        if change.lights || change.geometry {
            self.light_changes.record(changed_lights);
        }
        self.updated_since_frame = true;
        let total = start.elapsed().as_secs_f64() * 1e3;
        times.upload_ms = (total - times.bvh_ms - times.lights_ms).max(0.0);
        times
    }

    /// Every triangle rewritten and the whole tree refitted (rebuilt when due): for an
    /// update that cannot say what moved, or when the tree has degraded.
    fn update_all_geometry(
        &mut self,
        gpu: &Gpu,
        scene: &Scene,
        first_update_of_frame: bool,
        times: &mut SceneUpdateTimes,
    ) {
        let positions: Vec<[Vec3; 3]> = (0..scene.triangles.len())
            .map(|t| scene.triangle_positions(t))
            .collect();
        let t = Instant::now();
        let ordered: Vec<[Vec3; 3]> = self
            .bvh
            .triangle_order
            .iter()
            .map(|&i| positions[i as usize])
            .collect();
        self.bvh.refit(&ordered);
        if self.rebuild_due() {
            self.rebuild_bvh(gpu, &positions, self.rebuild_plant);
            times.bvh_rebuilt = true;
        }
        if let Some(accel) = &mut self.accel {
            if times.bvh_rebuilt {
                accel.rewrite_map(gpu, &self.bvh.triangle_order);
            }
            accel.moved(gpu, scene, first_update_of_frame);
        }
        times.bvh_ms = t.elapsed().as_secs_f64() * 1e3;
        // The light slots are fixed, so the per-triangle light index is too.
        let (triangles, shading) = triangle_records(
            scene,
            &self.bvh.triangle_order,
            &positions,
            &self.triangle_light,
        );
        gpu.queue
            .write_buffer(&self.buffers.triangles, 0, bytemuck::cast_slice(&triangles));
        gpu.queue
            .write_buffer(&self.buffers.shading, 0, bytemuck::cast_slice(&shading));
        gpu.queue.write_buffer(
            &self.buffers.bvh_nodes,
            0,
            bytemuck::cast_slice(&self.bvh.nodes),
        );
        self.light_geometry = self
            .light_geometry_kinds
            .iter()
            .map(|kind| {
                kind.map(|(is_triangle, index)| {
                    if is_triangle {
                        let t = &triangles[index as usize];
                        [t.p0, t.p1, t.p2].map(Vec3::from)
                    } else {
                        [scene.punctual_lights[index as usize].position; 3]
                    }
                })
            })
            .collect();
        times.triangles_rewritten = triangles.len();
        self.triangle_records = triangles;
        if self.dynamic {
            self.shading_records = shading;
        }
    }

    /// Only the `moved` triangles (BVH order, ascending) rewritten, and the tree refitted
    /// above them (`Bvh::refit_moved`): the same buffers as `update_all_geometry` at the
    /// cost of what moved. Returns the light entries among them, or `None` (nothing
    /// written) when the refitted tree is due for a rebuild.
    fn update_moved(
        &mut self,
        gpu: &Gpu,
        scene: &Scene,
        moved: Vec<usize>,
        first_update_of_frame: bool,
        times: &mut SceneUpdateTimes,
    ) -> Option<Vec<u32>> {
        let t = Instant::now();
        let links = &self.motion_index.as_ref()?.links;
        let rewritten = self
            .bvh
            .refit_moved(links, &moved, |s| scene.triangle_positions(s as usize));
        if self.rebuild_due() {
            return None;
        }
        if let Some(accel) = &mut self.accel {
            accel.moved(gpu, scene, first_update_of_frame);
        }
        times.bvh_ms = t.elapsed().as_secs_f64() * 1e3;
        times.triangles_rewritten = moved.len();
        let mut lights = Vec::new();
        for &p in &moved {
            let source = self.bvh.triangle_order[p];
            let light = self.triangle_light[p];
            let (triangle, shading) = triangle_record(
                scene,
                source,
                scene.triangle_positions(source as usize),
                light,
            );
            self.triangle_records[p] = triangle;
            self.shading_records[p] = shading;
            if light != NO_LIGHT {
                let corners = [triangle.p0, triangle.p1, triangle.p2].map(Vec3::from);
                self.light_geometry[light as usize] = Some(corners);
                lights.push(light);
            }
        }
        let b = &self.buffers;
        write_runs(
            gpu,
            &b.triangles,
            &self.triangle_records,
            &moved,
            UPLOAD_GAP,
        );
        write_runs(gpu, &b.shading, &self.shading_records, &moved, UPLOAD_GAP);
        write_runs(gpu, &b.bvh_nodes, &self.bvh.nodes, &rewritten, UPLOAD_GAP);
        Some(lights)
    }

    /// Whether every triangle light still has the area it had at the last table build
    /// (relative 1e-4: rigid motion changes areas by rounding only): of the `moved`
    /// triangles (BVH order) when the update names them, otherwise of every light.
    fn light_areas_match(&self, scene: &Scene, moved: Option<&[usize]>) -> bool {
        let unchanged = |entry: usize| {
            let Some(Some((source, area))) = self.light_areas.get(entry).copied() else {
                return true;
            };
            let [a, b, c] = scene.triangle_positions(source as usize);
            let now = 0.5 * (b - a).cross(c - a).length();
            (now - area).abs() <= 1e-4 * area.max(now)
        };
        match moved {
            Some(moved) => moved
                .iter()
                .map(|&p| self.triangle_light[p])
                .filter(|&light| light != NO_LIGHT)
                .all(|light| unchanged(light as usize)),
            None => (0..self.light_areas.len()).all(unchanged),
        }
    }

    /// Called once per rendered frame: makes the previous-frame buffers (triangles,
    /// materials, punctual lights) hold the frame just before this one. After an update
    /// they already do (copied before the write); a frame without update copies current →
    /// previous, so a scene that stopped changing stops having motion or light changes.
    pub fn begin_frame(&mut self, gpu: &Gpu) {
        if self.updated_since_frame {
            self.updated_since_frame = false;
            self.prev_differs = true;
        } else if self.prev_differs {
            self.copy_current_to_previous(gpu);
            if let Some(accel) = &mut self.accel {
                accel.settle(gpu);
            }
            self.prev_differs = false;
        }
    }

    /// Before the first update since the last frame, last frame's data becomes the
    /// previous frame's (later updates before the next frame keep it).
    fn keep_previous_frame(&mut self, gpu: &Gpu) {
        if !self.updated_since_frame {
            self.copy_current_to_previous(gpu);
        }
    }

    fn copy_current_to_previous(&mut self, gpu: &Gpu) {
        if !self.dynamic {
            return; // the previous-frame buffers are the current ones
        }
        self.prev_triangle_records
            .clone_from(&self.triangle_records);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        for (current, previous) in [
            (&self.buffers.triangles, &self.prev_triangles),
            (&self.buffers.materials, &self.prev_materials),
            (&self.buffers.punctual, &self.prev_punctual),
            (&self.buffers.bvh_nodes, &self.prev_bvh_nodes),
        ] {
            encoder.copy_buffer_to_buffer(current, 0, previous, 0, current.size());
        }
        // Submitted now: queued writes land at the start of the *next* submission, so the
        // copy reads the old triangles and the frame sees the new ones.
        gpu.queue.submit([encoder.finish()]);
    }
}
