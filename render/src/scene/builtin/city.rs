//! `city:N` and `city-roofs:N`: a night city 572 m across where locality matters — streets
//! between blocks of buildings that occlude, and N emissive triangles among street lamps,
//! lit windows and signs, so each pixel is lit by a few nearby lights among many (the case
//! world-space light structures exist for). `city:N` looks down a street from 1.7 m,
//! `city-roofs:N` over the roofs from 150 m. Deterministic; total emitted power is the same
//! for every N, so images compare across N.

use glam::{Quat, Vec3};

use super::many_lights::luminance;
use super::rng::SplitMix64;
use super::shapes::SceneBuilder;
use crate::scene::{Camera, Material, Scene};

/// Blocks per side, their side and the street between them (metres).
const BLOCKS: usize = 11;
const BLOCK: f32 = 40.0;
const STREET: f32 = 12.0;
const PITCH: f32 = BLOCK + STREET;
/// The city's half extent: 11 blocks and 12 streets, 572 m.
pub(super) const HALF: f32 = (BLOCKS as f32 * PITCH + STREET) / 2.0;
/// Σ area × luminance(radiance) over all lights, whatever N is.
const TOTAL_POWER: f32 = 2.0e5;
/// The shares of the lights: street lamps, lit windows, the rest signs.
const LAMP_SHARE: f32 = 0.25;
const WINDOW_SHARE: f32 = 0.65;
/// Warm and cool window colours and the signs' saturated ones.
const WINDOW_COLOURS: [Vec3; 3] = [
    Vec3::new(1.0, 0.78, 0.5),
    Vec3::new(1.0, 0.9, 0.75),
    Vec3::new(0.75, 0.85, 1.0),
];
const SIGN_COLOURS: [Vec3; 4] = [
    Vec3::new(1.0, 0.1, 0.15),
    Vec3::new(0.15, 0.35, 1.0),
    Vec3::new(0.1, 1.0, 0.3),
    Vec3::new(1.0, 0.15, 0.9),
];

/// Where the camera stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum View {
    Street,
    Roofs,
}

/// The west edge of block `i` (0..BLOCKS) along an axis.
fn block_start(i: usize) -> f32 {
    -HALF + STREET + i as f32 * PITCH
}

/// The centre line of street `i` (0..=BLOCKS) along an axis.
fn street_centre(i: usize) -> f32 {
    -HALF + STREET / 2.0 + i as f32 * PITCH
}

/// A building: its footprint centre, half size and height.
struct Building {
    centre: Vec3,
    half: Vec3,
}

