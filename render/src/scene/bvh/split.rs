//! The scene's tree with its moving triangles kept apart (docs/src/dynamic-scenes.md): the
//! root's two children are a tree over the triangles that never move (node 1) and a tree
//! over those of the animation's moving meshes (node 2). Cars driving through a city then
//! refit the moving subtree and the root only; the city's part keeps the quality it was
//! built with whatever the cars do, and when the refitted moving part has degraded, only it
//! is rebuilt (`rebuild_moving`), at the price of its own triangles rather than the
//! scene's. Traversal needs nothing new: the root is an ordinary interior node, and a ray
//! visits both parts where both boxes are ahead of it (trace_bvh.wgsl, `traverse.rs`).
//!
//! Layout: node 0 the root, 1 and 2 the parts' roots, then the static part's other nodes,
//! then from `MovingPart::first_node` the moving part's. Slots (BVH order) hold the static
//! triangles first, the moving ones from `MovingPart::first_slot`. Every child still comes
//! after its parent, so `refit`'s reverse sweep holds. The extra level leaves each part at
//! most `BVH_MAX_DEPTH` levels below the root, one more than a single tree, still well inside
//! the traversal's 64-entry stack.

use glam::Vec3;

use super::Bvh;
use super::refit::{node_area, node_box, sah_term};
use crate::gpu_types::GpuBvhNode;

/// Where the moving part of a split tree lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MovingPart {
    /// BVH-order slots from here on hold the moving triangles.
    pub first_slot: usize,
    /// The moving subtree's nodes other than its root (node 2) start here and run to the
    /// end of `Bvh::nodes`.
    pub first_node: usize,
}

/// The moving part's root.
const MOVING_ROOT: usize = 2;

impl Bvh {
    /// A tree over `triangles` with those marked `moving` apart from the rest. With no
    /// moving or no static triangle there is nothing to keep apart: a single tree, `None`.
    pub fn build_split(triangles: &[[Vec3; 3]], moving: &[bool]) -> (Bvh, Option<MovingPart>) {
        let is_moving = |t: usize| moving.get(t).copied().unwrap_or(false);
        let (moving_ids, static_ids): (Vec<u32>, Vec<u32>) =
            (0..triangles.len() as u32).partition(|&t| is_moving(t as usize));
        if moving_ids.is_empty() || static_ids.is_empty() {
            return (Bvh::build(triangles), None);
        }
        let of = |ids: &[u32]| -> Vec<[Vec3; 3]> {
            ids.iter().map(|&t| triangles[t as usize]).collect()
        };
        let still = Bvh::build(&of(&static_ids));
        let moved = Bvh::build(&of(&moving_ids));
        let mut nodes = vec![GpuBvhNode::default(); 3];
        graft(&mut nodes, 1, &still, 0);
        let part = MovingPart {
            first_slot: static_ids.len(),
            first_node: nodes.len(),
        };
        graft(&mut nodes, MOVING_ROOT, &moved, part.first_slot);
        let mut triangle_order: Vec<u32> = still
            .triangle_order
            .iter()
            .map(|&k| static_ids[k as usize])
            .collect();
        triangle_order.extend(moved.triangle_order.iter().map(|&k| moving_ids[k as usize]));
        let mut bvh = Bvh {
            nodes,
            triangle_order,
        };
        bvh.nodes[0].first = 1;
        bvh.bound_root();
        (bvh, Some(part))
    }

    /// A fresh tree over the moving part's triangles at `positions` (scene order), the
    /// static part's nodes and slots untouched. The moving slots are reordered: a caller
    /// keeping data in BVH order reorders it as after a full rebuild (`gpu_scene/rebuild.rs`).
    pub fn rebuild_moving(&mut self, part: MovingPart, positions: &[[Vec3; 3]]) {
        let sources = self.triangle_order.split_off(part.first_slot);
        let triangles: Vec<[Vec3; 3]> = sources.iter().map(|&s| positions[s as usize]).collect();
        let moved = Bvh::build(&triangles);
        self.nodes.truncate(part.first_node);
        graft(&mut self.nodes, MOVING_ROOT, &moved, part.first_slot);
        self.triangle_order
            .extend(moved.triangle_order.iter().map(|&k| sources[k as usize]));
        self.bound_root();
    }

    /// The moving part's SAH cost (`sah_cost`'s terms) relative to the static part's root
    /// box: what refitting can degrade and rebuilding restores. The static box is the
    /// yardstick because it never moves; the whole tree's root grows with the moving part
    /// and would hide its degradation.
    pub fn moving_sah_cost(&self, part: MovingPart) -> f64 {
        let Some(yardstick) = self.nodes.get(1) else {
            return 0.0;
        };
        let root_area = node_area(yardstick).max(f64::MIN_POSITIVE);
        let moving = std::iter::once(MOVING_ROOT).chain(part.first_node..self.nodes.len());
        moving
            .filter_map(|i| self.nodes.get(i))
            .map(|n| sah_term(n, root_area))
            .sum()
    }

    /// The root's box from its two children.
    fn bound_root(&mut self) {
        let b = node_box(&self.nodes[1]).union(node_box(&self.nodes[2]));
        self.nodes[0].min = b.min.to_array();
        self.nodes[0].max = b.max.to_array();
    }
}

/// Copies `sub` into `nodes`: its root to `root_at`, its other nodes appended (sibling pairs
/// stay adjacent, so every interior node's `first` just moves by the same offset), its
/// leaves' slots shifted by `first_slot`.
fn graft(nodes: &mut Vec<GpuBvhNode>, root_at: usize, sub: &Bvh, first_slot: usize) {
    let base = nodes.len();
    let place = |i: u32| {
        if i == 0 {
            root_at
        } else {
            base + i as usize - 1
        }
    };
    let moved = |n: &GpuBvhNode| {
        let first = if n.count > 0 {
            n.first + first_slot as u32
        } else {
            place(n.first) as u32
        };
        GpuBvhNode { first, ..*n }
    };
    if let Some(root) = sub.nodes.first() {
        nodes[root_at] = moved(root);
    }
    nodes.extend(sub.nodes.iter().skip(1).map(moved));
}

#[cfg(test)]
mod tests;
