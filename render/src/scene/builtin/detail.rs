//! `detail`: many small lights over fine occluders, the scene where small shadow detail
//! matters (docs/src/measured/how-the-bench-measures.md, "Shadow detail"). Four chandeliers of 64
//! tiny lights hang over a grille of 2 cm slats held 30 cm above the floor, running away from the
//! camera so that the floor shows between them, and a fence of thin posts stands by the back wall:
//! each chandelier throws the slats' stripes onto the floor with a penumbra about as wide as a
//! slat, and the four sets overlap into a fine pattern. A denoiser that blurs, or reuse that
//! carries one pixel's light sample to a neighbour across a stripe, loses it.

use glam::{Quat, Vec3};

use super::rng::SplitMix64;
use super::shapes::SceneBuilder;
use crate::scene::{Camera, Material, Scene};

const ROOM_HALF: Vec3 = Vec3::new(3.0, 1.5, 3.0);
/// Chandeliers: centre (x, z) at this height, each a disc of lights this wide.
const CHANDELIERS: [(f32, f32); 4] = [(-0.9, -0.9), (0.9, -0.9), (-0.9, 0.9), (0.9, 0.9)];
const CHANDELIER_HEIGHT: f32 = 2.6;
const CHANDELIER_RADIUS: f32 = 0.1;
const LIGHTS_PER_CHANDELIER: usize = 64;
const LIGHT_SIDE: f32 = 0.015;
/// Σ area × luminance(radiance) over all lights (a 6 × 6 m room lit to about the
/// brightness of `many-lights`' 12 × 12 m one).
const TOTAL_POWER: f32 = 40.0;
/// The grille: slats of this square section, this far apart (centre to centre), over
/// this half-extent, at this height above the floor.
const BAR: f32 = 0.02;
const BAR_PITCH: f32 = 0.08;
const LATTICE_HALF: f32 = 1.2;
const LATTICE_HEIGHT: f32 = 0.3;
/// The fence by the back wall: posts of this section, this far apart.
const POST: f32 = 0.03;
const POST_PITCH: f32 = 0.09;

pub(super) fn detail(name: &str) -> Scene {
    let mut b = SceneBuilder::new(name);
    let floor = b.material(Material::diffuse("floor", Vec3::splat(0.7)));
    let wall = b.material(Material::diffuse("wall", Vec3::splat(0.6)));
    let metal = b.material(Material::diffuse("lattice", Vec3::new(0.3, 0.28, 0.25)));
    b.room(Vec3::Y * ROOM_HALF.y, ROOM_HALF, wall, wall, floor);
    // Slats along z (away from the camera), on two crossbars at the ends.
    let bars = (2.0 * LATTICE_HALF / BAR_PITCH) as i32;
    for i in 0..=bars {
        let x = -LATTICE_HALF + i as f32 * BAR_PITCH;
        let along_z = Vec3::new(BAR * 0.5, BAR * 0.5, LATTICE_HALF);
        b.solid_box(
            Vec3::new(x, LATTICE_HEIGHT + BAR, 0.0),
            along_z,
            Quat::IDENTITY,
            metal,
        );
    }
    for z in [-LATTICE_HALF, LATTICE_HALF] {
        let along_x = Vec3::new(LATTICE_HALF, BAR * 0.5, BAR * 0.5);
        b.solid_box(
            Vec3::new(0.0, LATTICE_HEIGHT, z),
            along_x,
            Quat::IDENTITY,
            metal,
        );
    }
    // Four legs hold the grille up.
    for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
        let half = Vec3::new(0.02, LATTICE_HEIGHT * 0.5, 0.02);
        b.solid_box(
            Vec3::new(x * LATTICE_HALF, half.y, z * LATTICE_HALF),
            half,
            Quat::IDENTITY,
            metal,
        );
    }
    // The fence: thin posts 1.2 m high along the back wall.
    let posts = (4.0 / POST_PITCH) as i32;
    for i in 0..=posts {
        let x = -2.0 + i as f32 * POST_PITCH;
        let half = Vec3::new(POST * 0.5, 0.6, POST * 0.5);
        b.solid_box(Vec3::new(x, half.y, -2.3), half, Quat::IDENTITY, metal);
    }
    let n = CHANDELIERS.len() * LIGHTS_PER_CHANDELIER;
    let area = LIGHT_SIDE * LIGHT_SIDE;
    let tints = [
        Vec3::new(1.0, 0.8, 0.6),
        Vec3::new(0.7, 0.85, 1.0),
        Vec3::new(1.0, 0.95, 0.85),
        Vec3::new(0.85, 1.0, 0.8),
    ];
    let mut rng = SplitMix64::new(0xDE7A_11ED);
    let half = LIGHT_SIDE * 0.5;
    for ((x, z), tint) in CHANDELIERS.into_iter().zip(tints) {
        let luminance = tint.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let radiance = tint * (TOTAL_POWER / n as f32 / (area * luminance));
        let light = b.material(Material::emitter("chandelier", radiance, false));
        for _ in 0..LIGHTS_PER_CHANDELIER {
            // Uniform over the disc, at slightly different heights (a cluster, not a plate).
            let r = CHANDELIER_RADIUS * rng.next_f32().sqrt();
            let a = rng.next_f32() * std::f32::consts::TAU;
            let y = CHANDELIER_HEIGHT + rng.range(-0.05, 0.05);
            let center = Vec3::new(x + r * a.cos(), y, z + r * a.sin());
            // x × z = -y: facing down.
            b.rect(center, Vec3::X * half, Vec3::Z * half, light);
        }
    }
    let camera = Camera::look_at(
        Vec3::new(0.1, 1.7, 2.2),
        Vec3::new(0.0, 0.0, -0.4),
        55f32.to_radians(),
    );
    b.finish(Some(camera))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lights_hang_above_the_lattice_and_the_penumbra_is_about_a_bar_wide() {
        let s = detail("detail");
        assert_eq!(
            s.emissive_triangle_count(),
            2 * CHANDELIERS.len() * LIGHTS_PER_CHANDELIER
        );
        // A chandelier's width projected through the lattice onto the floor: the
        // penumbra of a bar's shadow. Between half a bar and a pitch keeps the stripes
        // visible yet soft.
        let penumbra =
            2.0 * CHANDELIER_RADIUS * LATTICE_HEIGHT / (CHANDELIER_HEIGHT - LATTICE_HEIGHT);
        assert!(
            penumbra > 0.5 * BAR && penumbra < BAR_PITCH,
            "penumbra {penumbra} m"
        );
    }
}
