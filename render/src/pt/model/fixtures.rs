//! What the path-reuse tests share beyond `experiment.rs`: a scene for finite differences
//! and a search for a path that takes a given route.

pub use super::experiment::pixel;
use super::experiment::random_numbers;
use super::path::{PathSample, Pixel, trace};
use super::toy_scene::ToyScene;
use crate::scene::builtin::rng::SplitMix64;

/// Rough enough a mirror that finite differences of its lobe stay smooth.
pub fn scene_for_fd() -> ToyScene {
    ToyScene::new(0.35, 0.1)
}

/// The first traced path from `pixel` through `quads` (primary included) that `accept`s.
pub fn find_path(
    scene: &ToyScene,
    pixel: &Pixel,
    quads: &[usize],
    accept: impl Fn(&PathSample) -> bool,
) -> PathSample {
    let mut rng = SplitMix64::new(11);
    for _ in 0..2_000_000 {
        if let Some(p) = trace(scene, pixel, random_numbers(&mut rng)) {
            let route: Vec<usize> = p.vertices[..=p.bounces].iter().map(|v| v.quad).collect();
            if route == quads && accept(&p) {
                return p;
            }
        }
    }
    panic!("no path along {quads:?} in 2M tries");
}
