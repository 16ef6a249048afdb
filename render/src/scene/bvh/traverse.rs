//! CPU traversal of a [`Bvh`], the same loop as `shaders/common/trace_bvh.wgsl`: a fixed stack,
//! nearer child first, boxes re-checked against the shrinking t_max when popped. Used by the
//! tests and by CPU-side queries (picking, checks).

use glam::Vec3;

use super::Bvh;
use crate::gpu_types::GpuBvhNode;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
    pub t_max: f32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    /// Triangle index in BVH order.
    pub triangle: u32,
    /// Barycentrics: the hit point is `(1−u−v)·p0 + u·p1 + v·p2`.
    pub u: f32,
    pub v: f32,
}

/// What a traversal touched: nodes whose box was tested or popped, and primitive tests
/// (triangles; instances at the top level of a two-level tree). The measure of a tree's
/// traversal cost that does not depend on the machine (docs/src/measured/dynamic-scenes.md).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Visits {
    pub nodes: u64,
    pub primitives: u64,
}

impl Bvh {
    /// Nearest hit with t in (0, t_max), either face. `tris_bvh_order[i]` is the triangle
    /// at BVH position `i`.
    pub fn closest_hit(&self, tris_bvh_order: &[[Vec3; 3]], ray: &Ray) -> Option<Hit> {
        self.closest_hit_counted(tris_bvh_order, ray, &mut Visits::default())
    }

    /// Whether anything is hit with t in (0, t_max): a shadow ray.
    pub fn any_hit(&self, tris_bvh_order: &[[Vec3; 3]], ray: &Ray) -> bool {
        self.any_hit_counted(tris_bvh_order, ray, &mut Visits::default())
    }

    /// `closest_hit`, adding what it touched to `visits`.
    pub fn closest_hit_counted(
        &self,
        tris: &[[Vec3; 3]],
        ray: &Ray,
        visits: &mut Visits,
    ) -> Option<Hit> {
        self.walk(ray, false, visits, |i, t_max| {
            triangle_hit(tris, i, ray, t_max)
        })
    }

    /// `any_hit`, adding what it touched to `visits`.
    pub fn any_hit_counted(&self, tris: &[[Vec3; 3]], ray: &Ray, visits: &mut Visits) -> bool {
        self.walk(ray, true, visits, |i, t_max| {
            triangle_hit(tris, i, ray, t_max)
        })
        .is_some()
    }

    /// The shared loop over the tree; `leaf(position, t_max)` tests the primitive at BVH
    /// position `position` and returns a hit nearer than t_max. `any` returns at the first
    /// hit found. The stack holds one pending sibling per level, so 64 entries cover
    /// `BVH_MAX_DEPTH`.
    pub fn walk(
        &self,
        ray: &Ray,
        any: bool,
        visits: &mut Visits,
        mut leaf: impl FnMut(u32, f32) -> Option<Hit>,
    ) -> Option<Hit> {
        let root = self.nodes.first()?;
        let inv_dir = safe_recip(ray.dir);
        let mut t_max = ray.t_max;
        let mut best = None;
        let mut stack = [(0u32, 0.0f32); 64];
        let mut len = 0;
        visits.nodes += 1;
        if let Some(t) = slab(root, ray.origin, inv_dir, t_max) {
            stack[0] = (0, t);
            len = 1;
        }
        while len > 0 {
            len -= 1;
            let (index, t_enter) = stack[len];
            if t_enter >= t_max {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.count > 0 {
                for i in node.first..node.first + node.count {
                    visits.primitives += 1;
                    if let Some(hit) = leaf(i, t_max) {
                        t_max = hit.t;
                        best = Some(hit);
                        if any {
                            return best;
                        }
                    }
                }
                continue;
            }
            visits.nodes += 2;
            let children = [node.first, node.first + 1]
                .map(|c| (c, slab(&self.nodes[c as usize], ray.origin, inv_dir, t_max)));
            let [near, far] = match (children[0].1, children[1].1) {
                (Some(a), Some(b)) if b < a => [children[1], children[0]],
                _ => children,
            };
            for (child, t) in [far, near] {
                if let Some(t) = t {
                    stack[len] = (child, t);
                    len += 1;
                }
            }
        }
        best
    }
}

fn triangle_hit(tris: &[[Vec3; 3]], i: u32, ray: &Ray, t_max: f32) -> Option<Hit> {
    let (t, u, v) = intersect_triangle(&tris[i as usize], ray.origin, ray.dir, t_max)?;
    Some(Hit {
        t,
        triangle: i,
        u,
        v,
    })
}

/// `1/dir` with components below 1e-30 replaced by ±1e-30 first, as `safe_inverse_dir` in
/// `trace_bvh.wgsl` does (WGSL leaves x/0 undefined). On the CPU it also matters: a ray parallel to
/// a slab and starting on its plane gives 0·1e30 = 0 (inside) instead of 0·∞ = NaN, which
/// would miss a box the ray runs along (e.g. an axis-aligned ray through a vertex).
fn safe_recip(dir: Vec3) -> Vec3 {
    const TINY: f32 = 1e-30;
    dir.map(|d| {
        let sign = if d >= 0.0 { 1.0 } else { -1.0 };
        1.0 / if d.abs() < TINY { sign * TINY } else { d }
    })
}

/// Ray–box slab test; the entry distance when the box overlaps (0, t_max).
fn slab(node: &GpuBvhNode, origin: Vec3, inv_dir: Vec3, t_max: f32) -> Option<f32> {
    let t0 = (Vec3::from(node.min) - origin) * inv_dir;
    let t1 = (Vec3::from(node.max) - origin) * inv_dir;
    let enter = t0.min(t1).max_element().max(0.0);
    let exit = t0.max(t1).min_element().min(t_max);
    (enter <= exit).then_some(enter)
}

/// Möller–Trumbore, both faces: `(t, u, v)` for a hit with t in (0, t_max).
pub(crate) fn intersect_triangle(
    tri: &[Vec3; 3],
    origin: Vec3,
    dir: Vec3,
    t_max: f32,
) -> Option<(f32, f32, f32)> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 || !det.is_finite() {
        return None; // parallel to the plane, or a degenerate triangle
    }
    let inv_det = 1.0 / det;
    let s = origin - tri[0];
    let u = s.dot(p) * inv_det;
    let q = s.cross(e1);
    let v = dir.dot(q) * inv_det;
    let t = e2.dot(q) * inv_det;
    // Written so that NaN fails every comparison.
    let inside = u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_max;
    inside.then_some((t, u, v))
}
