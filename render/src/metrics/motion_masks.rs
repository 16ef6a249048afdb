//! Which pixels of a moving shot a reuse-based estimator finds hardest, from geometry alone
//! (the same for every estimator, so their errors there compare;
//! docs/src/measured/how-the-bench-measures.md, "Errors where the view moves"):
//! - **disoccluded**: the surface a pixel sees was not visible in the previous frame (off
//!   screen, or behind something then) — where temporal reuse has no history, and where a
//!   ReSTIR that trusts a bad history smears dark (the failure users of Quake II RTX's port
//!   report);
//! - **near moving**: the pixel sees, or saw in the previous frame, a triangle that moved
//!   between the two frames, widened by [`near_moving_radius`] pixels — where light
//!   around a moving object changes, and where a denoiser fed without reuse paints blobs
//!   (Bevy Solari's report).
//!
//! Both come from CPU ray casts through the scene's triangles ([`Bvh`]) with the GPU's
//! camera rays (shaders/common/camera_ray.wgsl): the pixel's surface point now, carried to
//! the previous frame by its barycentrics on the same triangle, then projected into the
//! previous camera and tested for visibility there.

use glam::Vec3;

use crate::image::{LinearImage, luminance};
use crate::scene::Camera;
use crate::scene::bvh::{Bvh, Ray};

/// One frame as the masks see it: its camera and every triangle's positions (scene order).
#[derive(Clone, Copy)]
pub struct Posed<'a> {
    pub camera: Camera,
    pub positions: &'a [[Vec3; 3]],
}

/// One frame's masks, row-major from the top row like [`LinearImage`].
#[derive(Clone, Debug, PartialEq)]
pub struct MotionMasks {
    pub width: u32,
    pub height: u32,
    pub disoccluded: Vec<bool>,
    pub near_moving: Vec<bool>,
}

impl MotionMasks {
    /// Nothing marked: the first frame of a shot, which has no previous frame.
    pub fn empty(width: u32, height: u32) -> MotionMasks {
        let n = (width * height) as usize;
        MotionMasks {
            width,
            height,
            disoccluded: vec![false; n],
            near_moving: vec![false; n],
        }
    }
}

/// How far the near-moving mask reaches beyond the moving triangles' pixels: 1/64 of the
/// image width (at least one pixel), about the reach of the spatial reuse radius and of a
/// moving object's contact shadow at the sizes the bench runs, and the same share of the
/// image at every size.
pub fn near_moving_radius(width: u32) -> u32 {
    width.div_ceil(64).max(1)
}

/// A point is hidden in the previous frame when something lies in front of it by more than
/// this fraction of its distance (the point's own triangle is hit at the full distance,
/// within rounding).
const OCCLUSION_MARGIN: f32 = 1e-3;

/// Casts the masks' rays: one tree over the scene's triangles, refitted to each frame's
/// positions (the topology stays, so a moving scene costs a refit, not a rebuild).
pub struct MaskTracer {
    bvh: Bvh,
    /// The triangles in BVH order, as last fitted.
    ordered: Vec<[Vec3; 3]>,
}

struct SurfaceHit {
    triangle: usize,
    u: f32,
    v: f32,
}

impl MaskTracer {
    pub fn new(positions: &[[Vec3; 3]]) -> MaskTracer {
        let bvh = Bvh::build(positions);
        let ordered = bvh.in_leaf_order(positions);
        MaskTracer { bvh, ordered }
    }

    fn fit(&mut self, positions: &[[Vec3; 3]]) {
        let mut changed = false;
        for (slot, &i) in self.ordered.iter_mut().zip(&self.bvh.triangle_order) {
            let p = positions[i as usize];
            if *slot != p {
                *slot = p;
                changed = true;
            }
        }
        if changed {
            self.bvh.refit(&self.ordered);
        }
    }

    fn closest(&self, ray: &Ray) -> Option<SurfaceHit> {
        if self.bvh.nodes.is_empty() {
            return None;
        }
        let hit = self.bvh.closest_hit(&self.ordered, ray)?;
        Some(SurfaceHit {
            triangle: self.bvh.triangle_order[hit.triangle as usize] as usize,
            u: hit.u,
            v: hit.v,
        })
    }

