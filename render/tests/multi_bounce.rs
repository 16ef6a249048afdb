//! The multi-bounce reference (`max_bounces`, docs/src/frame.md, "The reference"): a furnace test
//! whose answer is exact, its planted-error twins, and the Cornell box with indirect light.
//!
//! **The furnace.** Inside a closed box whose walls are all Lambertian with albedo a and all emit
//! Le from the inside, the radiance is the same at every point and in every direction, bounce by
//! bounce: emission Le, direct light ∫ Le·(a/π)·cos dω = a·Le, and each further bounce multiplies
//! the last term by a. So with max_bounces = N every pixel's expectation is Le·(1 + a + … + a^N):
//! Le(1 + a) for N = 1 (today's direct-only reference), Le(1 + a + a²) for N = 2, Le(1 + a + a² +
//! a³) for N = 3. (So "2 bounces" — emission + direct light at the first hit + direct light at the
//! second hit — is a sum of three terms, not Le·(1 + a).) Every wall is both a light the light
//! sampler picks and a surface the BSDF ray hits, so an emitter counted twice or not at all by MIS
//! shows as a wrong level.

use crate::common;

use std::collections::BTreeSet;

use glam::Vec3;
use restir_render::effects::{Effect, EffectSet, SceneFeatures};
use restir_render::{Camera, LinearImage, Mode, Renderer, Scene, Settings};

const LE: f32 = 1.0;
const ALBEDO: f32 = 0.5;
const SIZE: u32 = 16;

fn furnace_box() -> Scene {
    common::furnace::furnace_box(LE, ALBEDO)
}

/// Le·(1 + a₁·(1 + a + … + a^(N−1))), where a₁ is the first vertex's albedo: a itself
/// for camera rays, but the rasterised surfaces (jitter off) store the base colour as
/// 8-bit unorm, so there a₁ = round(255·a)/255 (0.50196 for 0.5: +0.3 % at N = 2, which
/// the tolerance would otherwise flag).
fn furnace_expected(bounces: u32, jitter: bool) -> f64 {
    let a = ALBEDO as f64;
    let a1 = if jitter {
        a
    } else {
        (a * 255.0).round() / 255.0
    };
    let later: f64 = (0..bounces).map(|k| a.powi(k as i32)).sum();
    (1.0 + a1 * later) * LE as f64
}

/// How to break or vary the pipeline for one furnace run.
#[derive(Clone, Copy)]
struct Variant {
    jitter: bool,
    /// Shadow rays compiled in although the box is convex (the scene alone turns them off).
    shadows: bool,
    /// `reference_light_samples`: light samples per vertex.
    light_samples: u32,
    planted: Option<&'static str>,
}

const PLAIN: Variant = Variant {
    jitter: true,
    shadows: false,
    light_samples: 1,
    planted: None,
};

/// The mean over pixels and its standard error: pixels are independent averages of `spp`
/// samples with one expectation, so SE = (spread of pixel values)/√pixels.
struct Measured {
    mean: f64,
    standard_error: f64,
    non_finite: usize,
}

fn furnace(bounces: u32, v: Variant, spp: u32) -> Measured {
    let scene = furnace_box();
    let settings = common::settings(&[
        &format!("jitter={}", v.jitter),
        &format!("reference_spp={spp}"),
        &format!("max_bounces={bounces}"),
        &format!("reference_light_samples={}", v.light_samples),
    ]);
    let mut effects = EffectSet::detect(&SceneFeatures::of(&scene), &settings, false);
    assert!(
        !effects.contains(Effect::Shadows),
        "a closed convex box cannot occlude: the proof in effects.rs should see that"
    );
    if v.shadows {
        effects.enabled.insert(Effect::Shadows);
    }
    effects.planted = v
        .planted
        .map(str::to_string)
        .into_iter()
        .collect::<BTreeSet<_>>();
    let mut r = Renderer::new(common::gpu(), &scene, SIZE, SIZE, settings).unwrap();
    r.force_effects(Some(effects));
    // From the centre toward a corner region: every pixel sees a wall, some see an edge.
    r.set_camera(Camera::look_at(
        Vec3::ZERO,
        Vec3::new(1.0, 0.3, 0.6),
        70f32.to_radians(),
    ));
    r.set_mode(Mode::Reference);
    let img = common::accumulate(&mut r, 1);
    let lum: Vec<f64> = (0..SIZE * SIZE)
        .map(|i| img.luminance_at(i % SIZE, i / SIZE) as f64)
        .collect();
    let n = lum.len() as f64;
    let mean = lum.iter().sum::<f64>() / n;
    let var = lum.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Measured {
        mean,
        standard_error: (var / n).sqrt(),
        non_finite: img.non_finite_count(),
    }
}

