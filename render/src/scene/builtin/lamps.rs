//! `lamps`: lights behind glass, the scene of docs/src/transparency.md. Bulbs in clear and frosted
//! globes on two shelves, neon tubes in tinted glass, and a paper shade whose transmission
//! comes from a striped texture, in a small room. Every emitter is seen (and lights the
//! room) only through a transparent layer, so an estimator that treats glass as opaque
//! renders it dark, and one that drops the tint gets the colours wrong.

use glam::{Quat, Vec3, Vec4};

use super::shapes::{Facing, SceneBuilder};
use crate::scene::{AlphaMode, Camera, Material, Scene, Texture, TextureRef, Wrap};

/// Half-size of the room: 6 m wide, 3 m high, 4 m deep.
const HALF: Vec3 = Vec3::new(3.0, 1.5, 2.0);
const GLOBES_PER_SHELF: usize = 6;
const GLOBE_RADIUS: f32 = 0.2;
/// Globes stand on stems: a bulb right over the shelf would light a few pixels so brightly
/// that they alone decide an image's mean (and its noise).
const STEM_HEIGHT: f32 = 0.18;
const BULB_HALF: f32 = 0.07;
const BULB_RADIANCE: f32 = 25.0;
const NEON_RADIANCE: f32 = 25.0;
const NEON_COLOURS: [Vec3; 3] = [
    Vec3::new(1.0, 0.1, 0.3),
    Vec3::new(0.1, 0.6, 1.0),
    Vec3::new(0.3, 1.0, 0.2),
];

pub(super) fn lamps(name: &str) -> Scene {
    let mut b = SceneBuilder::new(name);
    let wall = b.material(Material::diffuse("wall", Vec3::splat(0.55)));
    let floor = b.material(Material {
        name: "floor".into(),
        base_color: Vec4::new(0.35, 0.28, 0.22, 1.0),
        roughness: 0.35,
        ..Material::default()
    });
    let wood = b.material(Material::diffuse("shelf", Vec3::new(0.45, 0.3, 0.18)));
    // The room, open toward the camera (+Z).
    let mut faces = [Some(wall); 6];
    faces[3] = Some(floor); // NegY
    faces[4] = None; // PosZ
    b.cuboid(
        Vec3::new(0.0, HALF.y, 0.0),
        HALF,
        Quat::IDENTITY,
        Facing::Inward,
        faces,
    );

    let clear = b.material(glass("clear glass", Vec3::new(0.96, 0.96, 0.92), None));
    let frosted = b.material(Material {
        name: "frosted glass".into(),
        base_color: Vec4::new(0.9, 0.9, 0.95, 0.45),
        roughness: 0.6,
        // Single-sided: the camera does not see the globe's inside, which its own bulb
        // would light from a few centimetres (fireflies for every estimator, a test that
        // measures noise instead of bias).
        double_sided: false,
        alpha_mode: AlphaMode::Blend,
        ..Material::default()
    });
    let bulb = b.material(Material::emitter(
        "bulb",
        Vec3::new(1.0, 0.7, 0.4) * BULB_RADIANCE,
        true,
    ));
    let stem = b.material(Material::diffuse("stem", Vec3::splat(0.2)));
    for (row, y) in [0.7f32, 1.5].into_iter().enumerate() {
        let shelf_z = -HALF.z + 0.35;
        b.solid_box(
            Vec3::new(0.0, y - 0.03, shelf_z),
            Vec3::new(HALF.x - 0.4, 0.03, 0.3),
            Quat::IDENTITY,
            wood,
        );
        for i in 0..GLOBES_PER_SHELF {
            let x = (i as f32 - (GLOBES_PER_SHELF as f32 - 1.0) * 0.5) * 0.8;
            let centre = Vec3::new(x, y + STEM_HEIGHT + GLOBE_RADIUS, shelf_z);
            b.solid_box(
                Vec3::new(x, y + STEM_HEIGHT * 0.5, shelf_z),
                Vec3::new(0.015, STEM_HEIGHT * 0.5, 0.015),
                Quat::IDENTITY,
                stem,
            );
            b.solid_box(centre, Vec3::splat(BULB_HALF), Quat::IDENTITY, bulb);
            let globe = if (i + row) % 3 == 2 { frosted } else { clear };
            sphere(&mut b, centre, GLOBE_RADIUS, globe);
        }
    }

    // Neon tubes on the back wall, each in a tube of tinted glass.
    for (i, colour) in NEON_COLOURS.into_iter().enumerate() {
        let y = 2.3 + 0.18 * i as f32;
        let centre = Vec3::new(-0.6 + 0.6 * i as f32, y, -HALF.z + 0.3);
        let tube = b.material(Material::emitter("neon", colour * NEON_RADIANCE, true));
        b.solid_box(centre, Vec3::new(0.7, 0.012, 0.012), Quat::IDENTITY, tube);
        let tint = Vec3::ONE.lerp(colour, 0.35);
        let glass_tube = b.material(glass("neon glass", tint, None));
        b.solid_box(
            centre,
            Vec3::new(0.74, 0.05, 0.05),
            Quat::IDENTITY,
            glass_tube,
        );
    }

    // A floor lamp: a bulb in an open paper shade whose transmission is a striped texture.
    let stripes = b.texture(striped_transmission());
    let paper = b.material(Material {
        base_color: Vec4::new(0.95, 0.85, 0.65, 1.0),
        double_sided: false, // as the frosted globes: its inside is not seen
        ..glass("paper shade", Vec3::ONE, Some(TextureRef::new(stripes)))
    });
    let lamp = Vec3::new(2.1, 1.3, 0.6);
    b.solid_box(lamp, Vec3::splat(0.05), Quat::IDENTITY, bulb);
    let pole = b.material(Material::diffuse("pole", Vec3::splat(0.1)));
    b.solid_box(
        Vec3::new(lamp.x, 0.5, lamp.z),
        Vec3::new(0.02, 0.5, 0.02),
        Quat::IDENTITY,
        pole,
    );
    let mut sides = [Some(paper); 6];
    sides[2] = None; // open top and bottom
    sides[3] = None;
    b.cuboid(
        lamp,
        Vec3::new(0.25, 0.2, 0.25),
        Quat::IDENTITY,
        Facing::Outward,
        sides,
    );

    let camera = Camera::look_at(
        Vec3::new(0.4, 1.5, 2.8),
        Vec3::new(0.0, 1.45, -1.5),
        55f32.to_radians(),
    );
    b.finish(Some(camera))
}

