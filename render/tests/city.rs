//! The night city (`builtin:city:N`, `builtin:city-roofs:N`): a large scene where each pixel
//! is lit by a few nearby lights among many. It loads at a million emissive triangles and
//! renders finite from both cameras, with one light, and through the reference.

use crate::common;

use restir_render::Mode;

fn finite_frames(scene: &str, mode: Mode, frames: u32) -> (usize, f64) {
    let mut r = common::renderer(scene, 32, 20, mode, common::settings(&["jitter=false"]));
    let mut mean = 0.0;
    for _ in 0..frames {
        r.render_frame().unwrap_or_else(|e| panic!("{scene}: {e}"));
        let img = r.read_radiance();
        let bad = img.non_finite_count();
        assert_eq!(bad, 0, "{scene} ({mode:?}): {bad} non-finite pixels");
        mean = common::indirect::mean_luma(&img);
    }
    (r.scene_info().emissive_triangles, mean)
}

/// 2^20 emissive triangles load and render (restir, the default settings) finite, lit.
#[test]
fn a_million_light_city_loads_and_renders_finite() {
    let (lights, mean) = finite_frames("builtin:city:1048576", Mode::Restir, 2);
    assert_eq!(lights, 1 << 20);
    assert!(mean > 0.0, "the street is black");
}

/// Both cameras, a single light, and the reference stay finite; the street is lit.
#[test]
fn small_cities_render_finite_from_both_cameras() {
    for (scene, mode) in [
        ("builtin:city:16384", Mode::Restir),
        ("builtin:city-roofs:16384", Mode::Restir),
        ("builtin:city:1", Mode::Restir),
        ("builtin:city:4096", Mode::Reference),
    ] {
        let (lights, mean) = finite_frames(scene, mode, 2);
        assert!(lights >= 1 && mean.is_finite(), "{scene}");
    }
}
