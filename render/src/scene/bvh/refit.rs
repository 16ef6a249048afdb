//! Refitting: new triangle positions, same tree. Every node's box is recomputed bottom-up
//! (children always come after their parent in `nodes`, so one reverse sweep suffices);
//! the topology and `triangle_order` stay, which keeps BVH-order indices — and with them
//! light-table entries — stable while a scene moves. The price is tree quality: boxes of
//! nodes whose triangles moved apart grow. `sah_cost` measures that, so the choice between
//! refitting and rebuilding is a number (docs/bench.md).

use glam::Vec3;

use super::Bvh;
use crate::scene::Aabb;

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

    /// The tree's SAH cost relative to its root box: Σ over interior nodes of area/root
    /// area (one traversal step each) plus Σ over leaves of area/root area × triangles.
    /// Lower is a better tree for the same triangles.
    pub fn sah_cost(&self) -> f64 {
        let Some(root) = self.nodes.first() else {
            return 0.0;
        };
        let area = |n: &crate::gpu_types::GpuBvhNode| {
            Aabb {
                min: Vec3::from(n.min),
                max: Vec3::from(n.max),
            }
            .half_area() as f64
        };
        let root_area = area(root).max(f64::MIN_POSITIVE);
        self.nodes
            .iter()
            .map(|n| {
                let weight = if n.count > 0 { n.count as f64 } else { 1.0 };
                area(n) / root_area * weight
            })
            .sum()
    }
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
