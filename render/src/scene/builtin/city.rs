//! `city:N` and `city-roofs:N`: a night city 572 m across where locality matters — streets
//! between blocks of buildings that occlude, and N emissive triangles among street lamps,
//! lit windows and signs, so each pixel is lit by a few nearby lights among many (the case
//! world-space light structures exist for). `city:N` looks down a street from 1.7 m,
//! `city-roofs:N` over the roofs from 150 m. Deterministic; total emitted power is the same
//! for every N, so images compare across N.

use glam::{Quat, Vec3};

use super::dynamic::{Motion, linear_vec3};
use super::many_lights::luminance;
use super::rng::SplitMix64;
use super::shapes::SceneBuilder;
use crate::scene::animation::{Target, Trs};
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
    let (b, _) = city_builder(name, n.div_ceil(2));
    let mut scene = b.finish(Some(camera(view)));
    // An odd N: the last light is one triangle of its quad.
    if n % 2 == 1 {
        scene.triangles.pop();
    }
    scene
}

/// The share of `city-traffic:N`'s lights on cars, and of its power.
const CAR_SHARE: f32 = 0.1;
const CAR_POWER_SHARE: f32 = 0.05;
/// Cars drive there and back along their street: this far, in this many seconds.
const CAR_TRAVEL: f32 = PITCH;
pub const CAR_PERIOD: f32 = 8.0;
/// Two of the four sign colours blink: on for a second, off for a second.
pub const SIGN_BLINK: f32 = 1.0;

/// `city:N` with traffic: a tenth of the N lights are headlights on cars that drive along
/// the streets (one convoy per lane, each a node of the animation), and two of the four
/// sign colours blink. For the light structures' refit and lag (docs/src/light-samplers.md).
pub(super) fn city_traffic(name: &str, n: usize) -> Scene {
    let car_rects = (n as f32 * CAR_SHARE / 2.0) as usize;
    let (mut b, signs) = city_builder(name, n.div_ceil(2) - car_rects);
    let mut motion = Motion::default();
    if car_rects > 0 {
        let colour = Vec3::new(1.0, 0.95, 0.85);
        let (w, h) = (0.25f32, 0.15f32);
        let power = TOTAL_POWER * CAR_POWER_SHARE / car_rects as f32;
        let headlight = b.material(Material::emitter(
            "headlight",
            colour * (power / (4.0 * w * h * luminance(colour))),
            false,
        ));
        // Two lanes per street along z, one each way; cars spread evenly over all lanes.
        let lanes = 2 * (BLOCKS + 1);
        for lane in 0..lanes {
            let count = car_rects / lanes + usize::from(lane < car_rects % lanes);
            if count == 0 {
                continue;
            }
            let (street, forward) = (lane / 2, lane % 2 == 0);
            let dir = if forward { Vec3::Z } else { Vec3::NEG_Z };
            let x = street_centre(street) + if forward { 2.5 } else { -2.5 };
            let node = motion.node(None, Trs::default());
            let first = b.vertex_count();
            let spacing = (2.0 * HALF - CAR_TRAVEL) / count as f32;
            for c in 0..count {
                let z = -HALF + (c as f32 + 0.5) * spacing;
                // u × v = dir: facing along the lane.
                let u = dir.cross(Vec3::Y) * w;
                b.rect(Vec3::new(x, 0.7, z), u, Vec3::Y * h, headlight);
            }
            motion.attach(&b, node, first);
            let there = dir * CAR_TRAVEL;
            motion.channel(
                Target::Translation(node),
                linear_vec3(
                    &[0.0, CAR_PERIOD / 2.0, CAR_PERIOD],
                    &[Vec3::ZERO, there, Vec3::ZERO],
                ),
            );
        }
    }
    let scene = b.finish(Some(camera(View::Street)));
    // Keys over the cars' whole period, so the clip loops with both in step.
    let keys = (CAR_PERIOD / SIGN_BLINK) as usize;
    for &m in signs.iter().step_by(2) {
        motion.blink(
            &scene,
            m as usize,
            (0..=keys).map(|k| k as f32 * SIGN_BLINK).collect(),
            (0..=keys)
                .map(|k| if k % 2 == 0 { 1.0 } else { 0.0 })
                .collect(),
        );
    }
    let mut scene = motion.finish(scene, "traffic");
    if n % 2 == 1 {
        scene.triangles.pop();
    }
    scene
}