    /// The masks of frame `current`, which follows `previous` (both with positions in scene
    /// order, as many as the tracer was built with; otherwise nothing is marked).
    pub fn masks(
        &mut self,
        previous: Posed,
        current: Posed,
        width: u32,
        height: u32,
    ) -> MotionMasks {
        let n = (width * height) as usize;
        let triangles = self.ordered.len();
        if previous.positions.len() != triangles || current.positions.len() != triangles {
            return MotionMasks::empty(width, height);
        }
        let moved: Vec<bool> = previous
            .positions
            .iter()
            .zip(current.positions)
            .map(|(a, b)| a != b)
            .collect();
        let pixel_ray = |camera: &Camera, p: usize| -> Ray {
            let (x, y) = ((p as u32 % width) as f32, (p as u32 / width) as f32);
            Ray {
                origin: camera.position,
                dir: camera_ray_direction(camera, width, height, x + 0.5, y + 0.5),
                t_max: f32::INFINITY,
            }
        };
        self.fit(current.positions);
        let now: Vec<Option<SurfaceHit>> = (0..n)
            .map(|p| self.closest(&pixel_ray(&current.camera, p)))
            .collect();
        self.fit(previous.positions);
        let mut disoccluded = vec![false; n];
        let mut seeds = vec![false; n];
        for p in 0..n {
            let before = self.closest(&pixel_ray(&previous.camera, p));
            let Some(hit) = &now[p] else {
                seeds[p] = before.is_some_and(|b| moved[b.triangle]);
                continue;
            };
            seeds[p] = moved[hit.triangle] || before.is_some_and(|b| moved[b.triangle]);
            let [a, b, c] = previous.positions[hit.triangle];
            let point = a * (1.0 - hit.u - hit.v) + b * hit.u + c * hit.v;
            disoccluded[p] = !self.visible(&previous.camera, point, width, height);
        }
        MotionMasks {
            width,
            height,
            disoccluded,
            near_moving: dilate(&seeds, width, height, near_moving_radius(width)),
        }
    }

    /// Whether `point` is inside `camera`'s image and nothing (as last fitted) hides it.
    fn visible(&self, camera: &Camera, point: Vec3, width: u32, height: u32) -> bool {
        let d = point - camera.position;
        let depth = d.dot(camera.forward());
        if depth <= 0.0 {
            return false;
        }
        let tan_v = (camera.yfov * 0.5).tan();
        let tan_h = tan_v * width as f32 / height as f32;
        let ndc_x = d.dot(camera.right()) / (depth * tan_h);
        let ndc_y = d.dot(camera.up()) / (depth * tan_v);
        if ndc_x.abs() > 1.0 || ndc_y.abs() > 1.0 {
            return false;
        }
        let distance = d.length();
        let ray = Ray {
            origin: camera.position,
            dir: d / distance,
            t_max: distance * (1.0 - OCCLUSION_MARGIN),
        };
        self.bvh.nodes.is_empty() || !self.bvh.any_hit(&self.ordered, &ray)
    }
}

/// The direction of the ray through image point (`x`, `y`) in pixels from the top-left
/// corner: shaders/common/camera_ray.wgsl's for a pinhole camera.
fn camera_ray_direction(camera: &Camera, width: u32, height: u32, x: f32, y: f32) -> Vec3 {
    let ndc_x = x / width as f32 * 2.0 - 1.0;
    let ndc_y = 1.0 - y / height as f32 * 2.0;
    let tan_v = (camera.yfov * 0.5).tan();
    let tan_h = tan_v * width as f32 / height as f32;
    (camera.forward() + camera.right() * (ndc_x * tan_h) + camera.up() * (ndc_y * tan_v))
        .normalize()
}

/// `mask` grown by a square of `radius` pixels.
fn dilate(mask: &[bool], width: u32, height: u32, radius: u32) -> Vec<bool> {
    let (w, h, r) = (width as i64, height as i64, radius as i64);
    let mut out = vec![false; mask.len()];
    for p in (0..mask.len()).filter(|&p| mask[p]) {
        let (x, y) = (p as i64 % w, p as i64 / w);
        for yy in (y - r).max(0)..=(y + r).min(h - 1) {
            for xx in (x - r).max(0)..=(x + r).min(w - 1) {
                out[(yy * w + xx) as usize] = true;
            }
        }
    }
    out
}

/// A frame's luminance error pooled over the pixels of a mask, over many frames: the share
/// of pixels marked, their luma RMSE and their signed bias (Σ(frame − reference) /
/// Σ reference: negative where a revealed surface is too dark).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MaskedError {
    marked: u64,
    pixels: u64,
    squared: f64,
    difference: f64,
    reference: f64,
}

impl MaskedError {
    /// Adds one frame's pixels under `mask` (non-finite pixels left out, as every metric
    /// does).
    pub fn push(&mut self, frame: &LinearImage, reference: &LinearImage, mask: &[bool]) {
        self.pixels += mask.len() as u64;
        for ((f, r), &m) in frame.pixels.iter().zip(&reference.pixels).zip(mask) {
            if !m {
                continue;
            }
            let (f, r) = (
                luminance([f[0], f[1], f[2]]) as f64,
                luminance([r[0], r[1], r[2]]) as f64,
            );
            if !(f.is_finite() && r.is_finite()) {
                continue;
            }
            self.marked += 1;
            self.squared += (f - r) * (f - r);
            self.difference += f - r;
            self.reference += r;
        }
    }

    /// Marked pixels over all pixels seen.
    pub fn share(&self) -> f64 {
        if self.pixels == 0 {
            0.0
        } else {
            self.marked as f64 / self.pixels as f64
        }
    }

    /// None when no pixel was marked.
    pub fn luma_rmse(&self) -> Option<f64> {
        (self.marked > 0).then(|| (self.squared / self.marked as f64).sqrt())
    }

    /// None when no pixel was marked or the marked reference is black.
    pub fn signed_bias(&self) -> Option<f64> {
        (self.marked > 0 && self.reference > 0.0).then(|| self.difference / self.reference)
    }
}

#[cfg(test)]
mod tests;
