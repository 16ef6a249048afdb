//! A two-level BVH on the CPU, measured against refitting and rebuilding the single tree
//! (`restir-viewer bench-bvh`, docs/src/measured/dynamic-scenes.md "BVH: refit, rebuild or two
//! levels"): a bottom-level tree (BLAS) per instance — each animated mesh binding, plus one
//! for every triangle that never moves — built once in the instance's own space, and a
//! top-level tree (TLAS) over the instances' world boxes, rebuilt every frame. The renderer
//! does not use it: the GPU traverses one tree whose root keeps the moving triangles apart
//! from the static ones (`split.rs`, shaders/common/trace_bvh.wgsl), refitted rather than
//! re-placed.

use glam::{Mat4, Vec3};

use super::{Bvh, Hit, Ray, Visits};
use crate::scene::{Aabb, Scene};

struct Instance {
    /// Source triangle indices, in this BLAS's order.
    triangles: Vec<u32>,
    /// The same triangles in the instance's space, BLAS order.
    local: Vec<[Vec3; 3]>,
    blas: Bvh,
    /// The node whose world matrix places the instance; `None` for the static one.
    node: Option<usize>,
}

pub struct TwoLevelBvh {
    instances: Vec<Instance>,
    /// Over the instances' world boxes; `triangle_order` holds instance indices.
    tlas: Bvh,
    to_world: Vec<Mat4>,
    to_local: Vec<Mat4>,
}

/// A hit in a two-level tree: the source triangle (scene order) and the ray parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstanceHit {
    pub t: f32,
    pub triangle: u32,
}

impl TwoLevelBvh {
    /// The BLASes of `scene`: triangles whose vertices belong to a mesh binding of its
    /// animation from that binding's local vertices, all others (as posed) in one static
    /// instance. Call `update` before tracing.
    pub fn new(scene: &Scene) -> TwoLevelBvh {
        let meshes = scene
            .animation
            .as_ref()
            .map(|a| a.meshes.as_slice())
            .unwrap_or(&[]);
        // Bindings by first vertex, to find a vertex's binding by binary search.
        let mut by_first: Vec<usize> = (0..meshes.len()).collect();
        by_first.sort_by_key(|&m| meshes[m].first);
        let binding_of = |vertex: u32| -> Option<usize> {
            let k = by_first.partition_point(|&m| meshes[m].first <= vertex);
            let m = *by_first.get(k.checked_sub(1)?)?;
            let b = &meshes[m];
            (vertex < b.first + b.local.len() as u32).then_some(m)
        };
        // Instance 0 is the static one; binding m is instance m + 1.
        let mut members: Vec<Vec<(u32, [Vec3; 3])>> = vec![Vec::new(); meshes.len() + 1];
        for (t, tri) in scene.triangles.iter().enumerate() {
            let binding = binding_of(tri.indices[0])
                .filter(|&m| tri.indices.iter().all(|&v| binding_of(v) == Some(m)));
            let (slot, positions) = match binding {
                Some(m) => {
                    let b = &meshes[m];
                    let p = tri
                        .indices
                        .map(|v| b.local[(v - b.first) as usize].position);
                    (m + 1, p)
                }
                None => (0, scene.triangle_positions(t)),
            };
            members[slot].push((t as u32, positions));
        }
        let instances = members
            .into_iter()
            .enumerate()
            .filter(|(_, m)| !m.is_empty())
            .map(|(slot, m)| {
                let positions: Vec<[Vec3; 3]> = m.iter().map(|x| x.1).collect();
                let blas = Bvh::build(&positions);
                let ids: Vec<_> = m.iter().map(|x| x.0).collect();
                let triangles = blas.in_leaf_order(&ids);
                let local = blas.in_leaf_order(&positions);
                Instance {
                    triangles,
                    local,
                    blas,
                    node: slot.checked_sub(1).map(|m| meshes[m].node),
                }
            })
            .collect::<Vec<_>>();
        let n = instances.len();
        TwoLevelBvh {
            instances,
            tlas: Bvh::build_boxes(&[]),
            to_world: vec![Mat4::IDENTITY; n],
            to_local: vec![Mat4::IDENTITY; n],
        }
    }

    pub fn instance_count(&self) -> usize {
        self.instances.len()
    }

