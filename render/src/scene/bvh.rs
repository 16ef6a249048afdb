//! A binned-SAH bounding volume hierarchy, built on the CPU and flattened into
//! [`GpuBvhNode`]s for the stack traversal in `shaders/common/trace_bvh.wgsl`; the CPU mirror of
//! that traversal is in `bvh/traverse.rs`.
//!
//! Layout: node 0 is the root; a leaf (`count > 0`) holds triangles `first..first+count` of
//! the BVH order; an interior node (`count == 0`) has its children at `first` and `first+1`.
//! An empty triangle list gives no nodes at all: callers must treat it as "nothing to hit"
//! (a `count == 0` root would read as an interior node with missing children).

use glam::Vec3;

use super::Aabb;
use crate::gpu_types::GpuBvhNode;

mod refit;
pub mod split;
mod traverse;
pub mod two_level;

pub use refit::RefitLinks;
pub use traverse::{Hit, Ray, Visits};

/// Deepest tree the builder makes (root = level 1). The WGSL traversal stack has 64 entries
/// and holds at most one pending sibling per level, so this leaves a safe margin.
pub const BVH_MAX_DEPTH: usize = 48;
/// Leaves hold at most this many triangles (except in the last-resort case of reaching
/// `BVH_MAX_DEPTH`, which the median fallback below makes unreachable in practice).
const MAX_LEAF: usize = 4;
/// SAH bins per axis over the centroid bounds (Wald 2007: 8–32 loses little quality).
const BINS: usize = 16;
/// SAH cost of one traversal step relative to one triangle test.
const TRAVERSAL_COST: f32 = 1.0;

pub struct Bvh {
    pub nodes: Vec<GpuBvhNode>,
    /// `triangle_order[i]` = index in the input of the i-th triangle in BVH order.
    pub triangle_order: Vec<u32>,
}

/// A triangle as the builder sees it; the builder partitions these in place, so the scans
/// over a node's range are sequential in memory.
#[derive(Clone, Copy)]
struct Prim {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

struct Task {
    node: usize,
    start: usize,
    end: usize,
    level: usize,
}

impl Bvh {
    /// `items` (one per input triangle) in the order the leaves hold the triangles: what a
    /// traversal indexes by the hit's slot.
    pub fn in_leaf_order<T: Copy>(&self, items: &[T]) -> Vec<T> {
        self.triangle_order
            .iter()
            .map(|&i| items[i as usize])
            .collect()
    }

    pub fn build(triangles: &[[Vec3; 3]]) -> Bvh {
        assert!(
            triangles.len() <= (1 << 30),
            "over 2^30 triangles: the light table indexes them in 30 bits"
        );
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|tri| {
                let mut bounds = Aabb::EMPTY;
                tri.iter().for_each(|&p| bounds.grow(p));
                bounds
            })
            .collect();
        Bvh::build_boxes(&boxes)
    }

    /// A tree over boxes (triangles' bounds, or instances' world bounds for the top level
    /// of `TwoLevelBvh`); leaves index `triangle_order` like `build`'s.
    pub fn build_boxes(boxes: &[Aabb]) -> Bvh {
        let mut prims: Vec<Prim> = boxes
            .iter()
            .enumerate()
            .map(|(i, &bounds)| Prim {
                bounds,
                centroid: bounds.center(),
                index: i as u32,
            })
            .collect();
        let mut nodes = Vec::new();
        if !prims.is_empty() {
            nodes.reserve(2 * prims.len() - 1);
            nodes.push(GpuBvhNode::default());
            let mut stack = vec![Task {
                node: 0,
                start: 0,
                end: prims.len(),
                level: 1,
            }];
            while let Some(task) = stack.pop() {
                let prims = &mut prims[task.start..task.end];
                let (bounds, centroids) = range_bounds(prims);
                let (min, max) = (bounds.min.to_array(), bounds.max.to_array());
                match split(prims, bounds, centroids, task.level) {
                    None => {
                        let (first, count) = (task.start as u32, prims.len() as u32);
                        nodes[task.node] = GpuBvhNode {
                            min,
                            first,
                            max,
                            count,
                        };
                    }
                    Some(mid) => {
                        let first = nodes.len();
                        nodes[task.node] = GpuBvhNode {
                            min,
                            first: first as u32,
                            max,
                            count: 0,
                        };
                        nodes.extend([GpuBvhNode::default(); 2]);
                        let level = task.level + 1;
                        let mid = task.start + mid;
                        stack.push(Task {
                            node: first,
                            start: task.start,
                            end: mid,
                            level,
                        });
                        stack.push(Task {
                            node: first + 1,
                            start: mid,
                            end: task.end,
                            level,
                        });
                    }
                }
            }
        }
        Bvh {
            nodes,
            triangle_order: prims.iter().map(|p| p.index).collect(),
        }
    }

    /// Number of levels (a lone leaf root is 1; no nodes is 0).
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = Vec::new();
        if !self.nodes.is_empty() {
            stack.push((0usize, 1usize));
        }
        while let Some((i, level)) = stack.pop() {
            deepest = deepest.max(level);
            let node = &self.nodes[i];
            if node.count == 0 {
                stack.push((node.first as usize, level + 1));
                stack.push((node.first as usize + 1, level + 1));
            }
        }
        deepest
    }
}

