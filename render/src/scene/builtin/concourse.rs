//! `concourse`: the showcase and default scene. A station concourse at night — the kind of
//! scene ReSTIR was made for: hundreds of small lights in a few colour temperatures
//! (warm downlights over the shop fronts, cool ones over the walkway, wall sconces,
//! coloured signs), pillars and kiosks casting many-light shadows, a glossy floor that
//! mirrors them. Unlike `many-lights` (a saturated colour cloud that shadows itself, the
//! stress test), most of its noise is the noise that resampling removes: which of many
//! similar lights matters here.

use glam::{Quat, Vec3, Vec4};

use super::many_lights::luminance;
use super::rng::SplitMix64;
use super::shapes::SceneBuilder;
use crate::scene::{Camera, Material, Scene};

/// Half-size of the hall: 14 m wide, 5 m high, 32 m long.
const HALF: Vec3 = Vec3::new(7.0, 2.5, 16.0);
/// Downlights: a grid over the ceiling (columns across × rows along).
const DOWNLIGHT_COLUMNS: usize = 12;
const DOWNLIGHT_ROWS: usize = 40;
const DOWNLIGHT_SIDE: f32 = 0.22;
/// Sconces: one row per side wall, at this height.
const SCONCES_PER_WALL: usize = 32;
const SCONCE_HEIGHT: f32 = 3.2;
/// Signs above the shop fronts: a few saturated colours, each a row of short segments.
const SIGNS_PER_WALL: usize = 6;
const SEGMENTS_PER_SIGN: usize = 10;

/// Colour temperatures as linear Rec. 709 (blackbody approximations, luminance 1).
const WARM_2700K: Vec3 = Vec3::new(1.0, 0.62, 0.30);
const NEUTRAL_4000K: Vec3 = Vec3::new(1.0, 0.80, 0.60);
const COOL_6500K: Vec3 = Vec3::new(0.90, 0.96, 1.0);
const SIGN_COLOURS: [Vec3; 4] = [
    Vec3::new(1.0, 0.08, 0.10),
    Vec3::new(0.05, 0.85, 1.0),
    Vec3::new(1.0, 0.15, 0.85),
    Vec3::new(1.0, 0.75, 0.05),
];

/// Emitted power (Σ area × luminance) of each group, chosen so the walkway reads as the
/// brightest area and the signs as accents.
const DOWNLIGHT_POWER: f32 = 300.0;
const SCONCE_POWER: f32 = 40.0;
const SIGN_POWER: f32 = 12.0;

pub(super) fn concourse(name: &str) -> Scene {
    let mut b = SceneBuilder::new(name);
    let floor = b.material(Material {
        name: "polished floor".into(),
        base_color: Vec4::new(0.32, 0.32, 0.34, 1.0),
        metallic: 0.0,
        roughness: 0.22,
        specular: 1.0,
        ..Material::default()
    });
    let wall = b.material(Material::diffuse("wall", Vec3::splat(0.4)));
    let ceiling = b.material(Material::diffuse("ceiling", Vec3::splat(0.25)));
    let pillar = b.material(Material::diffuse("pillar", Vec3::new(0.5, 0.48, 0.45)));
    let kiosk = b.material(Material::diffuse("kiosk", Vec3::new(0.45, 0.3, 0.2)));
    let shopfront = b.material(Material::diffuse("shop front", Vec3::new(0.2, 0.22, 0.25)));
    // Face order: +x, -x, ceiling, floor, +z, -z.
    b.room(Vec3::Y * HALF.y, HALF, wall, ceiling, floor);
    occluders(&mut b, pillar, kiosk, shopfront);
    downlights(&mut b);
    sconces(&mut b);
    signs(&mut b);
    let camera = Camera::look_at(
        Vec3::new(-0.8, 1.7, HALF.z - 1.0),
        Vec3::new(0.6, 1.3, -6.0),
        60f32.to_radians(),
    );
    b.finish(Some(camera))
}

