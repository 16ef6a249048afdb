//! A light BVH over emissive triangles, in plain Rust: the model a GPU light sampler is
//! checked against (many-lights sampling with locality; Conty & Kulla 2018, pbrt-v4's
//! `BVHLightSampler`). Each node bounds its lights' positions (a box), their emission
//! directions (a cone around an axis) and their power; a shading point walks down from the
//! root choosing each child with probability proportional to an importance that accounts
//! for distance and orientation, so a light's PDF is the product of the branch
//! probabilities on its path — exact, and what an estimator divides by. Moving lights refit
//! the bounds in place; adding or removing lights rebuilds.

use glam::{Quat, Vec3};

use crate::shader_constants::LIGHT_BVH_NEARLY_OPPOSITE;

/// A cone of directions: every direction within `acos(cos_theta)` of `w`. `cos_theta` −1
/// is the whole sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionCone {
    pub w: Vec3,
    pub cos_theta: f32,
}

impl DirectionCone {
    /// The single direction `w` (a degenerate `w`, a zero-area triangle's normal: every
    /// direction, so the bounds stay conservative).
    pub fn around(w: Vec3) -> DirectionCone {
        match w.try_normalize() {
            Some(w) => DirectionCone { w, cos_theta: 1.0 },
            None => DirectionCone::entire_sphere(),
        }
    }

    pub fn entire_sphere() -> DirectionCone {
        DirectionCone {
            w: Vec3::Z,
            cos_theta: -1.0,
        }
    }

    pub fn contains(&self, d: Vec3) -> bool {
        // A little slack for rounding: a direction on the rim is inside.
        self.cos_theta <= -1.0 || self.w.dot(d.normalize()) >= self.cos_theta - 1e-5
    }

    /// The smallest cone around both (pbrt-v4's `Union(DirectionCone, DirectionCone)`).
    pub fn union(a: DirectionCone, b: DirectionCone) -> DirectionCone {
        let theta_a = a.cos_theta.clamp(-1.0, 1.0).acos();
        let theta_b = b.cos_theta.clamp(-1.0, 1.0).acos();
        // The angle between the axes from both its sine and cosine: acos of a dot product
        // near 1 turns its rounding (6e-8) into 3.5e-4 rad, atan2 keeps it at 1e-7.
        let theta_d = a.w.cross(b.w).length().atan2(a.w.dot(b.w));
        let pi = std::f32::consts::PI;
        if (theta_d + theta_b).min(pi) <= theta_a {
            return a;
        }
        if (theta_d + theta_a).min(pi) <= theta_b {
            return b;
        }
        // Rotate a's axis toward b's, about their cross product. Axes within
        // NEARLY_OPPOSITE of opposite have no well-defined great circle (their cross product
        // is rounding noise): about any axis perpendicular to a's then, with θ_d taken as π
        // so that the cone still holds b's (a small threshold on the cross product instead
        // would jump between cones for parallel walls, and the GPU's refit,
        // lights/light_bvh_refit.wgsl, would land on either side of the jump).
        let (axis, theta_o) = if theta_d < pi - LIGHT_BVH_NEARLY_OPPOSITE {
            let axis = a.w.cross(b.w).normalize_or(perpendicular(a.w));
            (axis, (theta_a + theta_d + theta_b) / 2.0)
        } else {
            (perpendicular(a.w), (theta_a + pi + theta_b) / 2.0)
        };
        if theta_o >= pi {
            return DirectionCone::entire_sphere();
        }
        let w = Quat::from_axis_angle(axis, theta_o - theta_a) * a.w;
        DirectionCone {
            w: w.normalize(),
            cos_theta: theta_o.cos(),
        }
    }
}

/// A unit vector perpendicular to unit `w`, smooth near the coordinate axes where scenes'
/// normals gather (lights/light_bvh_refit.wgsl's `perpendicular` is the same).
pub fn perpendicular(w: Vec3) -> Vec3 {
    let e = if w.z.abs() > 0.9 { Vec3::X } else { Vec3::Z };
    w.cross(e).normalize()
}

/// What a node (or one light) bounds: positions, emission directions, power.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightBounds {
    pub min: Vec3,
    pub max: Vec3,
    pub phi: f32,
    /// The normals' cone (θ_o in pbrt's terms).
    pub normals: DirectionCone,
    /// cos θ_e: how far past its normal a light emits (0: a one-sided triangle, 90°).
    pub cos_theta_e: f32,
}

