//! Refit, then rebuild when the refitted tree got too slow: the BVH policy for animated
//! scenes, chosen from `restir-viewer bench-bvh` (docs/src/measured/dynamic-scenes.md "BVH: refit,
//! rebuild or two levels"). A refit keeps the tree's order and costs little, but emitters drifting
//! away from their leaf neighbours inflate its boxes (2.4× the nodes per ray at half an orbit of
//! `dynamic:many-lights:65536`); a rebuild restores the tree at ~30× a refit's price. So every
//! frame refits and compares the tree's SAH cost with the cost it had when built; past
//! `BVH_REBUILD_FACTOR` times that, it rebuilds. In an animated scene the tree keeps the moving
//! meshes' triangles in their own subtree (`scene::bvh::split`): only that part degrades, so only
//! its cost is watched and only it is rebuilt.
//!
//! A rebuild reorders the triangles. Light identity survives because slots never move: a
//! slot's triangle is fixed by `slot_order` (the upload's BVH order), and only the BVH
//! position its table entry points at is rewritten. The previous frame's triangle records
//! are reordered with the current ones, so object motion still finds last frame's triangle
//! under the same index.

use glam::Vec3;

use super::GpuScene;
use crate::gpu::Gpu;
use crate::gpu_types::{LIGHT_KIND_SHIFT, LIGHT_KIND_TRIANGLE, LIGHT_PRIM_MASK};
use crate::scene::bvh::Bvh;

/// Rebuild when the refitted SAH cost exceeds the built tree's by this factor. 1.5 keeps
/// traversal within 1.5× of a fresh tree; on `dynamic:many-lights:65536` (4 s orbits) it
/// rebuilds about every 15 frames at 30 fps, which amortises the rebuild to well under a
/// two-level BVH's per-frame top-level build (measured in docs/src/measured/dynamic-scenes.md).
pub const BVH_REBUILD_FACTOR: f64 = 1.5;

/// Which part of a rebuild to leave out: test-only plants, so the tests can show that
/// their detectors fire (`rebuild_tests.rs`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct RebuildPlant {
    pub skip_light_remap: bool,
    pub skip_previous_reorder: bool,
    /// The whole scene rebuilt as one tree, as before its moving part was kept apart.
    pub rebuild_whole_tree: bool,
}

impl GpuScene {
    /// After a refit: whether the policy asks for a rebuild now.
    pub(super) fn rebuild_due(&self) -> bool {
        self.dynamic
            && super::tree_quality(&self.bvh, self.moving_part)
                > self.bvh_rebuild_factor * self.built_sah
    }

    /// A fresh tree over `positions` (scene order): of the moving part only for a split
    /// tree, the static part's nodes and slots kept. Rewrites what depends on BVH order on
    /// the CPU side and the previous triangles on the GPU; the caller writes the current
    /// triangles, shading and nodes (as after any geometry change) and the light table.
    pub(super) fn rebuild_bvh(&mut self, gpu: &Gpu, positions: &[[Vec3; 3]], plant: RebuildPlant) {
        if plant.rebuild_whole_tree {
            self.moving_part = None;
        }
        let bvh = match self.moving_part {
            Some(part) => {
                // The nodes move over (nothing below reads the old ones); the old order
                // stays for the reorder.
                let mut bvh = Bvh {
                    nodes: std::mem::take(&mut self.bvh.nodes),
                    triangle_order: self.bvh.triangle_order.clone(),
                };
                bvh.rebuild_moving(part, positions);
                bvh
            }
            None => Bvh::build(positions),
        };
        let n = bvh.triangle_order.len();
        let mut old_position = vec![0usize; n];
        for (p, &source) in self.bvh.triangle_order.iter().enumerate() {
            old_position[source as usize] = p;
        }
        let reorder = |p: usize| old_position[bvh.triangle_order[p] as usize];
        let old_order = std::mem::take(&mut self.bvh.triangle_order);
        self.triangle_light = (0..n).map(|p| self.triangle_light[reorder(p)]).collect();
        if !plant.skip_previous_reorder {
            self.prev_triangle_records = (0..n)
                .map(|p| self.prev_triangle_records[reorder(p)])
                .collect();
            gpu.queue.write_buffer(
                &self.prev_triangles,
                0,
                bytemuck::cast_slice(&self.prev_triangle_records),
            );
            // Last frame's boxes in the new tree: the new topology refitted to last frame's
            // triangles (the software backend's previous geometry).
            let mut previous = Bvh {
                nodes: bvh.nodes.clone(),
                triangle_order: Vec::new(),
            };
            let prev_positions: Vec<[Vec3; 3]> = self
                .prev_triangle_records
                .iter()
                .map(|t| [t.p0, t.p1, t.p2].map(Vec3::from))
                .collect();
            previous.refit(&prev_positions);
            gpu.queue.write_buffer(
                &self.prev_bvh_nodes,
                0,
                bytemuck::cast_slice(&previous.nodes),
            );
        }
        self.bvh = bvh;
        self.motion_index = None;
        self.built_sah = super::tree_quality(&self.bvh, self.moving_part);
        if !plant.skip_light_remap {
            repoint_triangle_entries(
                &mut self.light_entries,
                &old_order,
                &self.bvh.triangle_order,
            );
            for (kind, entry) in self
                .light_geometry_kinds
                .iter_mut()
                .zip(&self.light_entries)
            {
                if let Some((true, index)) = kind {
                    *index = entry.0 & LIGHT_PRIM_MASK;
                }
            }
            self.write_light_table(gpu);
        }
    }
}

/// Makes triangle entries that point at positions of `from_order` (BVH position → scene
/// triangle) point at the same triangles' positions in `to_order`.
pub(super) fn repoint_triangle_entries(
    entries: &mut [(u32, f64)],
    from_order: &[u32],
    to_order: &[u32],
) {
    let mut position = vec![0u32; to_order.len()];
    for (p, &source) in to_order.iter().enumerate() {
        position[source as usize] = p as u32;
    }
    for (kind_prim, _) in entries.iter_mut() {
        if *kind_prim >> LIGHT_KIND_SHIFT == LIGHT_KIND_TRIANGLE {
            let source = from_order[(*kind_prim & LIGHT_PRIM_MASK) as usize];
            *kind_prim = LIGHT_KIND_TRIANGLE << LIGHT_KIND_SHIFT | position[source as usize];
        }
    }
}