/// Thin clear glass: everything covered transmits, tinted by `tint` (docs/src/transparency.md,
/// "The thin-layer model").
fn glass(name: &str, tint: Vec3, transmission_texture: Option<TextureRef>) -> Material {
    Material {
        name: name.into(),
        base_color: tint.extend(1.0),
        roughness: 0.05,
        double_sided: true,
        transmission: 1.0,
        transmission_texture,
        ..Material::default()
    }
}

/// Vertical stripes, 8 per turn: R = 0.9 (thin paper) and 0.3 (a printed band).
fn striped_transmission() -> Texture {
    let width = 16;
    let texels = (0..width)
        .map(|x| {
            let r = if (x / 2) % 2 == 0 { 230 } else { 77 };
            [r, r, r, 255]
        })
        .collect();
    Texture {
        name: "shade stripes".into(),
        width,
        height: 1,
        texels,
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::Repeat,
    }
}

/// A UV sphere of 12 × 8 facets, front faces outward.
fn sphere(b: &mut SceneBuilder, centre: Vec3, radius: f32, material: u32) {
    const SLICES: usize = 12;
    const STACKS: usize = 8;
    let point = |slice: usize, stack: usize| {
        let phi = std::f32::consts::TAU * slice as f32 / SLICES as f32;
        let theta = std::f32::consts::PI * stack as f32 / STACKS as f32;
        centre
            + radius
                * Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                )
    };
    for stack in 0..STACKS {
        for slice in 0..SLICES {
            let a = point(slice, stack);
            let b2 = point(slice + 1, stack);
            let c = point(slice + 1, stack + 1);
            let d = point(slice, stack + 1);
            // Counter-clockwise seen from outside (phi grows toward -Z seen from +Y).
            if stack > 0 {
                b.triangle([a, b2, d], material);
            }
            if stack + 1 < STACKS {
                b.triangle([b2, c, d], material);
            }
        }
    }
}
