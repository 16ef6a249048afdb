//! `light_sampler=auto`'s probe (docs/src/light-samplers.md, "Choosing"): at load, from the
//! scene alone, how much a sampler that knows where the lights are (the light BVH) would
//! gain over the power table. It replaces a fixed rule on how far the lights spread. Plain
//! data in, a number out: `effects.rs` hands it the scene's lights and surfaces.
//!
//! The lights are binned into a grid of at most 32 cells per axis over their box, each cell
//! with its power and power-weighted centre. At a few hundred surface points, drawn by area
//! with a fixed seed, a cell j contributes about c_j = Φ_j · max(0, n·ω_j) / max(d_j², h²),
//! where h is a cell's half-diagonal: power over squared distance, toward the surface. The
//! power table draws a cell with probability P_j = Φ_j / Φ. One sample's second moment
//! relative to its squared mean is then Σ_j c_j² / P_j / (Σ_j c_j)². A sampler that draws
//! each cell ∝ c_j reaches 1, the least possible. That ratio is how many times fewer
//! samples the ideal would need for the power table's variance. The probe reports its
//! median over the points, because a few points facing away from every light would
//! otherwise decide.
//!
//! The grid is coarse, so the figure is a lower bound on what locality is worth within a
//! cell, and it leaves out shadows: a city's walls hide most lights from most points, which
//! only adds to what a spatial sampler saves. It counts no cost either. The threshold it is
//! compared with (`effects::LIGHT_BVH_MIN_LOCALITY`) carries the walk's cost, as measured.

use glam::Vec3;

use crate::test_hash::hash;

/// Cells along the grid's longest axis (the others in proportion, at least 1).
const GRID: usize = 32;
/// Surface points the probe looks from.
pub const PROBE_POINTS: usize = 256;
/// The probe's fixed seed: the same scene gives the same figure on every run.
pub const PROBE_SEED: u32 = 0x5EED_1157;

/// What the probe found: its points (those some light reaches), and the median gain, in
/// hundredths (an integer, so that `SceneFeatures` stays comparable). `--stats` writes it
/// as its `light_probe` block.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct LightProbe {
    pub points: usize,
    pub locality_x100: u32,
}

impl LightProbe {
    pub fn locality(&self) -> f32 {
        self.locality_x100 as f32 / 100.0
    }
}

/// One grid cell: its power and its power-weighted centre.
struct Cell {
    power: f32,
    centre: Vec3,
}

