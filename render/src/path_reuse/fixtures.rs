//! What the path-reuse tests share: the toy scene's camera and pixels, and a search for
//! a path that takes a given route.

use glam::{Vec2, Vec3};

use super::path::{MAX_BOUNCES, PathSample, Pixel, trace};
use super::toy_scene::{FLOOR, Hit, ToyScene};
use crate::reservoir::test_support::Rng;

/// The camera: its view reflects off the floor toward the mirror, so glossy chains
/// (floor → mirror → emitter) carry light.
pub const CAMERA: Vec3 = Vec3::new(-3.0, -2.0, 2.5);

/// The floor pixel at `xy`.
pub fn pixel(xy: [f32; 2]) -> Pixel {
    let position = Vec2::from(xy).extend(0.0);
    Pixel {
        primary: Hit {
            position,
            normal: Vec3::Z,
            quad: FLOOR,
        },
        to_camera: (CAMERA - position).normalize(),
    }
}

/// Rough enough a mirror that finite differences of its lobe stay smooth.
pub fn scene_for_fd() -> ToyScene {
    ToyScene::new(0.35, 0.1)
}

pub fn random_numbers(rng: &mut Rng) -> [[f32; 2]; MAX_BOUNCES] {
    std::array::from_fn(|_| [rng.f32(), rng.f32()])
}

/// The first traced path from `pixel` through `quads` (primary included) that `accept`s.
pub fn find_path(
    scene: &ToyScene,
    pixel: &Pixel,
    quads: &[usize],
    accept: impl Fn(&PathSample) -> bool,
) -> PathSample {
    let mut rng = Rng::new(11);
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
