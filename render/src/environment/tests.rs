//! The environment's CPU side: the direction convention, the sampling distribution (pdf
//! normalised, ∝ luminance × solid angle, matched by a histogram of drawn directions, and
//! a planted sin θ omission caught by the same checks) and every kind of bad input.

use std::f64::consts::PI;

use glam::Vec3;

use super::distribution::{Weighting, texel_solid_angle};
use super::*;
use crate::image::luminance;
use crate::reservoir::test_support::{Rng, assert_chi_square};

/// A 32×16 test image: a gradient, a bright spot and a black band, so rows, columns and
/// zero-luminance texels all matter.
fn test_texels(w: u32, h: u32) -> Vec<[f32; 3]> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            if y == h / 2 {
                return [0.0; 3];
            }
            let spot = if (x, y) == (w / 4, h / 4) { 500.0 } else { 0.0 };
            [0.2 + x as f32 / w as f32 + spot, 0.5 + y as f32 * 0.1, 1.0]
        })
        .collect()
}

fn uniform6(rng: &mut Rng) -> [f32; 6] {
    std::array::from_fn(|_| rng.f32())
}

#[test]
fn convention_centre_faces_plus_x_and_top_row_is_the_zenith() {
    let none = [1.0, 0.0];
    let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-5;
    assert!(close(uv_to_direction([0.5, 0.5], none), Vec3::X));
    assert!(close(uv_to_direction([0.75, 0.5], none), Vec3::Z));
    assert!(close(uv_to_direction([0.25, 0.5], none), Vec3::NEG_Z));
    assert!(close(uv_to_direction([0.3, 0.0], none), Vec3::Y));
    assert!(close(uv_to_direction([0.3, 1.0], none), Vec3::NEG_Y));
    // +90° about +Y turns the image centre from +X to −Z (right-handed).
    let quarter = [0.0, 1.0]; // (cos 90°, sin 90°)
    assert!(close(uv_to_direction([0.5, 0.5], quarter), Vec3::NEG_Z));
    let mut rng = Rng::new(3);
    for _ in 0..1000 {
        let rot = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
        let n = (rot[0] * rot[0] + rot[1] * rot[1]).sqrt().max(1e-3);
        let rot = [rot[0] / n, rot[1] / n];
        let uv = [rng.range(0.001, 0.999), rng.range(0.01, 0.99)];
        let back = direction_to_uv(uv_to_direction(uv, rot), rot);
        assert!((back[0] - uv[0]).abs() < 1e-4 && (back[1] - uv[1]).abs() < 1e-4);
    }
}