/// Pillars in two rows along the walkway, kiosks between them, shop fronts (low boxes)
/// along both walls: shadows from many directions at once.
fn occluders(b: &mut SceneBuilder, pillar: u32, kiosk: u32, shopfront: u32) {
    for i in 0..8 {
        let z = -HALF.z + 2.0 + i as f32 * 4.0;
        for x in [-3.5f32, 3.5] {
            b.solid_box(
                Vec3::new(x, HALF.y, z),
                Vec3::new(0.3, HALF.y, 0.3),
                Quat::IDENTITY,
                pillar,
            );
        }
    }
    let mut rng = SplitMix64::new(0xC0_4C_0E_55);
    // Between the pillar pairs, but none right in front of the camera.
    for i in 0..6 {
        let z = -HALF.z + 4.0 + i as f32 * 4.0;
        let x = rng.range(-1.2, 1.2);
        let half = Vec3::new(
            rng.range(0.4, 0.8),
            rng.range(0.5, 1.1),
            rng.range(0.4, 0.9),
        );
        let turn = Quat::from_rotation_y(rng.range(-0.6, 0.6));
        b.solid_box(Vec3::new(x, half.y, z), half, turn, kiosk);
    }
    for i in 0..SIGNS_PER_WALL {
        let z = sign_z(i);
        for side in [-1.0f32, 1.0] {
            let half = Vec3::new(0.4, 1.2, 1.6);
            let center = Vec3::new(side * (HALF.x - half.x), half.y, z);
            b.solid_box(center, half, Quat::IDENTITY, shopfront);
        }
    }
}

/// z of sign (and shop front) `i` along each wall.
fn sign_z(i: usize) -> f32 {
    -HALF.z + 3.0 + i as f32 * (2.0 * HALF.z - 6.0) / (SIGNS_PER_WALL - 1) as f32
}

/// Radiance that gives each of `count` emitters of area `area` an equal share of `power`.
fn radiance(colour: Vec3, power: f32, count: usize, area: f32) -> Vec3 {
    colour * (power / (count as f32 * area * luminance(colour)))
}

/// The ceiling grid: warm over the two shop sides, cool over the walkway, a neutral
/// row every fifth; facing down.
fn downlights(b: &mut SceneBuilder) {
    let count = DOWNLIGHT_COLUMNS * DOWNLIGHT_ROWS;
    let area = DOWNLIGHT_SIDE * DOWNLIGHT_SIDE;
    let mut material = |colour: Vec3, label: &str| {
        b.material(Material::emitter(
            label,
            radiance(colour, DOWNLIGHT_POWER, count, area),
            false,
        ))
    };
    let (warm, neutral, cool) = (
        material(WARM_2700K, "downlight 2700 K"),
        material(NEUTRAL_4000K, "downlight 4000 K"),
        material(COOL_6500K, "downlight 6500 K"),
    );
    let half = DOWNLIGHT_SIDE * 0.5;
    let y = 2.0 * HALF.y - 0.02;
    for row in 0..DOWNLIGHT_ROWS {
        let z = -HALF.z + (row as f32 + 0.5) * (2.0 * HALF.z / DOWNLIGHT_ROWS as f32);
        for column in 0..DOWNLIGHT_COLUMNS {
            let x = -HALF.x + (column as f32 + 0.5) * (2.0 * HALF.x / DOWNLIGHT_COLUMNS as f32);
            let m = if row % 5 == 2 {
                neutral
            } else if x.abs() < 3.0 {
                cool
            } else {
                warm
            };
            // x × z = -y: facing down.
            b.rect(Vec3::new(x, y, z), Vec3::X * half, Vec3::Z * half, m);
        }
    }
}