/// The city with `rects` light quads (lamps, windows, signs), unfinished, and the sign
/// materials.
fn city_builder(name: &str, rects: usize) -> (SceneBuilder, Vec<u32>) {
    let rects = rects.max(1);
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

    // Every light has a slot of its own: emitters that overlap in one plane are ill-defined
    // (a ray meets one of them, a shadow ray to either passes), and at a million lights
    // randomly placed ones would overlap by the thousand. Where a kind has more lights than
    // slots at its full size, its slots (and lights) shrink until they all fit.
    let lamp_slots = street_slots(lamps);
    let lamp_half = 0.3 * lamp_slots.scale;
    let lamp = emitter(
        &mut b,
        "street lamp",
        Vec3::new(1.0, 0.85, 0.6),
        4.0 * lamp_half * lamp_half,
        power_of(0),
    );
    for slot in pick(&mut rng, lamp_slots.centres.len(), lamps) {
        // x × z = -y: facing down, 8 m over the street.
        b.rect(
            lamp_slots.centres[slot],
            Vec3::X * lamp_half,
            Vec3::Z * lamp_half,
            lamp,
        );
    }

    // Lit windows (1.2 × 1.6 m, from 7 m up) and signs (3 × 1 m, between 2.5 and 6.5 m),
    // 0.05 m proud of a facade and facing out of it.
    let window_slots = facade_slots(&blocks, 7.0, 1.0, (1.6, 2.2), windows);
    let sign_slots = facade_slots(&blocks, 2.5, -6.5, (3.5, 1.3), signs);
    let (ww, wh) = (0.6 * window_slots.scale, 0.8 * window_slots.scale);
    let (sw, sh) = (1.5 * sign_slots.scale, 0.5 * sign_slots.scale);
    let window_colours: Vec<u32> = WINDOW_COLOURS
        .iter()
        .map(|&c| emitter(&mut b, "window", c, 4.0 * ww * wh, power_of(1)))
        .collect();
    let sign_colours: Vec<u32> = SIGN_COLOURS
        .iter()
        .map(|&c| emitter(&mut b, "sign", c, 4.0 * sw * sh, power_of(2)))
        .collect();
    let chosen_windows = pick(&mut rng, window_slots.centres.len(), windows);
    let chosen_signs = pick(&mut rng, sign_slots.centres.len(), signs);
    let placed = chosen_windows
        .into_iter()
        .map(|k| (false, k))
        .chain(chosen_signs.into_iter().map(|k| (true, k)));
    for (sign, k) in placed {
        let (slots, (w, h), palette) = if sign {
            (&sign_slots, (sw, sh), &sign_colours)
        } else {
            (&window_slots, (ww, wh), &window_colours)
        };
        let (centre, normal) = (slots.centres[k], slots.normals[k]);
        let along = Vec3::Y.cross(normal);
        // u × v = normal: u along the wall, v up or down so that the front faces out.
        let (u, v) = if along.cross(Vec3::Y).dot(normal) > 0.0 {
            (along * w, Vec3::Y * h)
        } else {
            (Vec3::Y * h, along * w)
        };
        let material = palette[(rng.next_u64() % palette.len() as u64) as usize];
        b.rect(centre, u, v, material);
    }
    (b, sign_colours)
}

/// Light slots: their centres (and for facades their outward normals), and how much the
/// lights in them are scaled down from their full size to fit.
struct Slots {
    centres: Vec<Vec3>,
    normals: Vec<Vec3>,
    scale: f32,
}

/// The largest scale ≤ 1, in steps of 0.9×, at which `slots(scale)` holds `count`.
fn fitting(count: usize, slots: impl Fn(f32) -> Slots) -> Slots {
    let mut scale = 1.0f32;
    loop {
        let s = slots(scale);
        if s.centres.len() >= count || scale < 1e-3 {
            return s;
        }
        scale *= 0.9;
    }
}

/// A grid over the streets 8 m up, pitch 4 m at full size (intersections once).
fn street_slots(count: usize) -> Slots {
    fitting(count, |scale| {
        let pitch = 4.0 * scale;
        let mut centres = Vec::new();
        let across = (STREET / pitch).floor().max(1.0) as usize;
        let length = ((2.0 * HALF) / pitch).floor() as usize;
        for street in 0..=BLOCKS {
            let x0 = street_centre(street) - STREET / 2.0;
            for a in 0..across {
                let x = x0 + (a as f32 + 0.5) * STREET / across as f32;
                for l in 0..length {
                    let z = -HALF + (l as f32 + 0.5) * pitch;
                    // Streets along z own the intersections; along x, skip them.
                    centres.push(Vec3::new(x, 8.0, z));
                    let in_street =
                        (0..=BLOCKS).any(|s| (z - street_centre(s)).abs() < STREET / 2.0);
                    if !in_street {
                        centres.push(Vec3::new(z, 8.0, x));
                    }
                }
            }
        }
        let normals = vec![Vec3::NEG_Y; centres.len()];
        Slots {
            centres,
            normals,
            scale,
        }
    })
}

