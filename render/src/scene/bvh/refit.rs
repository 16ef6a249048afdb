//! Refitting: new triangle positions, same tree. Every node's box is recomputed bottom-up
//! (children always come after their parent in `nodes`, so one reverse sweep suffices);
//! the topology and `triangle_order` stay, which keeps BVH-order indices — and with them
//! light-table entries — stable while a scene moves. The price is tree quality: boxes of
//! nodes whose triangles moved apart grow. `sah_cost` measures that, so the choice between
//! refitting and rebuilding is a number (docs/src/measured/dynamic-scenes.md). When only a few
//! triangles moved (cars in a city), `refit_moved` rewrites their leaves and the nodes above them
//! only.

use glam::Vec3;

use super::Bvh;
use crate::gpu_types::GpuBvhNode;
use crate::scene::Aabb;

/// What a partial refit climbs: `Bvh::refit_links`.
pub struct RefitLinks {
    /// Per BVH-order triangle, its leaf.
    leaf: Vec<u32>,
    /// Per node, its parent (`NO_PARENT` for the root).
    parent: Vec<u32>,
}

const NO_PARENT: u32 = u32::MAX;

impl Bvh {
    /// `bvh_positions[i]` are the positions of the i-th triangle in BVH order.
    pub fn refit(&mut self, bvh_positions: &[[Vec3; 3]]) {
        let mut boxes = vec![Aabb::EMPTY; self.nodes.len()];
        for i in (0..self.nodes.len()).rev() {
            let node = self.nodes[i];
            let (first, count) = (node.first as usize, node.count as usize);
            let bounds = if count > 0 {
                let mut b = Aabb::EMPTY;
                for tri in bvh_positions.get(first..first + count).unwrap_or(&[]) {
                    tri.iter().for_each(|&p| b.grow(p));
                }
                b
            } else {
                boxes[first].union(boxes[first + 1])
            };
            boxes[i] = bounds;
            self.nodes[i].min = bounds.min.to_array();
            self.nodes[i].max = bounds.max.to_array();
        }
    }

    /// Per BVH-order triangle its leaf, per node its parent: what `refit_moved` climbs.
    pub fn refit_links(&self) -> RefitLinks {
        let mut leaf = vec![NO_PARENT; self.triangle_order.len()];
        let mut parent = vec![NO_PARENT; self.nodes.len()];
        for (i, node) in self.nodes.iter().enumerate() {
            let (first, count) = (node.first as usize, node.count as usize);
            if count > 0 {
                if let Some(slots) = leaf.get_mut(first..first + count) {
                    slots.fill(i as u32);
                }
            } else if first + 1 < parent.len() {
                parent[first] = i as u32;
                parent[first + 1] = i as u32;
            }
        }
        RefitLinks { leaf, parent }
    }

    /// The refit for `moved` triangles only (BVH order): their leaves and every node above
    /// them, children before parents; `position(s)` gives scene triangle s's corners now. Boxes are minima and maxima, exact in any order, so this gives the same nodes
    /// as `refit` whenever `moved` lists every triangle that moved. Returns the nodes it
    /// rewrote, ascending.
    pub fn refit_moved(
        &mut self,
        links: &RefitLinks,
        moved: &[usize],
        position: impl Fn(u32) -> [Vec3; 3],
    ) -> Vec<usize> {
        let mut dirty = vec![false; self.nodes.len()];
        let mut rewritten = Vec::new();
        for &triangle in moved {
            let mut node = links.leaf.get(triangle).copied().unwrap_or(NO_PARENT);
            // Up to the root, or to a node another moved triangle already marked.
            while node != NO_PARENT && !dirty[node as usize] {
                dirty[node as usize] = true;
                rewritten.push(node as usize);
                node = links.parent[node as usize];
            }
        }
        // Children come after their parent in `nodes`: descending order is bottom up.
        rewritten.sort_unstable_by(|a, b| b.cmp(a));
        for &i in &rewritten {
            let node = self.nodes[i];
            let (first, count) = (node.first as usize, node.count as usize);
            let bounds = if count > 0 {
                let mut b = Aabb::EMPTY;
                for t in first..first + count {
                    position(self.triangle_order[t])
                        .iter()
                        .for_each(|&p| b.grow(p));
                }
                b
            } else {
                node_box(&self.nodes[first]).union(node_box(&self.nodes[first + 1]))
            };
            self.nodes[i].min = bounds.min.to_array();
            self.nodes[i].max = bounds.max.to_array();
        }
        rewritten.reverse();
        rewritten
    }

    /// The tree's SAH cost relative to its root box: Σ over interior nodes of area/root
    /// area (one traversal step each) plus Σ over leaves of area/root area × triangles.
    /// Lower is a better tree for the same triangles.
    pub fn sah_cost(&self) -> f64 {
        let Some(root) = self.nodes.first() else {
            return 0.0;
        };
        let root_area = node_area(root).max(f64::MIN_POSITIVE);
        self.nodes.iter().map(|n| sah_term(n, root_area)).sum()
    }
}

