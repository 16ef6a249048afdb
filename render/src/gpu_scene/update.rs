//! Per-frame scene update for animated scenes: triangles and the BVH when geometry moved
//! (a refit: same tree, new boxes — measured against a rebuild in docs/bench.md), the light
//! table, punctual lights and materials only when lights changed. Buffers are rewritten in
//! place, so bind groups stay valid, and light-table indices stay the light's identity
//! (fixed slots, see `LightTable::build_with_slots`): the previous → current light map is
//! the identity and temporal reuse needs no remap pass.

use std::time::Instant;

use glam::Vec3;

use super::{GpuScene, gpu_materials, light_geometry, triangle_records};
use crate::gpu::Gpu;
use crate::scene::Scene;
use crate::scene::animation::SceneChange;
use crate::scene::lights::LightTable;

/// What one update cost on the CPU (milliseconds), for `--stats` and docs/bench.md.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct SceneUpdateTimes {
    /// Refitting the BVH to the new positions.
    pub bvh_ms: f64,
    /// Rebuilding the light table (alias table included).
    pub lights_ms: f64,
    /// Building the GPU records and queueing their upload.
    pub upload_ms: f64,
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
        let lights = if change.lights {
            let t = Instant::now();
            let table = LightTable::build_with_slots(
                scene,
                &self.bvh.triangle_order,
                &self.kept_materials,
                self.keep_punctual,
            );
            times.lights_ms = t.elapsed().as_secs_f64() * 1e3;
            Some(table)
        } else {
            None
        };
        if change.geometry {
            self.keep_previous_triangles(gpu);
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
            if let Some(table) = &lights {
                self.light_geometry = light_geometry(table, &triangles);
            }
            self.bounds = scene.bounds();
            self.info.bounds_min = self.bounds.min.into();
            self.info.bounds_max = self.bounds.max.into();
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
                gpu.queue.write_buffer(
                    &self.buffers.lights,
                    0,
                    bytemuck::cast_slice(&table.lights),
                );
                if !table.punctual.is_empty() {
                    gpu.queue.write_buffer(
                        &self.buffers.punctual,
                        0,
                        bytemuck::cast_slice(&table.punctual),
                    );
                }
                let materials = gpu_materials(scene);
                gpu.queue.write_buffer(
                    &self.buffers.materials,
                    0,
                    bytemuck::cast_slice(&materials),
                );
                self.sampleable = table.sampleable();
                self.light_pdfs = table.lights.iter().map(|l| l.select_pdf).collect();
                self.info.power_range = table.power_range;
                self.info.total_power = table.total_power;
                if !change.geometry {
                    for (entry, g) in table.lights.iter().zip(&mut self.light_geometry) {
                        if entry.kind_prim >> crate::gpu_types::LIGHT_KIND_SHIFT
                            != crate::gpu_types::LIGHT_KIND_TRIANGLE
                        {
                            let index =
                                (entry.kind_prim & crate::gpu_types::LIGHT_PRIM_MASK) as usize;
                            *g = [Vec3::from(table.punctual[index].position); 3];
                        }
                    }
                }
            }
        }
        self.updated_since_frame = true;
        let total = start.elapsed().as_secs_f64() * 1e3;
        times.upload_ms = (total - times.bvh_ms - times.lights_ms).max(0.0);
        times
    }

    /// Called once per rendered frame: makes `prev_triangles` the triangles of the frame
    /// just before this one. After an update it already is (copied before the write); a
    /// frame without update copies current → previous, so a scene that stopped moving
    /// stops having motion.
    pub fn begin_frame(&mut self, gpu: &Gpu) {
        if self.updated_since_frame {
            self.updated_since_frame = false;
            self.prev_differs = true;
        } else if self.prev_differs {
            self.copy_triangles_to_previous(gpu);
            self.prev_differs = false;
        }
    }

    /// Before the first update since the last frame, last frame's triangles become the
    /// previous ones (later updates before the next frame keep them).
    fn keep_previous_triangles(&mut self, gpu: &Gpu) {
        if !self.updated_since_frame {
            self.copy_triangles_to_previous(gpu);
        }
    }

    fn copy_triangles_to_previous(&self, gpu: &Gpu) {
        if !self.dynamic {
            return; // `prev_triangles` is the triangle buffer itself
        }
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(
            &self.buffers.triangles,
            0,
            &self.prev_triangles,
            0,
            self.buffers.triangles.size(),
        );
        // Submitted now: queued writes land at the start of the *next* submission, so the
        // copy reads the old triangles and the frame sees the new ones.
        gpu.queue.submit([encoder.finish()]);
    }
}