    /// Places every instance by its node's matrix in `world` (SceneAnimation::world_matrices)
    /// and rebuilds the TLAS over their world boxes: the per-frame work of this structure.
    pub fn update(&mut self, world: &[Mat4]) {
        let mut boxes = Vec::with_capacity(self.instances.len());
        for (i, inst) in self.instances.iter().enumerate() {
            let m = inst
                .node
                .and_then(|n| world.get(n).copied())
                .unwrap_or(Mat4::IDENTITY);
            self.to_world[i] = m;
            self.to_local[i] = m.inverse();
            boxes.push(transformed_box(root_box(&inst.blas), m));
        }
        self.tlas = Bvh::build_boxes(&boxes);
    }

    /// Nearest hit, adding TLAS and BLAS nodes and triangle tests to `visits`.
    pub fn closest_hit_counted(&self, ray: &Ray, visits: &mut Visits) -> Option<InstanceHit> {
        self.trace(ray, false, visits)
    }

    /// Whether anything is hit in (0, t_max): a shadow ray.
    pub fn any_hit_counted(&self, ray: &Ray, visits: &mut Visits) -> bool {
        self.trace(ray, true, visits).is_some()
    }

    fn trace(&self, ray: &Ray, any: bool, visits: &mut Visits) -> Option<InstanceHit> {
        let mut tlas_visits = Visits::default();
        let mut blas_visits = Visits::default();
        let mut found: Option<InstanceHit> = None;
        self.tlas
            .walk(ray, any, &mut tlas_visits, |position, t_max| {
                let i = self.tlas.triangle_order[position as usize] as usize;
                let inst = &self.instances[i];
                // An affine map keeps the ray parameter: t in the instance's space is t here.
                let m = self.to_local[i];
                let local = Ray {
                    origin: m.transform_point3(ray.origin),
                    dir: m.transform_vector3(ray.dir),
                    t_max,
                };
                let hit = inst.blas.walk(&local, any, &mut blas_visits, |j, t| {
                    let (t, u, v) = super::traverse::intersect_triangle(
                        &inst.local[j as usize],
                        local.origin,
                        local.dir,
                        t,
                    )?;
                    Some(Hit {
                        t,
                        triangle: j,
                        u,
                        v,
                    })
                })?;
                found = Some(InstanceHit {
                    t: hit.t,
                    triangle: inst.triangles[hit.triangle as usize],
                });
                Some(hit)
            });
        // A TLAS leaf's instance test is a traversal step (a transform and a root box);
        // the BLAS triangle tests are the primitives.
        visits.nodes += tlas_visits.nodes + tlas_visits.primitives + blas_visits.nodes;
        visits.primitives += blas_visits.primitives;
        found
    }

    /// SAH-style cost relative to the TLAS root box: the TLAS's own (its leaves' instance
    /// tests counted as traversal steps), plus for each instance its BLAS cost scaled by its
    /// world box's area. Comparable with `Bvh::sah_cost` of a single tree over the same
    /// triangles, as an estimate: a rotated instance's world box is larger than its BLAS
    /// root box, which this ignores.
    pub fn sah_cost(&self) -> f64 {
        let Some(root) = self.tlas.nodes.first() else {
            return 0.0;
        };
        let root_area = node_box(root).half_area() as f64;
        let root_area = root_area.max(f64::MIN_POSITIVE);
        let instances: f64 = self
            .instances
            .iter()
            .zip(&self.to_world)
            .map(|(inst, &m)| {
                let area = transformed_box(root_box(&inst.blas), m).half_area() as f64;
                area / root_area * inst.blas.sah_cost()
            })
            .sum();
        self.tlas.sah_cost() + instances
    }
}

fn node_box(n: &crate::gpu_types::GpuBvhNode) -> Aabb {
    Aabb {
        min: Vec3::from(n.min),
        max: Vec3::from(n.max),
    }
}

fn root_box(bvh: &Bvh) -> Aabb {
    bvh.nodes.first().map(node_box).unwrap_or(Aabb::EMPTY)
}