/// A node's box.
pub(super) fn node_box(n: &GpuBvhNode) -> Aabb {
    Aabb {
        min: Vec3::from(n.min),
        max: Vec3::from(n.max),
    }
}

pub(super) fn node_area(n: &GpuBvhNode) -> f64 {
    node_box(n).half_area() as f64
}

/// One node's share of an SAH cost measured against a box of `root_area`: its area, times
/// its triangles for a leaf (one traversal step for an interior node).
pub(super) fn sah_term(n: &GpuBvhNode, root_area: f64) -> f64 {
    let weight = if n.count > 0 { n.count as f64 } else { 1.0 };
    node_area(n) / root_area * weight
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::bvh::Ray;

    fn grid(offset: Vec3) -> Vec<[Vec3; 3]> {
        (0..64)
            .map(|i| {
                let p = Vec3::new((i % 8) as f32, (i / 8) as f32, 0.0) + offset;
                [p, p + Vec3::X * 0.5, p + Vec3::Y * 0.5]
            })
            .collect()
    }

    fn in_bvh_order(bvh: &Bvh, tris: &[[Vec3; 3]]) -> Vec<[Vec3; 3]> {
        bvh.triangle_order
            .iter()
            .map(|&i| tris[i as usize])
            .collect()
    }

    #[test]
    fn refit_after_a_move_matches_a_rebuild_of_the_moved_triangles() {
        let before = grid(Vec3::ZERO);
        let mut bvh = Bvh::build(&before);
        let moved = grid(Vec3::new(3.0, -2.0, 5.0));
        bvh.refit(&in_bvh_order(&bvh, &moved));
        let rebuilt = Bvh::build(&moved);
        assert_eq!(bvh.nodes[0].min, rebuilt.nodes[0].min);
        assert_eq!(bvh.nodes[0].max, rebuilt.nodes[0].max);
        // A translation keeps every box's shape: the cost is unchanged.
        let original = Bvh::build(&before);
        assert!((bvh.sah_cost() - original.sah_cost()).abs() < 1e-9);
        // And traversal finds the moved triangles where they are now.
        let ordered = in_bvh_order(&bvh, &moved);
        let ray = Ray {
            origin: Vec3::new(3.1, -1.9, 10.0),
            dir: Vec3::NEG_Z,
            t_max: f32::INFINITY,
        };
        let hit = bvh
            .closest_hit(&ordered, &ray)
            .expect("hits the moved grid");
        assert!((hit.t - 5.0).abs() < 1e-4, "{}", hit.t);
    }

    /// Moving a few triangles: the partial refit gives the full refit's nodes bit for bit;
    /// leaving one moved triangle out of its list is caught (planted).
    #[test]
    fn refitting_the_moved_triangles_equals_refitting_all() {
        let before = grid(Vec3::ZERO);
        let moved_set = [3usize, 17, 40, 41, 63];
        let after: Vec<[Vec3; 3]> = before
            .iter()
            .enumerate()
            .map(|(i, t)| {
                if moved_set.contains(&i) {
                    t.map(|p| p + Vec3::new(2.5, -1.0, 0.75))
                } else {
                    *t
                }
            })
            .collect();
        let built = Bvh::build(&before);
        let mut full = Bvh::build(&before);
        full.refit(&in_bvh_order(&full, &after));
        let slot_of = |source: usize| {
            built
                .triangle_order
                .iter()
                .position(|&s| s as usize == source)
                .unwrap()
        };
        let mut moved: Vec<usize> = moved_set.iter().map(|&s| slot_of(s)).collect();
        let partial = |moved: &[usize]| {
            let mut bvh = Bvh::build(&before);
            let links = bvh.refit_links();
            let rewritten = bvh.refit_moved(&links, moved, |s| after[s as usize]);
            (bvh, rewritten)
        };
        let (bvh, rewritten) = partial(&moved);
        assert_eq!(bvh.nodes, full.nodes);
        assert!(rewritten.windows(2).all(|w| w[0] < w[1]));
        assert!(
            rewritten.len() < bvh.nodes.len(),
            "only the paths of the moved"
        );
        moved.pop();
        let (planted, _) = partial(&moved);
        assert_ne!(planted.nodes, full.nodes, "a triangle left out must show");
    }

    #[test]
    fn scattering_triangles_raises_the_refit_cost_above_a_rebuild() {
        let before = grid(Vec3::ZERO);
        let mut bvh = Bvh::build(&before);
        // Mirror the order of the triangles: neighbours in the tree end up far apart.
        let scattered: Vec<[Vec3; 3]> = before.iter().rev().cloned().collect();
        let swapped: Vec<[Vec3; 3]> = (0..64)
            .map(|i| if i % 2 == 0 { scattered[i] } else { before[i] })
            .collect();
        bvh.refit(&in_bvh_order(&bvh, &swapped));
        let rebuilt = Bvh::build(&swapped);
        assert!(
            bvh.sah_cost() > rebuilt.sah_cost(),
            "{} vs {}",
            bvh.sah_cost(),
            rebuilt.sah_cost()
        );
    }
}
