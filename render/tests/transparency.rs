//! Issue 19: light through glass. Shadow rays through a pane of known coverage and
//! transmission carry exactly its transmittance; emitters behind glass are seen and light
//! the scene, and accumulated `restir` agrees with the reference on `builtin:lamps` and on
//! Khronos' LightsPunctualLamp; unlit surfaces show their base colour. Each test has a
//! planted twin: glass treated as opaque (`PLANTED_OPAQUE_GLASS`, what the loader did
//! before), or the unlit extension ignored.
//!
//! Sizes are tiny (lavapipe on two cores); every tolerance says where it comes from.

mod common;

use glam::{Vec2, Vec3, Vec4};
use restir_render::scene::{AlphaMode, Camera, Material, Triangle, Vertex};
use restir_render::{LinearImage, Mode, Renderer, Scene, load_scene};

const OPAQUE_GLASS: &str = "PLANTED_OPAQUE_GLASS";

/// The rectangle `center ± u ± v`, front face along u × v.
fn rect(scene: &mut Scene, center: Vec3, u: Vec3, v: Vec3, material: u32) {
    let base = scene.vertices.len() as u32;
    let normal = u.cross(v).normalize();
    let corners = [center - u - v, center + u - v, center + u + v, center - u + v];
    let uvs = [Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
    for (position, uv) in corners.into_iter().zip(uvs) {
        scene.vertices.push(Vertex {
            position,
            normal,
            uv,
        });
    }
    for t in [[0, 1, 2], [0, 2, 3]] {
        scene.triangles.push(Triangle {
            indices: t.map(|i| base + i),
            material,
        });
    }
}

fn material(scene: &mut Scene, m: Material) -> u32 {
    scene.materials.push(m);
    scene.materials.len() as u32 - 1
}

/// The pane's model values: coverage 0.5, transmission 0.8, tint (1, 0.5, 0.25), so
/// transmittance = (1 − a) + a·t·tint = (0.9, 0.7, 0.6) (README "Conventions").
const PANE_TRANSMITTANCE: [f64; 3] = [0.9, 0.7, 0.6];

/// A floor under a downward square emitter, optionally with a large pane between them that
/// every light path to the floor crosses; the camera sits under the pane looking down.
fn pane_scene(with_pane: bool) -> Scene {
    let mut s = Scene {
        name: "pane".into(),
        ..Scene::default()
    };
    let floor = material(&mut s, Material::diffuse("floor", Vec3::splat(0.5)));
    let light = material(&mut s, Material::emitter("light", Vec3::splat(4.0), false));
    rect(&mut s, Vec3::ZERO, Vec3::Z * 2.0, Vec3::X * 2.0, floor);
    rect(&mut s, Vec3::Y * 2.0, Vec3::X, Vec3::Z, light);
    // Under the floor, out of every light path: it only makes occlusion possible, so both
    // scenes compile shadow rays and run the same estimators (effects.rs).
    rect(&mut s, Vec3::NEG_Y, Vec3::Z * 0.1, Vec3::X * 0.1, floor);
    if with_pane {
        let pane = material(
            &mut s,
            Material {
                name: "pane".into(),
                base_color: Vec4::new(1.0, 0.5, 0.25, 0.5),
                alpha_mode: AlphaMode::Blend,
                transmission: 0.8,
                double_sided: true,
                specular: 0.0,
                ..Material::default()
            },
        );
        rect(&mut s, Vec3::Y, Vec3::Z * 3.0, Vec3::X * 3.0, pane);
    }
    s.camera = Some(Camera::look_at(
        Vec3::new(0.0, 0.9, 1.2),
        Vec3::ZERO,
        60f32.to_radians(),
    ));
    s
}

fn channel_means(img: &LinearImage) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for p in &img.pixels {
        for c in 0..3 {
            sum[c] += p[c] as f64;
        }
    }
    sum.map(|s| s / img.pixels.len() as f64)
}

/// Per channel: the floor's mean radiance with the pane over without it, in `mode`.
fn pane_ratio(mode: Mode, planted: &[&str]) -> [f64; 3] {
    let render = |with_pane: bool| {
        let scene = pane_scene(with_pane);
        let settings = common::settings(&["jitter=false", "reference_spp=64"]);
        let mut r = Renderer::new(common::gpu(), &scene, 32, 24, settings).unwrap();
        r.plant_for_tests(planted);
        r.set_mode(mode);
        let frames = if mode == Mode::Reference { 4 } else { 64 };
        channel_means(&common::accumulate(&mut r, frames))
    };
    let (with, without) = (render(true), render(false));
    assert!(without.iter().all(|&c| c > 0.01), "the floor is lit: {without:?}");
    [0, 1, 2].map(|c| with[c] / without[c])
}