/// One emissive triangle: its corners and its power (emitted flux, any consistent unit).
/// A punctual light is its position three times (no normal: it emits all around).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmissiveTriangle {
    pub p: [Vec3; 3],
    pub power: f32,
    /// Emits from both faces (a double-sided material).
    pub two_sided: bool,
}

impl EmissiveTriangle {
    pub fn normal(&self) -> Vec3 {
        (self.p[1] - self.p[0])
            .cross(self.p[2] - self.p[0])
            .normalize_or_zero()
    }

    pub fn centroid(&self) -> Vec3 {
        (self.p[0] + self.p[1] + self.p[2]) / 3.0
    }

    /// A one-sided emitter emits into the hemisphere of its normal; a two-sided one (or a
    /// point) all around: its normals' cone is the whole sphere.
    pub fn bounds(&self) -> LightBounds {
        LightBounds {
            min: self.p[0].min(self.p[1]).min(self.p[2]),
            max: self.p[0].max(self.p[1]).max(self.p[2]),
            phi: self.power.max(0.0),
            normals: if self.two_sided {
                DirectionCone::entire_sphere()
            } else {
                DirectionCone::around(self.normal())
            },
            cos_theta_e: 0.0,
        }
    }
}

/// cos(max(0, a − b)) from the sines and cosines of a and b.
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// sin(max(0, a − b)).
fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

impl LightBounds {
    pub fn union(a: &LightBounds, b: &LightBounds) -> LightBounds {
        if a.phi <= 0.0 {
            return *b;
        }
        if b.phi <= 0.0 {
            return *a;
        }
        LightBounds {
            min: a.min.min(b.min),
            max: a.max.max(b.max),
            phi: a.phi + b.phi,
            normals: DirectionCone::union(a.normals, b.normals),
            cos_theta_e: a.cos_theta_e.min(b.cos_theta_e),
        }
    }

    pub fn centre(&self) -> Vec3 {
        (self.min + self.max) / 2.0
    }

    /// An upper bound on what the lights inside can send to a surface at `p` with normal
    /// `n` (pbrt-v4's `LightBounds::Importance`): power over squared distance, times the
    /// most favourable emission angle and receiving angle any point of the box allows.
    /// `orientation` false leaves out both angle terms (the planted error of the tests).
    pub fn importance(&self, p: Vec3, n: Vec3, orientation: bool) -> f32 {
        if self.phi <= 0.0 {
            return 0.0;
        }
        let pc = self.centre();
        let diagonal = (self.max - self.min).length();
        let d2 = p.distance_squared(pc).max(diagonal / 2.0);
        if !orientation {
            return self.phi / d2;
        }
        let wi = (p - pc).normalize_or_zero();
        let cos_w = self.normals.w.dot(wi);
        let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
        // The directions from p the box subtends, as a cone (its bounding sphere's).
        let radius = diagonal / 2.0;
        let dist2 = p.distance_squared(pc);
        let cos_b = if dist2 < radius * radius {
            -1.0
        } else {
            safe_sqrt(1.0 - radius * radius / dist2)
        };
        let sin_b = safe_sqrt(1.0 - cos_b * cos_b);
        let cos_o = self.normals.cos_theta;
        let sin_o = safe_sqrt(1.0 - cos_o * cos_o);
        let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, cos_o);
        let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, cos_o);
        let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if cos_p <= self.cos_theta_e {
            return 0.0;
        }
        let mut importance = self.phi * cos_p / d2;
        if n != Vec3::ZERO {
            let cos_i = wi.dot(n.normalize()).abs();
            let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
            importance *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        }
        importance.max(0.0)
    }
}

#[derive(Clone, Debug)]
pub enum Node {
    Interior {
        bounds: LightBounds,
        children: [usize; 2],
    },
    Leaf {
        bounds: LightBounds,
        light: usize,
    },
}

impl Node {
    pub fn bounds(&self) -> &LightBounds {
        match self {
            Node::Interior { bounds, .. } | Node::Leaf { bounds, .. } => bounds,
        }
    }
}

/// The tree: nodes (the root first) and, per light, the branch choices from the root to its
/// leaf (bit k: the second child at depth k) and how deep that leaf is.
#[derive(Clone, Debug)]
pub struct LightBvh {
    pub nodes: Vec<Node>,
    pub trails: Vec<(u64, u32)>,
    /// Lights with a non-finite corner or power are not in the tree (their PDF is 0). A
    /// light with no power is, with PDF 0 until a refit gives it power (a blinking light).
    pub in_tree: Vec<bool>,
    /// Per node its parent, per light its leaf (`NO_NODE`: the root; a light not in the
    /// tree): what a refit of a few lights climbs.
    pub parents: Vec<u32>,
    pub leaves: Vec<u32>,
}

