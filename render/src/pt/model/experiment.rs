//! The toy-scene experiments of path reuse: initial reservoirs, references by path tracing,
//! and independent trials of one pairwise spatial step, with how the neighbours' shifts
//! ended. The tests assert on them (`unbiased_tests.rs`); `restir-viewer bench-shifts`
//! prints them.

use glam::{Vec2, Vec3};

use super::pairwise::{Candidate, Planted, pairwise_path_reuse};
use super::path::{MAX_BOUNCES, PathSample, Pixel, evaluate, trace};
use super::shift::{Failure, Shift, shift_path};
use super::toy_scene::{FLOOR, Hit, ToyScene};
use crate::reservoir::Reservoir;
use crate::scene::builtin::rng::SplitMix64;

/// The camera: its view reflects off the floor toward the mirror, so glossy chains
/// (floor → mirror → emitter) carry light.
pub const CAMERA: Vec3 = Vec3::new(-3.0, -2.0, 2.5);

/// BSDF-sampled candidates per initial reservoir.
pub const CANDIDATES: usize = 4;

/// The hybrid shift's thresholds in the experiments (the floor's roughness is 0.2–0.6,
/// the mirror's 0.03, the wall's 1).
pub const HYBRID: Shift = Shift::Hybrid {
    rough_threshold: 0.2,
    min_distance: 0.1,
};

/// The toy scene with a near mirror (roughness 0.03).
pub fn glossy_scene() -> ToyScene {
    ToyScene::new(0.35, 0.03)
}

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

/// A canonical pixel and its neighbours' offsets.
#[derive(Clone, Copy, Debug)]
pub struct Place {
    pub name: &'static str,
    pub at: [f32; 2],
    pub offsets: &'static [[f32; 2]; 4],
}

/// Neighbours 0.2–0.3 away all round, so the floor's roughness and view angle differ.
pub const ALL_ROUND: [[f32; 2]; 4] = [[0.25, 0.1], [-0.2, 0.2], [0.15, -0.25], [-0.25, -0.1]];
/// Neighbours 0.6–0.8 to one side (−y): farther from the back wall, where reconnections to
/// the wall carry Jacobians of 2–5 one way, and on smoother floor, where replayed bounces
/// meet narrower lobes. A symmetric set partly cancels either.
pub const ONE_SIDED: [[f32; 2]; 4] = [[0.0, -0.6], [0.3, -0.6], [-0.3, -0.6], [0.15, -0.8]];

/// Where glossy chains by the mirror carry much of the light.
pub const BY_THE_MIRROR: [f32; 2] = [0.2, -0.6];
/// 0.5 from the back wall: neighbours' reconnection distances differ by tens of percent.
pub const BY_THE_WALL: [f32; 2] = [0.2, 1.1];

pub const PLACES: [Place; 4] = [
    Place {
        name: "by the mirror, all round",
        at: BY_THE_MIRROR,
        offsets: &ALL_ROUND,
    },
    Place {
        name: "by the mirror, one side",
        at: BY_THE_MIRROR,
        offsets: &ONE_SIDED,
    },
    Place {
        name: "by the wall, all round",
        at: BY_THE_WALL,
        offsets: &ALL_ROUND,
    },
    Place {
        name: "by the wall, one side",
        at: BY_THE_WALL,
        offsets: &ONE_SIDED,
    },
];

pub fn random_numbers(rng: &mut SplitMix64) -> [[f32; 2]; MAX_BOUNCES] {
    std::array::from_fn(|_| [rng.next_f32(), rng.next_f32()])
}

/// An initial reservoir of `CANDIDATES` BSDF-sampled paths (RIS, target = contribution).
pub fn initial(scene: &ToyScene, pixel: &Pixel, rng: &mut SplitMix64) -> Reservoir<PathSample> {
    let mut r = Reservoir::empty();
    for _ in 0..CANDIDATES {
        if let Some(p) = trace(scene, pixel, random_numbers(rng)) {
            let e = evaluate(scene, pixel, &p);
            if e.pdf > 0.0 {
                let w = e.contribution / (e.pdf * CANDIDATES as f32);
                r.update(p, w, e.contribution, rng.next_f32());
            }
        }
    }
    r.finalize_initial();
    r
}