/// Bounds of the triangles and of their centroids over a range.
fn range_bounds(prims: &[Prim]) -> (Aabb, Aabb) {
    let mut bounds = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    for p in prims {
        bounds = bounds.union(p.bounds);
        centroids.grow(p.centroid);
    }
    (bounds, centroids)
}

/// Levels a balanced (median-split) subtree over `count` triangles needs below its root.
fn levels_needed(count: usize) -> usize {
    let leaves = count.div_ceil(MAX_LEAF);
    leaves.next_power_of_two().trailing_zeros() as usize
}

/// Decides how to split `prims` (a node at `level`), partitions them in place and returns
/// the split position, or `None` for a leaf.
fn split(prims: &mut [Prim], bounds: Aabb, centroids: Aabb, level: usize) -> Option<usize> {
    let count = prims.len();
    let must_split = count > MAX_LEAF;
    if count < 2 || level >= BVH_MAX_DEPTH {
        return None;
    }
    let extent = centroids.extent();
    if extent.max_element() <= 0.0 {
        // Identical centroids: no plane separates them. Halving by index keeps leaves small
        // and the depth logarithmic (10 000 copies of one triangle → 13 levels).
        return must_split.then_some(count / 2);
    }
    let area = bounds.half_area();
    let sah = if area > 0.0 && area.is_finite() {
        best_binned_split(prims, centroids)
    } else {
        None
    };
    let Some(best) = sah else {
        // A node with no area (all triangles on a line or a point) or centroids too close for
        // the bins: SAH cannot rank anything, so fall back to the object median.
        return must_split.then(|| median_split(prims, extent));
    };
    if !must_split && TRAVERSAL_COST + best.cost / area >= count as f32 {
        return None;
    }
    // Depth guard: SAH may peel off one triangle per level (e.g. exponentially spaced
    // centroids). If the larger side could no longer be finished with median splits within
    // BVH_MAX_DEPTH, switch to the median now; the median halves the count, so this
    // guarantee then holds all the way down.
    let larger = best.left_count.max(count - best.left_count);
    if level + 1 + levels_needed(larger) > BVH_MAX_DEPTH {
        return Some(median_split(prims, extent));
    }
    Some(partition(prims, |p| best.bins.bin(p.centroid) <= best.bin))
}

/// Maps centroids to bins along one axis.
#[derive(Clone, Copy)]
struct Binning {
    axis: usize,
    min: f32,
    scale: f32,
}

impl Binning {
    fn bin(&self, centroid: Vec3) -> usize {
        // `as usize` saturates (and maps NaN to 0), so every centroid lands in a bin.
        (((centroid[self.axis] - self.min) * self.scale) as usize).min(BINS - 1)
    }
}

struct SahSplit {
    bins: Binning,
    /// Bins `0..=bin` go left.
    bin: usize,
    cost: f32,
    left_count: usize,
}

/// Best SAH plane among the bin boundaries of all three axes; cost = A_l·N_l + A_r·N_r.
fn best_binned_split(prims: &[Prim], centroids: Aabb) -> Option<SahSplit> {
    let extent = centroids.extent();
    let binnings: [Option<Binning>; 3] = std::array::from_fn(|axis| {
        let scale = BINS as f32 / extent[axis];
        (extent[axis] > 0.0 && scale.is_finite()).then_some(Binning {
            axis,
            min: centroids.min[axis],
            scale,
        })
    });
    let mut counts = [[0usize; BINS]; 3];
    let mut boxes = [[Aabb::EMPTY; BINS]; 3];
    for p in prims {
        for b in binnings.iter().flatten() {
            let i = b.bin(p.centroid);
            counts[b.axis][i] += 1;
            boxes[b.axis][i] = boxes[b.axis][i].union(p.bounds);
        }
    }
    let mut best: Option<SahSplit> = None;
    for b in binnings.iter().flatten() {
        let (counts, boxes) = (&counts[b.axis], &boxes[b.axis]);
        // Right-to-left sweep first, so the left-to-right one can price each plane.
        let mut right_area = [0.0f32; BINS];
        let mut acc = Aabb::EMPTY;
        for i in (1..BINS).rev() {
            acc = acc.union(boxes[i]);
            right_area[i] = acc.half_area();
        }
        let (mut left, mut left_count) = (Aabb::EMPTY, 0);
        for i in 0..BINS - 1 {
            left = left.union(boxes[i]);
            left_count += counts[i];
            let right_count = prims.len() - left_count;
            if left_count == 0 || right_count == 0 {
                continue;
            }
            let cost =
                left.half_area() * left_count as f32 + right_area[i + 1] * right_count as f32;
            if best.as_ref().is_none_or(|s| cost < s.cost) {
                best = Some(SahSplit {
                    bins: *b,
                    bin: i,
                    cost,
                    left_count,
                });
            }
        }
    }
    best
}

/// Splits at the median centroid along the widest axis; both halves are non-empty.
fn median_split(prims: &mut [Prim], extent: Vec3) -> usize {
    let axis = extent.max_position();
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    mid
}

/// Moves the prims satisfying `left` to the front; returns how many there are.
fn partition(prims: &mut [Prim], left: impl Fn(&Prim) -> bool) -> usize {
    let (mut i, mut j) = (0, prims.len());
    while i < j {
        if left(&prims[i]) {
            i += 1;
        } else {
            j -= 1;
            prims.swap(i, j);
        }
    }
    i
}

#[cfg(test)]
mod tests;