#[test]
fn shadow_rays_through_a_pane_carry_its_transmittance() {
    // Every light path to the floor crosses the pane once, so the closed form is the
    // unobstructed image times the transmittance, per channel. The two scenes' light tables
    // are ordered differently (the pane changes the BVH), so their noise differs: 256 spp
    // of the reference, 64 frames of nee/restir over 768 pixels put the mean's standard
    // error near 0.2 % (measured spread below 0.5 %); 1.5 % is > 3 σ, and the nearest wrong
    // model (the tint dropped: 0.9 in every channel) is 50 % off in blue.
    for mode in [Mode::Reference, Mode::Nee, Mode::Restir] {
        let ratio = pane_ratio(mode, &[]);
        eprintln!("{mode:?}: with / without pane = {ratio:.4?}");
        for c in 0..3 {
            assert!(
                (ratio[c] / PANE_TRANSMITTANCE[c] - 1.0).abs() < 0.015,
                "{mode:?} channel {c}: {:.4} vs {}",
                ratio[c],
                PANE_TRANSMITTANCE[c]
            );
        }
    }
}

#[test]
fn planted_opaque_pane_blocks_the_light() {
    // The twin: the pane as an opaque surface (the loader's old "BLEND is opaque").
    let ratio = pane_ratio(Mode::Reference, &[OPAQUE_GLASS]);
    eprintln!("opaque pane: with / without = {ratio:.4?}");
    assert!(ratio.iter().all(|&c| c < 0.05), "detector silent: {ratio:?}");
}

/// Accumulated `restir` and the reference of `scene` (jitter off), with `planted` defines.
fn restir_and_reference(scene: &Scene, size: (u32, u32), planted: &[&str]) -> (LinearImage, LinearImage) {
    let settings = common::settings(&["jitter=false"]);
    let mut r = Renderer::new(common::gpu(), scene, size.0, size.1, settings).unwrap();
    r.plant_for_tests(planted);
    let reference = common::reference(&mut r, 8, 64);
    r.set_mode(Mode::Restir);
    let image = common::accumulate(&mut r, 48);
    (image, reference)
}