/// Mean and standard error of the mean.
pub fn mean_and_se(values: &[f64]) -> (f64, f64) {
    let n = values.len().max(2) as f64;
    let mean = values.iter().sum::<f64>() / n;
    let sq: f64 = values.iter().map(|v| (v - mean).powi(2)).sum();
    (mean, (sq / (n - 1.0) / n).sqrt())
}

/// The pixel's indirect light (paths of two or more bounces) by path tracing `samples`
/// paths: mean and standard error.
pub fn reference(scene: &ToyScene, pixel: &Pixel, samples: usize) -> (f64, f64) {
    let mut rng = SplitMix64::new(99);
    let values: Vec<f64> = (0..samples)
        .map(|_| {
            trace(scene, pixel, random_numbers(&mut rng)).map_or(0.0, |p| {
                let e = evaluate(scene, pixel, &p);
                e.contribution as f64 / e.pdf as f64
            })
        })
        .collect();
    mean_and_se(&values)
}

/// How the neighbours' paths fared when shifted to the canonical pixel.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outcomes {
    pub moved: u64,
    /// Of the moved ones, those that carry under 1 % of their target here that they did
    /// where found (p̂_here(T(y))·|J| < p̂_there(y) / 100): moved, but of no use (the
    /// reconnection of a glossy chain, which evaluates the mirror at a new angle).
    pub moved_useless: u64,
    pub replay_left: u64,
    pub undefined: u64,
    pub occluded: u64,
    pub elsewhere: u64,
    /// Σ |log2 |J|| over the moved ones.
    pub abs_log2_jacobian: f64,
}

impl Outcomes {
    pub fn total(&self) -> u64 {
        self.moved + self.replay_left + self.undefined + self.occluded + self.elsewhere
    }

    /// One shift's result: `Ok((|J|, carried))`, `carried` = p̂_here(T(y))·|J| / p̂_there(y).
    fn count(&mut self, result: Result<(f32, f32), Failure>) {
        match result {
            Ok((j, carried)) => {
                self.moved += 1;
                self.moved_useless += u64::from(carried < 0.01);
                self.abs_log2_jacobian += (j as f64).log2().abs();
            }
            Err(Failure::ReplayLeft) => self.replay_left += 1,
            Err(Failure::ReconnectionUndefined) => self.undefined += 1,
            Err(Failure::Occluded) => self.occluded += 1,
            Err(Failure::ReconnectsElsewhere) => self.elsewhere += 1,
        }
    }
}

/// What `trials` independent spatial steps at `place` gave.
#[derive(Clone, Copy, Debug)]
pub struct Trials {
    pub mean: f64,
    pub se: f64,
    pub outcomes: Outcomes,
}

/// `trials` independent pairwise spatial steps at `place` (fresh initial reservoirs at the
/// canonical pixel and its four neighbours each time): the reused estimate `p̂(y)·W`.
pub fn spatial_trials(
    scene: &ToyScene,
    place: &Place,
    shift: Shift,
    planted: Planted,
    trials: usize,
    seed: u64,
) -> Trials {
    let mut rng = SplitMix64::new(seed);
    let here = pixel(place.at);
    let around: Vec<Pixel> = place
        .offsets
        .iter()
        .map(|o| pixel([place.at[0] + o[0], place.at[1] + o[1]]))
        .collect();
    let mut outcomes = Outcomes::default();
    let values: Vec<f64> = (0..trials)
        .map(|_| {
            let canonical = Candidate {
                pixel: &here,
                reservoir: initial(scene, &here, &mut rng),
            };
            let neighbours: Vec<Candidate> = around
                .iter()
                .map(|p| Candidate {
                    pixel: p,
                    reservoir: initial(scene, p, &mut rng),
                })
                .collect();
            for n in &neighbours {
                if let Some(y) = &n.reservoir.sample {
                    let moved = shift_path(scene, y, n.pixel, &here, shift).map(|s| {
                        let t = evaluate(scene, &here, &s.path).contribution;
                        (s.jacobian, t * s.jacobian / n.reservoir.p_hat)
                    });
                    outcomes.count(moved);
                }
            }
            let mut u = || rng.next_f32();
            let r = pairwise_path_reuse(scene, &canonical, &neighbours, shift, planted, &mut u);
            (r.p_hat * r.weight) as f64
        })
        .collect();
    let (mean, se) = mean_and_se(&values);
    Trials { mean, se, outcomes }
}
