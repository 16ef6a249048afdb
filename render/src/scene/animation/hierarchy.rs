//! The node tree kept from glTF: each node's rest local transform and its parent, and the
//! world transforms of a pose (parent chains composed: world = parent world × local).

use glam::{Mat4, Quat, Vec3};

/// A local transform as glTF gives it. A node given by `matrix` cannot be animated (spec
/// §3.5.3: animation targets TRS), so it keeps its matrix exactly, shear and all.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Local {
    Matrix(Mat4),
    Trs(Trs),
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    pub translation: Vec3,
    pub rotation: Quat,
    pub scale: Vec3,
}

impl Default for Trs {
    fn default() -> Self {
        Self {
            translation: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            scale: Vec3::ONE,
        }
    }
}

impl Trs {
    /// T × R × S, the glTF order.
    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub name: String,
    pub parent: Option<usize>,
    pub rest: Local,
}

/// Nodes plus an order in which every parent comes before its children.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Hierarchy {
    nodes: Vec<Node>,
    order: Vec<usize>,
}

impl Hierarchy {
    /// Refuses parent indices out of range and cycles (a node must not be its own ancestor).
    pub fn new(nodes: Vec<Node>) -> Result<Self, String> {
        let n = nodes.len();
        if let Some((i, p)) = nodes
            .iter()
            .enumerate()
            .find_map(|(i, node)| node.parent.filter(|&p| p >= n).map(|p| (i, p)))
        {
            return Err(format!("node {i} has parent {p} of {n} nodes"));
        }
        // Depth by walking up; a walk longer than n steps has met a cycle.
        let mut depth = vec![0usize; n];
        for (i, d) in depth.iter_mut().enumerate() {
            let mut at = i;
            while let Some(p) = nodes[at].parent {
                *d += 1;
                if *d > n {
                    return Err(format!("node {i} is its own ancestor"));
                }
                at = p;
            }
        }
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&i| depth[i]);
        Ok(Self { nodes, order })
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    pub fn node(&self, i: usize) -> &Node {
        &self.nodes[i]
    }

    /// The rest TRS of node `i`, or `None` for a matrix node (not animatable).
    pub fn rest_trs(&self, i: usize) -> Option<Trs> {
        match self.nodes[i].rest {
            Local::Trs(trs) => Some(trs),
            Local::Matrix(_) => None,
        }
    }

    /// World matrices for local transforms `locals` (one per node, from `rest_locals` with a
    /// pose's channels applied).
    pub fn world_matrices(&self, locals: &[Local]) -> Vec<Mat4> {
        let mut world = vec![Mat4::IDENTITY; self.nodes.len()];
        for &i in &self.order {
            let local = match locals[i] {
                Local::Matrix(m) => m,
                Local::Trs(trs) => trs.matrix(),
            };
            world[i] = match self.nodes[i].parent {
                Some(p) => world[p] * local,
                None => local,
            };
        }
        world
    }

    pub fn rest_locals(&self) -> Vec<Local> {
        self.nodes.iter().map(|n| n.rest).collect()
    }

    /// Whether node `i` or one of its ancestors is in `animated`.
    pub fn moves(&self, i: usize, animated: &[bool]) -> bool {
        let mut at = Some(i);
        let mut steps = 0;
        while let Some(n) = at {
            if animated[n] {
                return true;
            }
            at = self.nodes[n].parent;
            steps += 1;
            if steps > self.nodes.len() {
                break; // `new` refuses cycles; this is only a guard
            }
        }
        false
    }
}