fn luma(p: [f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Mean luma of `image` and of `reference` over the pixels the reference shows below
/// LIT_LUMA_MAX: lit surfaces, not the emitters seen directly.
fn lit_means(image: &LinearImage, reference: &LinearImage) -> (f64, f64) {
    let (mut a, mut b) = (0.0, 0.0);
    for (p, q) in image.pixels.iter().zip(&reference.pixels) {
        if luma(*q) < LIT_LUMA_MAX {
            a += luma(*p);
            b += luma(*q);
        }
    }
    (a, b)
}

const LIT_LUMA_MAX: f64 = 4.0;

fn lamps() -> Scene {
    load_scene("builtin:lamps").unwrap()
}

#[test]
fn restir_agrees_with_the_reference_behind_glass() {
    // builtin:lamps: every emitter sits in glass (clear and frosted globes, tinted tubes,
    // a textured shade). 2 %: the bar; the 512-spp reference and 48 correlated
    // frames each carry well under 0.5 % standard error in the mean at this size (measured
    // spread of the ratio over seeds below), and the twin is far outside.
    let (image, reference) = restir_and_reference(&lamps(), (64, 48), &[]);
    let ratio = image.mean_luminance() / reference.mean_luminance();
    eprintln!("lamps: restir / reference = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.02, "ratio {ratio:.4}");
}

#[test]
fn planted_opaque_glass_darkens_the_lamps() {
    // The twin: glass as opaque hides the bulbs and the neon, and blocks their light; only
    // the shade's open top and bottom let any out.
    let (image, _) = restir_and_reference(&lamps(), (64, 48), &[OPAQUE_GLASS]);
    let (bright, _) = restir_and_reference(&lamps(), (64, 48), &[]);
    let ratio = image.mean_luminance() / bright.mean_luminance();
    eprintln!("lamps, opaque glass / glass: {ratio:.4}");
    assert!(ratio < 0.5, "detector silent: {ratio:.4}");
}

#[test]
#[ignore]
fn explore_lamps() {
    let mut scene = lamps();
    if std::env::var("NO_GLASS").is_ok() {
        let mats = scene.materials.clone();
        scene.triangles.retain(|t| !mats[t.material as usize].is_transparent());
    }
    if let Ok(v) = std::env::var("FROSTED_CLEAR") {
        for m in &mut scene.materials {
            if m.alpha_mode == AlphaMode::Blend && v == "1" { m.base_color.w = 1.0; m.alpha_mode = AlphaMode::Opaque; m.transmission = 1.0; }
            if m.transmission_texture.is_some() && v == "1" { m.transmission_texture = None; }
        }
    }
    for jitter in ["jitter=false"] {
    let settings = common::settings(&[jitter]);
    let mut r = Renderer::new(common::gpu(), &scene, 32, 24, settings).unwrap();
    let reference = common::reference(&mut r, 32, 64);
    let ref_lum = reference.mean_luminance();
    for (mode, extra, seed) in [
        (Mode::Restir, Vec::<&str>::new(), 1),
        (Mode::Restir, vec![], 2),
        (Mode::Restir, vec![], 3),
        (Mode::Restir, vec!["mis_visibility=false"], 1),
        (Mode::Restir, vec!["mis_visibility=false"], 2),
        (Mode::Restir, vec!["mis_visibility=false"], 3),

    ] {
        let mut a = vec![jitter];
        a.extend(extra.iter().copied());
        r.set_settings(common::settings(&a));
        r.set_seed(seed);
        r.set_mode(mode);
        let t0 = std::time::Instant::now();
        let img = common::accumulate(&mut r, 256);
        eprintln!("{:?}", t0.elapsed());
        let (a, b) = lit_means(&img, &reference);
        eprintln!("{jitter} {mode:?} {extra:?} {seed}: {:.4} lit {:.4}", img.mean_luminance() / ref_lum, a / b);
    }
    }
}

#[test]
#[ignore]
fn explore_specks() {
    let mut scene = lamps();
    let keep_glass = std::env::var("KEEP_GLASS").is_ok();
    if !keep_glass {
        let mats = scene.materials.clone();
        scene.triangles.retain(|t| !mats[t.material as usize].is_transparent());
    }
    let settings = common::settings(&["jitter=false"]);
    let mut r = Renderer::new(common::gpu(), &scene, 160, 120, settings).unwrap();
    r.set_mode(Mode::Nee);
    let img = common::accumulate(&mut r, 32);
    let rgba: Vec<u8> = img
        .pixels
        .iter()
        .flat_map(|p| {
            let t = |c: f32| ((c / (1.0 + c)).powf(1.0 / 2.2) * 255.0) as u8;
            [t(p[0] * 0.5), t(p[1] * 0.5), t(p[2] * 0.5), 255]
        })
        .collect();
    restir_render::image::save_png_rgba8(
        std::path::Path::new(&format!("/tmp/l/specks_{keep_glass}.png")),
        160,
        120,
        &rgba,
    )
    .unwrap();
}

#[test]
#[ignore]
fn explore_variance() {
    let scene = lamps();
    let settings = common::settings(&["jitter=false"]);
    let mut r = Renderer::new(common::gpu(), &scene, 32, 24, settings).unwrap();
    r.set_mode(Mode::Nee);
    let mut imgs = vec![];
    for seed in [1, 2] {
        r.set_seed(seed);
        imgs.push(common::accumulate(&mut r, 256));
    }
    let mut d: Vec<(f64, usize, f64, f64)> = imgs[0].pixels.iter().zip(&imgs[1].pixels).enumerate()
        .map(|(i, (a, b))| ((luma(*a) - luma(*b)).abs(), i, luma(*a), luma(*b))).collect();
    d.sort_by(|x, y| y.0.partial_cmp(&x.0).unwrap());
    let total: f64 = d.iter().map(|x| x.0).sum();
    eprintln!("means {} {}", imgs[0].mean_luminance(), imgs[1].mean_luminance());
    for x in d.iter().take(12) {
        eprintln!("pixel ({}, {}): diff {:.3} ({:.3} vs {:.3}), share {:.3}", x.1 % 32, x.1 / 32, x.0, x.2, x.3, x.0 / total);
    }
}

#[test]
#[ignore]
fn explore_pixel() {
    let scene = lamps();
    let settings = common::settings(&["jitter=false"]);
    let mut r = Renderer::new(common::gpu(), &scene, 32, 24, settings).unwrap();
    r.set_mode(Mode::Nee);
    for seed in [1, 2] {
        r.set_seed(seed);
        r.reset_accumulation();
        let mut v = vec![];
        for _ in 0..24 {
            r.render_frame().unwrap();
            let img = r.read_radiance();
            v.push(format!("{:.2}", luma(img.get(22, 10))));
        }
        let s = r.read_surfaces();
        let p = &s[10 * 32 + 22];
        eprintln!("seed {seed}: {} | depth {} thr {:?} first {} mat {}", v.join(" "), p.depth, p.throughput, p.transparent_first, p.material);
    }
}