/// No node: the root's parent, the leaf of a light outside the tree.
pub const NO_NODE: u32 = u32::MAX;

/// A drawn light and the probability of drawing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampled {
    pub light: usize,
    pub pdf: f32,
}

impl LightBvh {
    /// Builds top-down, splitting each node's lights at the median centroid along the box's
    /// longest axis (a leaf holds one light, as in pbrt-v4). Depth is at most 64 (the trail
    /// is a u64), which a median split reaches only past 2^64 lights.
    pub fn build(lights: &[EmissiveTriangle]) -> LightBvh {
        let mut bvh = LightBvh {
            nodes: Vec::new(),
            trails: vec![(0, 0); lights.len()],
            in_tree: vec![false; lights.len()],
            parents: Vec::new(),
            leaves: vec![NO_NODE; lights.len()],
        };
        let mut ids: Vec<usize> = (0..lights.len())
            .filter(|&i| {
                let l = &lights[i];
                l.power >= 0.0 && l.power.is_finite() && l.p.iter().all(|v| v.is_finite())
            })
            .collect();
        if !ids.is_empty() {
            bvh.build_node(lights, &mut ids, 0, 0);
        }
        bvh.parents = vec![NO_NODE; bvh.nodes.len()];
        for (index, node) in bvh.nodes.iter().enumerate() {
            match node {
                Node::Interior { children, .. } => {
                    children.iter().for_each(|&c| bvh.parents[c] = index as u32)
                }
                Node::Leaf { light, .. } => bvh.leaves[*light] = index as u32,
            }
        }
        bvh
    }

