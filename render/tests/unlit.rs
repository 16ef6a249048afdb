//! `KHR_materials_unlit` (docs/src/scenes.md, "Emitters and materials"). The camera sees base
//! colour × base colour texture as radiance, in every mode, however the surface is lit; the surface
//! lights nothing. The planted twin (`PLANTED_UNLIT_AS_LIT`) shades it as a lit surface, as the
//! loader did before the extension was read.

use crate::common;

use common::scene_parts::{material, rect};
use glam::{Vec3, Vec4};
use restir_render::scene::{Camera, Material, Texture, TextureRef, Wrap};
use restir_render::{LinearImage, Mode, Renderer, Scene};

const BASE: [f32; 3] = [0.8, 0.5, 0.25];
/// The texture's one sRGB value (every texel alike, so filtering cannot change it).
const TEXEL: u8 = 188;

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The hand-computed radiance of the unlit card: base colour × decoded texel.
fn expected() -> [f32; 3] {
    let t = srgb_to_linear(TEXEL as f32 / 255.0);
    BASE.map(|b| b * t)
}

/// A card facing the camera, unlit and textured, over a diffuse floor; `light` adds a bright
/// emitter right in front of the card (it would light a lit card far above its colour).
fn card_scene(light: bool) -> Scene {
    let mut s = Scene {
        name: "unlit card".into(),
        ..Scene::default()
    };
    s.textures.push(Texture {
        name: "grey".into(),
        width: 2,
        height: 2,
        texels: vec![[TEXEL, TEXEL, TEXEL, 255]; 4],
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::Repeat,
    });
    let card = material(
        &mut s,
        Material {
            name: "card".into(),
            base_color: Vec4::new(BASE[0], BASE[1], BASE[2], 1.0),
            base_color_texture: Some(TextureRef::new(0)),
            unlit: true,
            ..Material::default()
        },
    );
    let floor = material(&mut s, Material::diffuse("floor", Vec3::splat(0.5)));
    rect(
        &mut s,
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::X,
        Vec3::Y * 0.75,
        card,
    );
    rect(
        &mut s,
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::Z * 1.5,
        Vec3::X * 2.0,
        floor,
    );
    if light {
        let lamp = material(&mut s, Material::emitter("lamp", Vec3::splat(20.0), false));
        // Facing the card (-Z), above the camera's line of sight.
        rect(
            &mut s,
            Vec3::new(0.0, 2.2, 1.5),
            Vec3::Y * 0.3,
            Vec3::X * 0.3,
            lamp,
        );
    }
    s.camera = Some(Camera::look_at(
        Vec3::new(0.0, 1.0, 3.0),
        Vec3::new(0.0, 1.0, 0.0),
        40f32.to_radians(),
    ));
    s
}

fn render(scene: &Scene, mode: Mode, planted: &[&str]) -> LinearImage {
    let settings = common::settings(&["jitter=false", "reference_spp=16"]);
    let mut r = Renderer::new(common::gpu(), scene, 32, 24, settings).unwrap();
    r.plant_for_tests(planted);
    r.set_mode(mode);
    common::accumulate(&mut r, 4)
}

/// The worst relative error over the colour channels of the image's centre pixel (on the card).
fn centre_error(image: &LinearImage) -> f32 {
    let p = image.get(image.width / 2, image.height / 2);
    let e = expected();
    (0..3)
        .map(|c| (p[c] - e[c]).abs() / e[c])
        .fold(0.0, f32::max)
}

#[test]
fn unlit_card_shows_its_base_colour_in_every_mode() {
    // 1e-3: f32 shading of an exact value (the card reflects nothing, so there is no noise);
    // the texel is decoded by the same sRGB formula as here.
    let scene = card_scene(true);
    for mode in [Mode::Restir, Mode::Nee, Mode::Reference] {
        let error = centre_error(&render(&scene, mode, &[]));
        eprintln!("{mode:?}: centre pixel off by {error:.2e}");
        assert!(error < 1e-3, "{mode:?}: centre pixel off by {error}");
    }
}

#[test]
fn planted_unlit_as_lit_misses_the_colour() {
    // The twin: shaded as lit, the card shows the lamp's reflection, not its colour.
    let error = centre_error(&render(
        &card_scene(true),
        Mode::Reference,
        &["PLANTED_UNLIT_AS_LIT"],
    ));
    eprintln!("unlit shaded as lit: centre pixel off by {error:.2}");
    assert!(error > 0.2, "detector silent: {error}");
}

#[test]
fn unlit_card_lights_nothing() {
    // Without an emitter the floor stays black in the reference (two bounces): the card's
    // colour is no light source. Only the card's own pixels are lit.
    let image = render(&card_scene(false), Mode::Reference, &[]);
    let e = expected();
    let lit: Vec<_> = image
        .pixels
        .iter()
        .filter(|p| p[0] > 0.0 || p[1] > 0.0 || p[2] > 0.0)
        .collect();
    assert!(!lit.is_empty(), "the card is seen");
    for p in lit {
        assert!(
            (p[0] - e[0]).abs() < 1e-3 * e[0],
            "a pixel other than the card is lit: {p:?}"
        );
    }
}