/// 256 samples per pixel × 256 pixels. The tolerance is 5 standard errors of the mean
/// (p < 1e-6 for a correct estimator), measured from the image itself: ~0.1 % of the level
/// for N ≥ 2 (about 0.5 % for N = 1, whose old code samples lights only, without MIS, in a
/// convex scene: noisy near the box's edges). SE is asserted below 1 % of the level so the
/// test keeps its power: the planted errors move the level by 11-16 % (z > 100).
const SPP: u32 = 256;

/// Whether the furnace at N bounces comes out at its exact level (within 5 SE).
fn furnace_holds(bounces: u32, v: Variant) -> bool {
    let m = furnace(bounces, v, SPP);
    let expected = furnace_expected(bounces, v.jitter);
    let z = (m.mean - expected) / m.standard_error;
    eprintln!(
        "furnace N={bounces} jitter={} shadows={} light samples={} planted={:?}: mean {:.5}, \
         expected {:.5} (ratio {:.4}), SE {:.5}, z {z:.2}",
        v.jitter,
        v.shadows,
        v.light_samples,
        v.planted,
        m.mean,
        expected,
        m.mean / expected,
        m.standard_error,
    );
    assert_eq!(m.non_finite, 0, "non-finite pixels");
    assert!(
        m.standard_error < 0.01 * expected,
        "too noisy for the tolerance to mean anything: SE {}",
        m.standard_error
    );
    z.abs() < 5.0
}

#[test]
fn furnace_one_two_and_three_bounces_are_exact() {
    for bounces in 1..=3 {
        assert!(furnace_holds(bounces, PLAIN), "N={bounces}");
    }
    // The rasterised surfaces (jitter off) and shadow rays compiled in (every shadow ray
    // must find its wall unoccluded) take other code paths to the same answer.
    let surfaces = Variant {
        jitter: false,
        ..PLAIN
    };
    assert!(furnace_holds(2, surfaces), "jitter off");
    let shadows = Variant {
        shadows: true,
        ..PLAIN
    };
    assert!(furnace_holds(2, shadows), "shadows on");
    assert!(furnace_holds(3, shadows), "shadows on, N=3");
}

/// Several light samples per vertex, each weighed by the multi-sample balance heuristic
/// (n·p_light + p_bsdf): still exact, with shadow rays compiled in (the BSDF strategy in
/// the weight) and without (light samples alone at the first vertex). Planted: each of the
/// n samples weighed as if alone counts the light sampling's share n times.
#[test]
fn furnace_is_exact_with_several_light_samples_per_vertex() {
    let four = Variant {
        light_samples: 4,
        ..PLAIN
    };
    assert!(furnace_holds(1, four), "N=1, 4 light samples");
    assert!(furnace_holds(2, four), "N=2, 4 light samples");
    let shadows = Variant {
        shadows: true,
        ..four
    };
    assert!(furnace_holds(2, shadows), "shadows on, 4 light samples");
    let planted = Variant {
        planted: Some("PLANTED_LIGHT_SAMPLES_UNWEIGHTED"),
        ..shadows
    };
    assert!(!furnace_holds(2, planted), "n samples each weighed alone");
}