/// The world box of a box's eight corners under `m`.
fn transformed_box(b: Aabb, m: Mat4) -> Aabb {
    let mut out = Aabb::EMPTY;
    for k in 0..8 {
        let corner = Vec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        );
        out.grow(m.transform_point3(corner));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::animation::ClipChoice;
    use crate::scene::builtin::builtin_scene;

    /// Rays from above the stage, down and slightly slanted, over a 16 × 16 grid.
    fn rays() -> Vec<Ray> {
        (0..256)
            .map(|k| {
                let (x, z) = ((k % 16) as f32 / 15.0, (k / 16) as f32 / 15.0);
                Ray {
                    origin: Vec3::new(-3.0 + 6.0 * x, 3.5, -3.0 + 6.0 * z),
                    dir: Vec3::new(0.1, -1.0, 0.05),
                    t_max: f32::INFINITY,
                }
            })
            .collect()
    }

    /// (source triangle, t) of every ray's nearest hit in a single tree over `scene` as posed.
    fn single_level_hits(scene: &Scene) -> Vec<Option<(u32, f32)>> {
        let positions: Vec<[Vec3; 3]> = (0..scene.triangles.len())
            .map(|t| scene.triangle_positions(t))
            .collect();
        let bvh = Bvh::build(&positions);
        let ordered: Vec<[Vec3; 3]> = bvh
            .triangle_order
            .iter()
            .map(|&i| positions[i as usize])
            .collect();
        rays()
            .iter()
            .map(|r| {
                bvh.closest_hit(&ordered, r)
                    .map(|h| (bvh.triangle_order[h.triangle as usize], h.t))
            })
            .collect()
    }

    /// How many rays hit a different triangle (or t off by more than 1e-4 m) in the two-level
    /// tree placed at `placed_at` than in a single tree of the scene posed at `posed_at`.
    fn mismatches(posed_at: f32, placed_at: f32) -> (usize, usize) {
        let mut scene = builtin_scene("dynamic:moving-occluder").unwrap();
        let anim = scene.animation.clone().unwrap();
        let mut two = TwoLevelBvh::new(&scene);
        anim.pose(&mut scene, posed_at, ClipChoice::All);
        two.update(&anim.world_matrices(placed_at, ClipChoice::All));
        let expected = single_level_hits(&scene);
        let mut visits = Visits::default();
        let got: Vec<_> = rays()
            .iter()
            .map(|r| {
                two.closest_hit_counted(r, &mut visits)
                    .map(|h| (h.triangle, h.t))
            })
            .collect();
        let differ = expected
            .iter()
            .zip(&got)
            .filter(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => a.0 != b.0 || (a.1 - b.1).abs() > 1e-4,
                (None, None) => false,
                _ => true,
            })
            .count();
        let blade_hits = expected.iter().flatten().count();
        (differ, blade_hits)
    }

    #[test]
    fn two_level_hits_what_a_single_tree_of_the_posed_scene_hits() {
        // The blade at 1.3 s (about a third of a turn): every ray finds the same triangle
        // at the same distance (f32 transforms of the ray: well under 1e-4 m).
        let (differ, hits) = mismatches(1.3, 1.3);
        assert!(hits > 200, "{hits} hits");
        assert_eq!(differ, 0);
        let scene = builtin_scene("dynamic:moving-occluder").unwrap();
        // The blade's mesh binding, and everything else in one static instance.
        assert_eq!(TwoLevelBvh::new(&scene).instance_count(), 2);
    }

    #[test]
    fn planted_stale_instance_transform_is_detected() {
        // Test power: the TLAS placed with the blade's pose 0.4 s earlier (36° back) must
        // disagree with the posed scene on the rays that meet the blade.
        let (differ, _) = mismatches(1.3, 0.9);
        assert!(differ > 5, "only {differ} rays differ");
    }

    #[test]
    fn shadow_rays_agree_with_closest_hits() {
        let mut scene = builtin_scene("dynamic:moving-occluder").unwrap();
        let anim = scene.animation.clone().unwrap();
        let mut two = TwoLevelBvh::new(&scene);
        anim.pose(&mut scene, 0.7, ClipChoice::All);
        two.update(&anim.world_matrices(0.7, ClipChoice::All));
        let mut visits = Visits::default();
        for mut r in rays() {
            let nearest = two.closest_hit_counted(&r, &mut visits).map(|h| h.t);
            r.t_max = nearest.map_or(f32::INFINITY, |t| t * 0.999);
            assert!(
                !two.any_hit_counted(&r, &mut visits),
                "hit before the nearest"
            );
            r.t_max = nearest.map_or(f32::INFINITY, |t| t * 1.001);
            assert_eq!(two.any_hit_counted(&r, &mut visits), nearest.is_some());
        }
        assert!(visits.nodes > 0 && visits.primitives > 0);
    }
}