/// A grid on every building's four walls between `low` m and `top` (a height above the
/// ground if negative, else metres below the roof), cells `cell` (along, up) at full size.
fn facade_slots(blocks: &[Building], low: f32, top: f32, cell: (f32, f32), count: usize) -> Slots {
    fitting(count, |scale| {
        let (pw, ph) = (cell.0 * scale, cell.1 * scale);
        let (mut centres, mut normals) = (Vec::new(), Vec::new());
        for building in blocks {
            let high = if top < 0.0 {
                -top
            } else {
                2.0 * building.half.y - top
            };
            let rows = ((high - low) / ph).floor().max(0.0) as usize;
            for normal in [Vec3::X, Vec3::NEG_X, Vec3::Z, Vec3::NEG_Z] {
                let along = Vec3::Y.cross(normal);
                let width = 2.0 * building.half.dot(along.abs()) - 1.0;
                let cols = (width / pw).floor().max(0.0) as usize;
                let offset = building.half.dot(normal.abs()) + 0.05;
                for c in 0..cols {
                    for r in 0..rows {
                        let a = -width / 2.0 + (c as f32 + 0.5) * pw;
                        let y = low + (r as f32 + 0.5) * ph;
                        let base = Vec3::new(building.centre.x, y, building.centre.z);
                        centres.push(base + normal * offset + along * a);
                        normals.push(normal);
                    }
                }
            }
        }
        Slots {
            centres,
            normals,
            scale,
        }
    })
}

/// `count` distinct indices of `0..slots` in random order (a partial Fisher–Yates shuffle).
fn pick(rng: &mut SplitMix64, slots: usize, count: usize) -> Vec<usize> {
    let mut all: Vec<usize> = (0..slots).collect();
    let count = count.min(slots);
    for i in 0..count {
        let j = i + (rng.next_u64() % (slots - i) as u64) as usize;
        all.swap(i, j);
    }
    all.truncate(count);
    all
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

    /// No two lights overlap, at any N: every light has a slot of its own (overlapping
    /// emitters in one plane are ill-defined: a ray meets one, a shadow ray passes both).
    #[test]
    fn no_two_lights_overlap() {
        for n in [4096usize, 60_000] {
            let s = city("city", n, View::Street);
            // Each quad's centre (its two triangles share the diagonal's midpoint).
            let mut centres: Vec<(Vec3, f32)> = s
                .triangles
                .chunks(2)
                .filter(|t| t.len() == 2 && s.materials[t[0].material as usize].is_emissive())
                .map(|t| {
                    let p = t[0].indices.map(|i| s.vertices[i as usize].position);
                    let size = (p[1] - p[0]).length().min((p[2] - p[1]).length());
                    ((p[0] + p[2]) / 2.0, size)
                })
                .collect();
            centres.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
            for (i, &(a, size)) in centres.iter().enumerate() {
                for &(b, other) in centres[i + 1..].iter().take_while(|(b, _)| b.x - a.x < 4.0) {
                    let gap = (a - b).abs();
                    // Two quads in one plane overlap when their centres are closer than a side
                    // along the plane; 0.9 of the smaller side leaves rounding room.
                    let same_plane = gap.min_element() < 1e-3;
                    assert!(
                        !same_plane || gap.max_element() >= 0.9 * size.min(other),
                        "N = {n}: lights at {a} and {b} overlap"
                    );
                }
            }
        }
    }

    /// `city-traffic:N` has N lights at t = 0, a tenth on cars that move, and blinking
    /// signs that switch some lights off and on again.
    #[test]
    fn traffic_moves_cars_and_blinks_signs() {
        use crate::scene::animation::ClipChoice;
        for n in [1usize, 4096, 4097] {
            let s = city_traffic("city-traffic", n);
            assert_eq!(emissive_triangles(&s), n, "N = {n}");
        }
        let mut s = city_traffic("city-traffic", 4096);
        let anim = s.animation.clone().unwrap();
        let lit = emissive_triangles(&s);
        let before: Vec<Vec3> = s.vertices.iter().map(|v| v.position).collect();
        anim.pose(&mut s, 1.5, ClipChoice::All);
        let moved = s
            .vertices
            .iter()
            .zip(&before)
            .filter(|(v, b)| v.position.distance(**b) > 1.0)
            .count();
        // 4 vertices per car quad, 409 car lights in 204 quads.
        assert_eq!(moved, 4 * 204, "the cars drive");
        assert!(
            emissive_triangles(&s) < lit,
            "half the signs are off at 1.5 s"
        );
        anim.pose(&mut s, CAR_PERIOD, ClipChoice::All);
        assert_eq!(emissive_triangles(&s), lit, "and on again");
    }
}