#[test]
fn furnace_detects_a_missing_mis_weight_on_bsdf_found_emission() {
    // The emitter found by the BSDF ray counted with weight 1 next to the light sample's
    // balance weight: each vertex's direct light is counted more than once.
    let planted = Variant {
        planted: Some("PLANTED_NO_BSDF_MIS"),
        ..PLAIN
    };
    assert!(!furnace_holds(2, planted));
}

#[test]
fn furnace_detects_a_throughput_without_its_pdf() {
    // throughput *= f·cos instead of f·cos/pdf: the indirect terms shrink by cos/pdf = π
    // on average for cosine sampling (from a² to a²/π).
    let planted = Variant {
        planted: Some("PLANTED_NO_THROUGHPUT_PDF"),
        ..PLAIN
    };
    assert!(!furnace_holds(2, planted));
}

/// The reference of builtin:cornell (32×24, jitter off, 128 spp) with N bounces, and the
/// non-finite values the reference pass replaced.
fn cornell(bounces: u32) -> (LinearImage, u64) {
    let settings = common::settings(&[
        "jitter=false",
        "reference_spp=64",
        &format!("max_bounces={bounces}"),
    ]);
    let mut r = common::renderer("builtin:cornell", 32, 24, Mode::Reference, settings);
    let img = common::accumulate(&mut r, 2);
    let replaced = r
        .collect_reports(true)
        .iter()
        .map(|f| f.counters.non_finite_total())
        .sum();
    (img, replaced)
}

#[test]
fn cornell_with_a_second_bounce_is_brighter_and_finite() {
    let (one, replaced_one) = cornell(1);
    let (two, replaced_two) = cornell(2);
    let (eight, replaced_eight) = cornell(8);
    for (name, img, replaced) in [
        ("1", &one, replaced_one),
        ("2", &two, replaced_two),
        ("8", &eight, replaced_eight),
    ] {
        assert_eq!(
            img.non_finite_count(),
            0,
            "{name} bounces: non-finite pixels"
        );
        assert_eq!(
            replaced, 0,
            "{name} bounces: the pass replaced non-finite values"
        );
    }
    let ratio = two.mean_luminance() / one.mean_luminance();
    let ratio_eight = eight.mean_luminance() / two.mean_luminance();
    eprintln!("cornell mean luma: 2 / 1 bounces {ratio:.4}, 8 / 2 bounces {ratio_eight:.4}");
    // Indirect light is non-negative and, in a closed white-walled box, large: the walls'
    // albedo is ~0.5-0.7, so the second bounce adds tens of percent; 1.1 leaves room for
    // noise (the 128-spp means are within ~1 % of their expectations).
    assert!(ratio > 1.1, "2 bounces / 1 bounce = {ratio}");
    // Further bounces add less than the first indirect one but never subtract.
    assert!(ratio_eight > 1.0, "8 bounces / 2 bounces = {ratio_eight}");
    // Pixel by pixel: more bounces can only add light (up to noise); a pixel much darker
    // than its 1-bounce self would mean the path lost its direct term.
    let darker = (0..32 * 24)
        .filter(|i| {
            let (x, y) = (i % 32, i / 32);
            two.luminance_at(x, y) < 0.7 * one.luminance_at(x, y)
        })
        .count();
    assert!(
        darker < 32 * 24 / 50,
        "{darker} pixels much darker with 2 bounces"
    );
}

#[test]
fn max_bounces_is_a_shading_parameter_from_1_to_8_and_reaches_the_shaders() {
    let def = Settings::def("max_bounces").expect("in the parameter table");
    assert_eq!(def.stage, restir_render::settings::Stage::Shading);
    assert_eq!(Settings::default().max_bounces, 1);
    let mut s = Settings::default();
    let warning = s.set_from_str("max_bounces", "20").unwrap();
    assert!(warning.is_some());
    assert_eq!(s.max_bounces, 8);
    s.set_from_str("max_bounces", "0").unwrap();
    assert_eq!(s.max_bounces, 1);
    s.set_from_str("max_bounces", "3").unwrap();
    assert_eq!(s.gpu_params(100).max_bounces, 3);
}