/// `n` (≥ 1, checked by the caller) emissive triangles over the city.
pub(super) fn city(name: &str, n: usize, view: View) -> Scene {
    let rects = n.div_ceil(2);
    let buildings = BLOCKS * BLOCKS;
    let mut b = SceneBuilder::with_capacity(
        name,
        4 * (rects + 1) + 24 * buildings,
        2 * rects + 2 + 12 * buildings,
    );
    let ground = b.material(Material::diffuse("asphalt", Vec3::splat(0.12)));
    let facades: Vec<u32> = [0.45, 0.35, 0.55, 0.4]
        .iter()
        .enumerate()
        .map(|(i, &g)| {
            b.material(Material::diffuse(
                &format!("facade {i}"),
                Vec3::new(g, g * 0.95, g * 0.9),
            ))
        })
        .collect();
    // y up: u × v = +y for the ground.
    b.rect(Vec3::ZERO, Vec3::Z * HALF, Vec3::X * HALF, ground);

    let mut rng = SplitMix64::new(0xC17_7_0F_11_6475);
    let mut blocks = Vec::with_capacity(buildings);
    for i in 0..BLOCKS {
        for j in 0..BLOCKS {
            let height = rng.range(10.0, 60.0);
            let inset = rng.range(1.0, 4.0);
            let half = Vec3::new(BLOCK / 2.0 - inset, height / 2.0, BLOCK / 2.0 - inset);
            let centre = Vec3::new(
                block_start(i) + BLOCK / 2.0,
                height / 2.0,
                block_start(j) + BLOCK / 2.0,
            );
            let facade = facades[(rng.next_u64() % facades.len() as u64) as usize];
            b.solid_box(centre, half, Quat::IDENTITY, facade);
            blocks.push(Building { centre, half });
        }
    }

    // Each kind gets its share of the power; within a kind every light the same power.
    let lamps = ((rects as f32 * LAMP_SHARE) as usize).max(1).min(rects);
    let windows = ((rects as f32 * WINDOW_SHARE) as usize).min(rects - lamps);
    let signs = rects - lamps - windows;
    let kinds = [(lamps, 0.45f32), (windows, 0.35), (signs, 0.2)];
    let power_of = |kind: usize| {
        let (count, share) = kinds[kind];
        let total_share: f32 = kinds.iter().filter(|k| k.0 > 0).map(|k| k.1).sum();
        TOTAL_POWER * share / total_share / count.max(1) as f32
    };
    let emitter = |b: &mut SceneBuilder, label: &str, colour: Vec3, area: f32, power: f32| {
        b.material(Material::emitter(
            label,
            colour * (power / (area * luminance(colour))),
            false,
        ))
    };

    // Street lamps: 0.6 m squares 8 m up, facing down, along both kerbs of every street.
    let lamp_half = 0.3;
    let lamp = emitter(
        &mut b,
        "street lamp",
        Vec3::new(1.0, 0.85, 0.6),
        4.0 * lamp_half * lamp_half,
        power_of(0),
    );
    for _ in 0..lamps {
        let street = street_centre((rng.next_u64() % (BLOCKS as u64 + 1)) as usize);
        let kerb = if rng.next_f32() < 0.5 { -1.0 } else { 1.0 } * (STREET / 2.0 - 1.0);
        let along = rng.range(-HALF + 1.0, HALF - 1.0);
        let centre = if rng.next_f32() < 0.5 {
            Vec3::new(street + kerb, 8.0, along)
        } else {
            Vec3::new(along, 8.0, street + kerb)
        };
        // x × z = -y: facing down.
        b.rect(centre, Vec3::X * lamp_half, Vec3::Z * lamp_half, lamp);
    }

    // Lit windows (1.2 × 1.6 m) and signs (3 × 1 m, low on the facade), 0.05 m proud of a
    // facade and facing out of it.
    let window_colours: Vec<u32> = WINDOW_COLOURS
        .iter()
        .map(|&c| emitter(&mut b, "window", c, 1.2 * 1.6, power_of(1)))
        .collect();
    let sign_colours: Vec<u32> = SIGN_COLOURS
        .iter()
        .map(|&c| emitter(&mut b, "sign", c, 3.0, power_of(2)))
        .collect();
    for k in 0..windows + signs {
        let sign = k >= windows;
        let building = &blocks[(rng.next_u64() % blocks.len() as u64) as usize];
        let (w, h) = if sign { (1.5, 0.5) } else { (0.6, 0.8) };
        let height = if sign {
            rng.range(3.0, 6.0)
        } else {
            rng.range(2.0, (2.0 * building.half.y - 2.0).max(2.5))
        };
        // One of the four walls: its outward normal and the axis along it.
        let (normal, along) = match rng.next_u64() % 4 {
            0 => (Vec3::X, Vec3::Z),
            1 => (Vec3::NEG_X, Vec3::Z),
            2 => (Vec3::Z, Vec3::X),
            _ => (Vec3::NEG_Z, Vec3::X),
        };
        let reach = building.half.dot(along.abs()) - w - 0.5;
        let offset = building.half.dot(normal.abs()) + 0.05;
        let centre = Vec3::new(building.centre.x, height, building.centre.z)
            + normal * offset
            + along * rng.range(-reach, reach);
        // u × v = normal: u along the wall, v up or down so that the front faces out.
        let (u, v) = if along.cross(Vec3::Y).dot(normal) > 0.0 {
            (along * w, Vec3::Y * h)
        } else {
            (Vec3::Y * h, along * w)
        };
        let palette = if sign { &sign_colours } else { &window_colours };
        let material = palette[(rng.next_u64() % palette.len() as u64) as usize];
        b.rect(centre, u, v, material);
    }
    let mut scene = b.finish(Some(camera(view)));
    // An odd N: the last light is one triangle of its quad.
    if n % 2 == 1 {
        scene.triangles.pop();
    }
    scene
}

fn camera(view: View) -> Camera {
    let street = street_centre(BLOCKS / 2);
    match view {
        View::Street => Camera::look_at(
            Vec3::new(street, 1.7, HALF - 20.0),
            Vec3::new(street, 6.0, 0.0),
            60f32.to_radians(),
        ),
        View::Roofs => Camera::look_at(
            Vec3::new(-HALF * 0.6, 150.0, HALF * 0.6),
            Vec3::new(0.0, 0.0, 0.0),
            55f32.to_radians(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn emissive_triangles(s: &Scene) -> usize {
        s.triangles
            .iter()
            .filter(|t| s.materials[t.material as usize].is_emissive())
            .count()
    }

    /// N emissive triangles exactly, deterministic, 572 m across, every light outside every
    /// building and above the ground; odd N too.
    #[test]
    fn a_city_has_its_lights_in_the_open() {
        for n in [1usize, 2, 3, 1000, 4097] {
            let s = city("city", n, View::Street);
            assert_eq!(emissive_triangles(&s), n, "N = {n}");
        }
        let a = city("city", 2048, View::Street);
        let b = city("city", 2048, View::Street);
        assert_eq!(a.triangles.len(), b.triangles.len());
        assert!(
            a.vertices
                .iter()
                .zip(&b.vertices)
                .all(|(x, y)| x.position == y.position)
        );
        let bounds = a.bounds();
        assert!(bounds.max.x - bounds.min.x >= 500.0 && bounds.max.z - bounds.min.z >= 500.0);
        for t in &a.triangles {
            if !a.materials[t.material as usize].is_emissive() {
                continue;
            }
            let p = t.indices.map(|i| a.vertices[i as usize].position);
            let c = (p[0] + p[1] + p[2]) / 3.0;
            assert!(c.is_finite() && c.y > 0.5, "{c}");
            // Inside no building (0.01 m of slack for the lights 0.05 m off a facade).
            let inside = (0..BLOCKS * BLOCKS).any(|k| {
                let (i, j) = (k / BLOCKS, k % BLOCKS);
                let (x0, z0) = (block_start(i), block_start(j));
                c.x > x0 + 4.01
                    && c.x < x0 + BLOCK - 4.01
                    && c.z > z0 + 4.01
                    && c.z < z0 + BLOCK - 4.01
                    && c.y < 9.9
            });
            assert!(!inside, "a light inside a building at {c}");
        }
    }
}