    fn build_node(
        &mut self,
        lights: &[EmissiveTriangle],
        ids: &mut [usize],
        trail: u64,
        depth: u32,
    ) -> usize {
        let index = self.nodes.len();
        if ids.len() == 1 {
            let light = ids[0];
            self.trails[light] = (trail, depth);
            self.in_tree[light] = true;
            self.nodes.push(Node::Leaf {
                bounds: lights[light].bounds(),
                light,
            });
            return index;
        }
        self.nodes.push(Node::Leaf {
            bounds: lights[ids[0]].bounds(),
            light: ids[0],
        });
        let (lo, hi) = ids
            .iter()
            .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &i| {
                let c = lights[i].centroid();
                (lo.min(c), hi.max(c))
            });
        let extent = hi - lo;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let mid = ids.len() / 2;
        ids.select_nth_unstable_by(mid, |&a, &b| {
            lights[a].centroid()[axis].total_cmp(&lights[b].centroid()[axis])
        });
        let (left, right) = ids.split_at_mut(mid);
        let a = self.build_node(lights, left, trail, depth + 1);
        let b = self.build_node(lights, right, trail | (1 << depth), depth + 1);
        let bounds = LightBounds::union(self.nodes[a].bounds(), self.nodes[b].bounds());
        self.nodes[index] = Node::Interior {
            bounds,
            children: [a, b],
        };
        index
    }

    /// The probabilities of taking each child at an interior node: ∝ their importance, or,
    /// where both are 0 (the parent's looser bounds let the walk this far, the children's
    /// do not), ∝ their power, so every walk ends at a light and the PDF sums to 1 over the
    /// lights (a light that cannot reach the point then contributes 0; still unbiased).
    fn branch(
        &self,
        children: [usize; 2],
        p: Vec3,
        n: Vec3,
        orientation: bool,
    ) -> Option<[f32; 2]> {
        let share = |w: [f32; 2]| {
            let total = w[0] + w[1];
            (total > 0.0 && total.is_finite()).then(|| [w[0] / total, w[1] / total])
        };
        share(children.map(|c| self.nodes[c].bounds().importance(p, n, orientation)))
            .or_else(|| share(children.map(|c| self.nodes[c].bounds().phi)))
    }

    /// Draws a light for shading point `p` (normal `n`, or zero) with the number `u` in
    /// [0, 1): down from the root, each child with probability ∝ its importance, `u`
    /// rescaled at each step. None only for a tree without lights.
    pub fn sample(&self, p: Vec3, n: Vec3, mut u: f32, orientation: bool) -> Option<Sampled> {
        let mut node = 0;
        let mut pdf = 1.0f32;
        loop {
            match self.nodes.get(node)? {
                Node::Leaf { light, .. } => return Some(Sampled { light: *light, pdf }),
                Node::Interior { children, .. } => {
                    let prob = self.branch(*children, p, n, orientation)?;
                    if u < prob[0] {
                        u = (u / prob[0]).min(1.0 - f32::EPSILON);
                        pdf *= prob[0];
                        node = children[0];
                    } else {
                        u = ((u - prob[0]) / prob[1]).min(1.0 - f32::EPSILON);
                        pdf *= prob[1];
                        node = children[1];
                    }
                }
            }
        }
    }

    /// The probability that `sample` draws `light` at `p`: the product of the branch
    /// probabilities along its trail (0 for a light not in the tree).
    pub fn pdf(&self, light: usize, p: Vec3, n: Vec3, orientation: bool) -> f32 {
        if !self.in_tree.get(light).copied().unwrap_or(false) {
            return 0.0;
        }
        let (trail, depth) = self.trails[light];
        let mut node = 0;
        let mut pdf = 1.0;
        for k in 0..depth {
            let Node::Interior { children, .. } = &self.nodes[node] else {
                return 0.0;
            };
            let Some(prob) = self.branch(*children, p, n, orientation) else {
                return 0.0;
            };
            let side = ((trail >> k) & 1) as usize;
            pdf *= prob[side];
            node = children[side];
        }
        pdf
    }

    /// Moved lights or changed powers (same lights): every node's bounds recomputed from
    /// its children, leaves from their triangles, bottom up. The tree's shape is kept, so
    /// its quality degrades as lights wander; adding or removing lights rebuilds.
    pub fn refit(&mut self, lights: &[EmissiveTriangle]) {
        for index in (0..self.nodes.len()).rev() {
            self.recompute(index, lights);
        }
    }

    /// The refit for `changed` lights only (those that moved or changed power): their
    /// leaves and every node above them, children before parents; the other nodes keep
    /// their bounds, which are still right. The same tree as `refit` when `changed` lists
    /// every light that changed. Returns the nodes it rewrote, in ascending order.
    pub fn refit_changed(&mut self, lights: &[EmissiveTriangle], changed: &[usize]) -> Vec<usize> {
        let rewritten = self.nodes_above(changed);
        // Preorder: a node's children come after it, so descending order is bottom up.
        for &index in rewritten.iter().rev() {
            self.recompute(index, lights);
        }
        rewritten
    }

    /// The leaves of the `changed` lights and every node above them, ascending.
    pub fn nodes_above(&self, changed: &[usize]) -> Vec<usize> {
        let (mut marks, mut nodes) = (Vec::new(), Vec::new());
        self.nodes_above_into(changed, &mut marks, &mut nodes);
        nodes
    }

    /// `nodes_above` into `nodes`, with `marks` (one flag per node, all false between
    /// calls) kept by the caller: a refit every frame then allocates nothing, and clears
    /// only the flags it set, not one per node of a million-light tree.
    pub fn nodes_above_into(
        &self,
        changed: &[usize],
        marks: &mut Vec<bool>,
        nodes: &mut Vec<usize>,
    ) {
        marks.resize(self.nodes.len(), false);
        nodes.clear();
        for &light in changed {
            let mut node = self.leaves.get(light).copied().unwrap_or(NO_NODE);
            // Up to the root, or to a node another changed light already marked.
            while node != NO_NODE && !marks[node as usize] {
                marks[node as usize] = true;
                nodes.push(node as usize);
                node = self.parents[node as usize];
            }
        }
        for &node in nodes.iter() {
            marks[node] = false;
        }
        nodes.sort_unstable();
    }

    /// Node `index`'s bounds from its light or its children.
    fn recompute(&mut self, index: usize, lights: &[EmissiveTriangle]) {
        let bounds = match &self.nodes[index] {
            Node::Leaf { light, .. } => lights[*light].bounds(),
            Node::Interior { children, .. } => LightBounds::union(
                self.nodes[children[0]].bounds(),
                self.nodes[children[1]].bounds(),
            ),
        };
        match &mut self.nodes[index] {
            Node::Leaf { bounds: b, .. } | Node::Interior { bounds: b, .. } => *b = bounds,
        }
    }
}

#[cfg(test)]
mod tests;