/// Small warm wall lights above the shop fronts, facing into the hall.
fn sconces(b: &mut SceneBuilder) {
    let (w, h) = (0.12, 0.3);
    let count = 2 * SCONCES_PER_WALL;
    let m = b.material(Material::emitter(
        "sconce 2700 K",
        radiance(WARM_2700K, SCONCE_POWER, count, 4.0 * w * h),
        false,
    ));
    for i in 0..SCONCES_PER_WALL {
        let z = -HALF.z + (i as f32 + 0.5) * (2.0 * HALF.z / SCONCES_PER_WALL as f32);
        let x = HALF.x - 0.03;
        // z × y = -x: faces the hall from the +x wall; -z × y = +x from the -x wall.
        b.rect(Vec3::new(x, SCONCE_HEIGHT, z), Vec3::Z * w, Vec3::Y * h, m);
        b.rect(
            Vec3::new(-x, SCONCE_HEIGHT, z),
            -Vec3::Z * w,
            Vec3::Y * h,
            m,
        );
    }
}

/// Coloured signs: a row of short segments above each shop front.
fn signs(b: &mut SceneBuilder) {
    let count = 2 * SIGNS_PER_WALL * SEGMENTS_PER_SIGN;
    let (w, h) = (0.12, 0.05);
    let materials: Vec<u32> = SIGN_COLOURS
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            b.material(Material::emitter(
                &format!("sign {i}"),
                radiance(c, SIGN_POWER, count, 4.0 * w * h),
                false,
            ))
        })
        .collect();
    for i in 0..SIGNS_PER_WALL {
        let z0 = sign_z(i);
        for side in [-1.0f32, 1.0] {
            let m = materials[(i * 2 + (side > 0.0) as usize) % materials.len()];
            // In front of the shop front's face (0.8 m from the wall), above its top.
            let x = side * (HALF.x - 0.85);
            for s in 0..SEGMENTS_PER_SIGN {
                let z = z0 - 1.35 + s as f32 * 0.3;
                let y = 2.7 + 0.12 * ((s % 2) as f32);
                // side = +1: z × y = -x, into the hall; mirrored on the other wall.
                let along = Vec3::Z * (w * side);
                b.rect(Vec3::new(x, y, z), along, Vec3::Y * h, m);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every light in the scene (downlights, sconces, sign segments): 664.
    const LIGHTS: usize = DOWNLIGHT_COLUMNS * DOWNLIGHT_ROWS
        + 2 * SCONCES_PER_WALL
        + 2 * SIGNS_PER_WALL * SEGMENTS_PER_SIGN;

    #[test]
    fn concourse_has_its_lights_facing_into_the_hall() {
        let s = concourse("concourse");
        assert_eq!(s.emissive_triangle_count(), 2 * LIGHTS);
        for t in &s.triangles {
            if !s.materials[t.material as usize].is_emissive() {
                continue;
            }
            let [a, b, c] = t.indices.map(|i| s.vertices[i as usize].position);
            let n = (b - a).cross(c - a).normalize();
            let centre = (a + b + c) / 3.0;
            // Every emitter's front faces the hall's axis or the floor.
            let towards_axis = Vec3::new(-centre.x, HALF.y - centre.y, 0.0);
            assert!(
                n.dot(towards_axis) > 0.0 || n.y < -0.99,
                "light at {centre} faces {n}"
            );
            assert!(
                centre
                    .abs()
                    .cmple(Vec3::new(HALF.x, 2.0 * HALF.y, HALF.z))
                    .all()
            );
        }
    }

    #[test]
    fn concourse_power_is_split_as_documented() {
        let s = concourse("concourse");
        let total: f32 = (0..s.triangles.len())
            .filter(|&t| s.materials[s.triangles[t].material as usize].is_emissive())
            .map(|t| {
                let [a, b, c] = s.triangle_positions(t);
                let area = 0.5 * (b - a).cross(c - a).length();
                area * luminance(s.materials[s.triangles[t].material as usize].emission)
            })
            .sum();
        let expected = DOWNLIGHT_POWER + SCONCE_POWER + SIGN_POWER;
        assert!((total - expected).abs() < 1e-3 * expected, "{total}");
    }
}