#[test]
fn pdf_integrates_to_one_and_is_luminance_over_its_integral() {
    let (w, h) = (32, 16);
    let texels = test_texels(w, h);
    let d = EnvDistribution::build(w, h, &texels);
    // Piecewise constant per texel: the integral over the sphere is exact as a sum.
    let mut integral = 0.0;
    for y in 0..h {
        for x in 0..w {
            integral += d.table[(y * w + x) as usize].pdf as f64 * texel_solid_angle(y, w, h);
        }
    }
    assert!((integral - 1.0).abs() < 1e-5, "∫ pdf dω = {integral}");
    // The same integral by Monte Carlo over uniform directions, as a check of `pdf(uv)`.
    let mut rng = Rng::new(1);
    let n = 200_000;
    let mut sum = 0.0;
    for _ in 0..n {
        let z = rng.range(-1.0, 1.0);
        let phi = rng.range(0.0, std::f32::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let dir = Vec3::new(r * phi.cos(), z, r * phi.sin());
        sum += d.pdf(direction_to_uv(dir, [1.0, 0.0])) as f64 * 4.0 * PI;
    }
    // The spot texel holds most of the mass in 1/512 of the sphere: the estimate's
    // relative standard error is ~√(512/n) ≈ 5 %, so 25 % is a 5σ bound.
    assert!(
        (sum / n as f64 - 1.0).abs() < 0.25,
        "MC ∫ pdf = {}",
        sum / n as f64
    );
    for (i, t) in texels.iter().enumerate() {
        let expected = luminance(*t) as f64 / d.integral;
        let got = d.table[i].pdf as f64;
        assert!(
            (got - expected).abs() <= 1e-5 * expected.max(1e-12),
            "texel {i}"
        );
    }
}

/// χ² of drawn directions against the intended density luminance / ∫ luminance dω, in
/// bins of one texel; panics (through `assert_chi_square`) when they disagree.
fn assert_histogram_matches_luminance(d: &EnvDistribution, texels: &[[f32; 3]], n: usize) {
    let (w, h) = (d.width, d.height);
    let integral: f64 = (0..texels.len())
        .map(|i| luminance(texels[i]) as f64 * texel_solid_angle(i as u32 / w, w, h))
        .sum();
    let probs: Vec<f64> = (0..texels.len())
        .map(|i| luminance(texels[i]) as f64 * texel_solid_angle(i as u32 / w, w, h) / integral)
        .collect();
    let mut counts = vec![0u64; texels.len()];
    let mut rng = Rng::new(7);
    for _ in 0..n {
        let s = d.sample(uniform6(&mut rng));
        let (x, y) = texel_of(s.uv, w, h);
        counts[(y * w + x) as usize] += 1;
        assert!(s.pdf > 0.0, "a drawn direction has pdf 0 at {:?}", s.uv);
    }
    assert_chi_square(&counts, &probs);
}

#[test]
fn drawn_directions_follow_luminance_times_solid_angle() {
    let (w, h) = (32, 16);
    let texels = test_texels(w, h);
    assert_histogram_matches_luminance(&EnvDistribution::build(w, h, &texels), &texels, 400_000);
}

#[test]
fn a_planted_sin_theta_omission_is_caught() {
    // Test power: the same histogram check must reject a distribution that weights
    // texels by luminance alone (poles oversampled). A uniform sky makes it stark.
    let (w, h) = (32, 16);
    let texels = vec![[1.0f32; 3]; (w * h) as usize];
    assert_histogram_matches_luminance(&EnvDistribution::build(w, h, &texels), &texels, 200_000);
    let planted = EnvDistribution::build_with(w, h, &texels, Weighting::PerTexel);
    let caught = std::panic::catch_unwind(|| {
        assert_histogram_matches_luminance(&planted, &texels, 200_000);
    });
    assert!(
        caught.is_err(),
        "the χ² check missed a distribution without sin θ"
    );
    // And its pdf is no longer luminance / ∫ L: the per-texel check above would fail too.
    let l_over_integral = 1.0 / (4.0 * PI);
    let worst = planted
        .table
        .iter()
        .take((w * h) as usize)
        .map(|t| (t.pdf as f64 / l_over_integral - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst > 1.0, "pdf deviates by only {worst}");
}

#[test]
fn builtin_sky_is_finite_with_a_sun_far_brighter_than_the_sky() {
    let sky = load_environment("builtin:sky").unwrap();
    assert_eq!((sky.width, sky.height), (512, 256));
    assert!(
        sky.texels
            .iter()
            .flatten()
            .all(|c| c.is_finite() && *c >= 0.0)
    );
    let lum: Vec<f32> = sky.texels.iter().map(|t| luminance(*t)).collect();
    let max = lum.iter().cloned().fold(0.0, f32::max);
    let mean = lum.iter().sum::<f32>() / lum.len() as f32;
    assert!(max > 100.0 * mean, "sun {max} vs mean {mean}");
    // The sun is above the horizon, in the +X/+Z quadrant.
    let i = lum.iter().position(|&l| l == max).unwrap() as u32;
    let dir = uv_to_direction(
        [(i % 512) as f32 / 512.0, (i / 512) as f32 / 256.0],
        [1.0, 0.0],
    );
    assert!(dir.y > 0.4 && dir.x > 0.0 && dir.z > 0.0, "sun at {dir}");
}

fn temp_file(name: &str, bytes: &[u8]) -> String {
    let dir = std::env::temp_dir().join(format!("restir-env-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.to_string_lossy().into_owned()
}

fn exr_bytes(w: u32, h: u32, texels: &[[f32; 3]]) -> Vec<u8> {
    let flat: Vec<f32> = texels.iter().flatten().copied().collect();
    let img = image::Rgb32FImage::from_raw(w, h, flat).unwrap();
    let mut out = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb32F(img)
        .write_to(&mut out, image::ImageFormat::OpenExr)
        .unwrap();
    out.into_inner()
}

fn hdr_bytes(w: u32, h: u32, texels: &[[f32; 3]]) -> Vec<u8> {
    let mut out = Vec::new();
    let pixels: Vec<image::Rgb<f32>> = texels.iter().map(|t| image::Rgb(*t)).collect();
    image::codecs::hdr::HdrEncoder::new(&mut out)
        .encode(&pixels, w as usize, h as usize)
        .unwrap();
    out
}

/// The error for `path`: one line, starting with the file, containing `what`.
fn assert_fails(path: &str, what: &str) {
    let e = load_environment(path).unwrap_err().to_string();
    assert!(e.starts_with(path), "'{e}' does not start with {path}");
    assert!(e.contains(what), "'{e}' does not say '{what}'");
    assert!(!e.contains('\n'), "'{e}' is more than one line");
}

#[test]
fn good_hdr_and_exr_files_load_with_the_same_texels() {
    let texels = test_texels(8, 4);
    let exr = load_environment(&temp_file("ok.exr", &exr_bytes(8, 4, &texels))).unwrap();
    assert_eq!((exr.width, exr.height), (8, 4));
    assert_eq!(exr.texels, texels);
    let hdr = load_environment(&temp_file("ok.hdr", &hdr_bytes(8, 4, &texels))).unwrap();
    // RGBE shares one exponent: 8 mantissa bits relative to the texel's largest channel.
    for (a, b) in hdr.texels.iter().zip(&texels) {
        let max = b.iter().cloned().fold(0.0, f32::max);
        for c in 0..3 {
            assert!((a[c] - b[c]).abs() <= max / 128.0, "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn bad_environment_files_fail_with_one_line_naming_the_file() {
    assert_fails("/no/such/sky.hdr", "cannot read");
    assert_fails(&temp_file("empty.hdr", b""), "empty");
    let hdr = hdr_bytes(8, 4, &test_texels(8, 4));
    assert_fails(
        &temp_file("truncated.hdr", &hdr[..hdr.len() / 2]),
        "cannot decode",
    );
    let exr = exr_bytes(8, 4, &test_texels(8, 4));
    assert_fails(
        &temp_file("truncated.exr", &exr[..exr.len() / 2]),
        "cannot decode",
    );
    // The decoder or our own check refuses a 0×0 image; either way it is named.
    let zero = temp_file(
        "zero.hdr",
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n",
    );
    let e = load_environment(&zero).unwrap_err().to_string();
    assert!(
        e.starts_with(&zero) && (e.contains("zero size") || e.contains("cannot decode")),
        "{e}"
    );
    println!("{e}");
    let mut nan = test_texels(8, 4);
    nan[9][1] = f32::NAN;
    nan[12][0] = f32::INFINITY;
    assert_fails(
        &temp_file("nan.exr", &exr_bytes(8, 4, &nan)),
        "2 texels are not finite, the first at (1, 1)",
    );
    let mut negative = test_texels(8, 4);
    negative[3][2] = -1.0;
    assert_fails(
        &temp_file("negative.exr", &exr_bytes(8, 4, &negative)),
        "negative",
    );
    assert_fails(
        &temp_file("sky.png", b"not an hdr"),
        "expected .hdr or .exr",
    );
    assert_fails("builtin:nope", "unknown built-in environment");
}

#[test]
fn strength_and_rotation_are_checked() {
    let sky = load_environment("builtin:sky").unwrap();
    assert!(
        sky.clone()
            .with_strength_and_rotation(f32::NAN, 0.0)
            .is_err()
    );
    assert!(sky.clone().with_strength_and_rotation(-1.0, 0.0).is_err());
    assert!(
        sky.clone()
            .with_strength_and_rotation(1.0, f32::INFINITY)
            .is_err()
    );
    let e = sky.with_strength_and_rotation(2.0, 90.0).unwrap();
    let [c, s] = e.rotation_cos_sin();
    assert!(c.abs() < 1e-6 && (s - 1.0).abs() < 1e-6);
}

#[test]
fn oversized_images_are_halved_until_they_fit() {
    let texels = vec![[1.0f32, 2.0, 3.0]; 16 * 8];
    let (w, h, out) = load::fit_to("big.exr", 16, 8, texels, 20);
    assert_eq!((w, h), (4, 2));
    assert!(out.iter().all(|t| *t == [1.0, 2.0, 3.0]));
}
