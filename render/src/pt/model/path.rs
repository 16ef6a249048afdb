//! Paths from a pixel's primary surface to an emitter: traced from random numbers, and
//! evaluated (contribution and density) from their vertices, the same function for a path
//! as found and a path as shifted.

use glam::Vec3;

use super::lobe::Lobe;
use super::toy_scene::{Hit, Kind, ToyScene};

/// Most bounces a path has (`x_1 → … → x_{MAX_BOUNCES+1}`).
pub const MAX_BOUNCES: usize = 3;

/// A pixel as reuse sees it: its primary surface (the G-buffer) and the direction back to
/// the camera.
#[derive(Clone, Copy, Debug)]
pub struct Pixel {
    pub primary: Hit,
    pub to_camera: Vec3,
}

/// A path of `bounces` bounces: `vertices[0]` is the pixel's primary surface,
/// `vertices[bounces]` is on an emitter. `numbers[b]` drew the direction at `vertices[b]`
/// (for a reconnected bounce: the numbers that would have drawn it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathSample {
    pub bounces: usize,
    pub vertices: [Hit; MAX_BOUNCES + 1],
    pub numbers: [[f32; 2]; MAX_BOUNCES],
}

/// What the path estimator needs of a path at a pixel: `f` and the density it was sampled
/// with (the product of its lobes' densities; meaningful for a traced path).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluated {
    pub contribution: f32,
    pub pdf: f32,
}

/// The lobe of a reflecting surface (`None` for emitters and the blocker).
pub fn lobe_at(scene: &ToyScene, hit: &Hit) -> Option<Lobe> {
    scene.lobe(hit)
}

/// The direction arriving light leaves by at vertex `b` of `path` (toward the camera at
/// the primary, toward the previous vertex after).
pub fn w_in(pixel: &Pixel, path: &PathSample, b: usize) -> Vec3 {
    if b == 0 {
        pixel.to_camera
    } else {
        (path.vertices[b - 1].position - path.vertices[b].position).normalize()
    }
}

/// One bounce: the direction `numbers` draw at `at` (arriving from `w_in`), and what it
/// hits. `None` when `at` does not reflect, the direction is below it, or nothing is hit.
pub fn bounce(scene: &ToyScene, at: &Hit, w_in: Vec3, numbers: [f32; 2]) -> Option<Hit> {
    let lobe = lobe_at(scene, at)?;
    let sampled = lobe.sample(at.normal, w_in, numbers);
    if lobe.eval(at.normal, w_in, sampled.direction) <= 0.0 {
        return None;
    }
    scene.intersect(at.position, sampled.direction, f32::MAX)
}

/// Traces from `pixel` with `numbers`: the path, if it reaches an emitter after two or
/// more bounces (one bounce is direct light, which ReSTIR DI owns) within `MAX_BOUNCES`.
pub fn trace(
    scene: &ToyScene,
    pixel: &Pixel,
    numbers: [[f32; 2]; MAX_BOUNCES],
) -> Option<PathSample> {
    let mut path = PathSample {
        numbers,
        ..PathSample::default()
    };
    path.vertices[0] = pixel.primary;
    for (b, &u) in numbers.iter().enumerate() {
        let next = bounce(scene, &path.vertices[b], w_in(pixel, &path, b), u)?;
        path.vertices[b + 1] = next;
        match scene.kind(&next) {
            Kind::Emits { .. } if b >= 1 => {
                path.bounces = b + 1;
                return Some(path);
            }
            Kind::Reflects(_) => {}
            _ => return None,
        }
    }
    None
}

/// `f(x̄)` at `pixel` and the density of sampling it by its lobes (module docs of
/// `path_reuse`). Visibility between consecutive vertices is the caller's (traced or
/// shadow-tested) knowledge.
pub fn evaluate(scene: &ToyScene, pixel: &Pixel, path: &PathSample) -> Evaluated {
    if path.bounces == 0 {
        return Evaluated {
            contribution: 0.0,
            pdf: 0.0,
        };
    }
    let mut contribution = 1.0;
    let mut pdf = 1.0;
    for b in 0..path.bounces {
        let at = &path.vertices[b];
        let Some(lobe) = lobe_at(scene, at) else {
            return Evaluated {
                contribution: 0.0,
                pdf: 0.0,
            };
        };
        let w_in = w_in(pixel, path, b);
        let out = (path.vertices[b + 1].position - at.position).normalize();
        contribution *= lobe.eval(at.normal, w_in, out) * at.normal.dot(out).abs();
        pdf *= lobe.pdf(at.normal, w_in, out);
    }
    let last = &path.vertices[path.bounces];
    contribution *= scene.emitted(last, path.vertices[path.bounces - 1].position);
    Evaluated { contribution, pdf }
}
