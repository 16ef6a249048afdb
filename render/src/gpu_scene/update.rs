//! Per-frame scene update for animated scenes: triangles and the BVH when geometry moved
//! (a refit: same tree, new boxes; a rebuild once the refitted tree has degraded, see
//! `rebuild.rs` and docs/bench.md) and the TLAS of the ray-query backend (`accel.rs`), the
//! light
//! table, punctual lights and materials only when lights changed. Buffers are rewritten in
//! place, so bind groups stay valid, and light-table indices stay the light's identity
//! (fixed slots, see `LightTable::build_with_slots`): the previous → current light map is
//! the identity and temporal reuse needs no remap pass.

use std::time::Instant;

use glam::Vec3;

use super::GpuScene;
use super::rebuild::repoint_triangle_entries;
use super::records::{gpu_materials, light_areas, triangle_records};
use crate::gpu::Gpu;
use crate::scene::Scene;
use crate::scene::animation::SceneChange;
use crate::scene::lights::LightTable;

/// What one update cost on the CPU (milliseconds), for `--stats` and docs/bench.md.
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
        // Rigid emitter motion keeps every power: the table (alias probabilities) stays
        // valid, only the geometry it points at moved (the shader reads that from the
        // triangles). Rebuild only when emission changed or some emitter's area did.
        let rebuild_table = change.lights
            && (change.emission || self.directional || !self.light_areas_match(scene));
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
        if change.geometry {
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
            self.light_motion_generation += 1;
            self.bounds = scene.bounds();
            self.info.bounds_min = self.bounds.min.into();
            self.info.bounds_max = self.bounds.max.into();
            self.triangle_records = triangles;
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
            for (g, kind) in self
                .light_geometry
                .iter_mut()
                .zip(&self.light_geometry_kinds)
            {
                if let Some((false, index)) = *kind {
                    *g = Some([scene.punctual_lights[index as usize].position; 3]);
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
                self.light_entries = entries;
                // Through the environment share, as at upload (it also sets light_pdfs).
                self.write_light_table(gpu);
                self.light_power_generation += 1;
                self.info.power_range = table.power_range;
                self.info.total_power = table.total_power;
            }
        }
        self.updated_since_frame = true;
        let total = start.elapsed().as_secs_f64() * 1e3;
        times.upload_ms = (total - times.bvh_ms - times.lights_ms).max(0.0);
        times
    }

    /// Whether every triangle light still has the area it had at the last table build
    /// (relative 1e-4: rigid motion changes areas by rounding only).
    fn light_areas_match(&self, scene: &Scene) -> bool {
        self.light_areas.iter().all(|&(source, area)| {
            let [a, b, c] = scene.triangle_positions(source as usize);
            let now = 0.5 * (b - a).cross(c - a).length();
            (now - area).abs() <= 1e-4 * area.max(now)
        })
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