fn cells(lights: &[(Vec3, f32)]) -> (Vec<Cell>, f32) {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for &(p, _) in lights {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    let extent = (hi - lo).max(Vec3::splat(1e-3));
    let size = extent.max_element() / GRID as f32;
    let dims = (extent / size)
        .ceil()
        .max(Vec3::ONE)
        .min(Vec3::splat(GRID as f32));
    let [nx, ny, nz] = [dims.x as usize, dims.y as usize, dims.z as usize];
    let mut power = vec![0.0f64; nx * ny * nz];
    let mut weighted = vec![glam::DVec3::ZERO; nx * ny * nz];
    for &(p, phi) in lights {
        let g = ((p - lo) / extent * dims).floor();
        let at = |v: f32, n: usize| (v.max(0.0) as usize).min(n - 1);
        let i = at(g.x, nx) + nx * (at(g.y, ny) + ny * at(g.z, nz));
        power[i] += phi as f64;
        weighted[i] += p.as_dvec3() * phi as f64;
    }
    let cells = power
        .iter()
        .zip(&weighted)
        .filter(|(p, _)| **p > 0.0)
        .map(|(&p, &w)| Cell {
            power: p as f32,
            centre: (w / p).as_vec3(),
        })
        .collect();
    let cell = extent / dims;
    (cells, 0.5 * cell.length())
}

/// `PROBE_POINTS` points on the `surfaces` (triangle `i` or `None` for one that is not a
/// surface to probe, such as an emitter), drawn by area, with their normals.
fn surface_points(
    surfaces: usize,
    surface: &impl Fn(usize) -> Option<[Vec3; 3]>,
    seed: u32,
) -> Vec<(Vec3, Vec3)> {
    let area =
        |t: usize| surface(t).map_or(0.0, |[a, b, c]| 0.5 * (b - a).cross(c - a).length() as f64);
    let mut cumulative = Vec::with_capacity(surfaces);
    let mut total = 0.0f64;
    for t in 0..surfaces {
        let a = area(t);
        if a.is_finite() {
            total += a;
        }
        cumulative.push(total);
    }
    if total <= 0.0 {
        return Vec::new();
    }
    (0..PROBE_POINTS as u32)
        .filter_map(|k| {
            let target = hash(k, seed) as f64 * total;
            let t = cumulative
                .partition_point(|&c| c <= target)
                .min(cumulative.len() - 1);
            let [a, b, c] = surface(t)?;
            let (mut u, mut v) = (hash(k, seed ^ 1), hash(k, seed ^ 2));
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let n = (b - a).cross(c - a).try_normalize()?;
            Some((a + (b - a) * u + (c - a) * v, n))
        })
        .collect()
}

/// The probe of `lights` (position, power) seen from points on the `surfaces` (see
/// `surface_points`); `None` without lights or surfaces.
pub fn probe(
    lights: &[(Vec3, f32)],
    surfaces: usize,
    surface: impl Fn(usize) -> Option<[Vec3; 3]>,
    seed: u32,
) -> Option<LightProbe> {
    let lights: Vec<(Vec3, f32)> = lights
        .iter()
        .copied()
        .filter(|(p, phi)| p.is_finite() && *phi > 0.0 && phi.is_finite())
        .collect();
    if lights.is_empty() {
        return None;
    }
    let (cells, half_diagonal) = cells(&lights);
    let total: f64 = cells.iter().map(|c| c.power as f64).sum();
    let floor = (half_diagonal * half_diagonal).max(1e-8);
    let mut ratios: Vec<f64> = surface_points(surfaces, &surface, seed)
        .into_iter()
        .filter_map(|(p, n)| {
            let (mut sum, mut second) = (0.0f64, 0.0f64);
            for cell in &cells {
                let d = cell.centre - p;
                let d2 = d.length_squared();
                // Either side of the surface: a probe point cannot tell which one is seen.
                let cos = (n.dot(d) / d2.sqrt().max(1e-6)).abs();
                let c = cell.power as f64 * cos as f64 / d2.max(floor) as f64;
                let share = cell.power as f64 / total;
                sum += c;
                second += c * c / share;
            }
            (sum > 0.0).then(|| second / (sum * sum))
        })
        .collect();
    if ratios.is_empty() {
        return None;
    }
    ratios.sort_by(|a, b| a.total_cmp(b));
    let median = ratios[ratios.len() / 2];
    Some(LightProbe {
        points: ratios.len(),
        locality_x100: (median * 100.0).round().min(u32::MAX as f64) as u32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A floor of 64 × 64 m under `lights`.
    fn floor(t: usize) -> Option<[Vec3; 3]> {
        let s = 32.0;
        [
            [
                Vec3::new(-s, 0.0, -s),
                Vec3::new(s, 0.0, -s),
                Vec3::new(s, 0.0, s),
            ],
            [
                Vec3::new(-s, 0.0, -s),
                Vec3::new(s, 0.0, s),
                Vec3::new(-s, 0.0, s),
            ],
        ]
        .get(t)
        .copied()
    }

    /// Lights 2 m over the floor, `n` × `n` of them over `span` metres.
    fn grid_of_lights(n: usize, span: f32) -> Vec<(Vec3, f32)> {
        (0..n * n)
            .map(|i| {
                let (x, z) = ((i % n) as f32, (i / n) as f32);
                let at = |k: f32| (k + 0.5) / n as f32 * span - span / 2.0;
                (Vec3::new(at(x), 2.0, at(z)), 1.0)
            })
            .collect()
    }

    #[test]
    fn the_same_scene_gives_the_same_figure() {
        let lights = grid_of_lights(32, 60.0);
        let a = probe(&lights, 2, floor, PROBE_SEED).unwrap();
        let b = probe(&lights, 2, floor, PROBE_SEED).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.points, PROBE_POINTS);
        assert_ne!(
            probe(&lights, 2, floor, PROBE_SEED + 1),
            Some(a),
            "the seed moves it"
        );
    }

    /// One light: nothing to gain over the table (1 exactly, in hundredths).
    #[test]
    fn one_light_gains_nothing() {
        let lights = [(Vec3::new(0.0, 2.0, 0.0), 5.0)];
        assert_eq!(
            probe(&lights, 2, floor, PROBE_SEED).unwrap().locality_x100,
            100
        );
        assert_eq!(probe(&[], 2, floor, PROBE_SEED), None);
        assert_eq!(probe(&lights, 0, floor, PROBE_SEED), None);
    }

    /// The same lights spread over the whole floor gain more from locality than packed
    /// into its middle, where every point sees them all from about as far.
    #[test]
    fn spread_lights_gain_more_than_packed_ones() {
        let spread = probe(&grid_of_lights(32, 60.0), 2, floor, PROBE_SEED).unwrap();
        let packed = probe(&grid_of_lights(32, 2.0), 2, floor, PROBE_SEED).unwrap();
        assert!(
            spread.locality() > 4.0 * packed.locality(),
            "spread {spread:?}, packed {packed:?}"
        );
    }
}
