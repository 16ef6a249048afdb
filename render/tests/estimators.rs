//! The estimators (docs/src/ris.md) agree with closed forms and with each other.
//! All run on lavapipe at tiny sizes; every threshold is justified next to it.

use crate::common;

use glam::Vec3;
use restir_render::metrics::{luma_rmse, rgb_rmse};
use restir_render::{LinearImage, Mode, Settings};

/// Irradiance at `p` (normal `n`) from a uniform Lambertian polygon of radiance 1:
/// E = ½ Σ_i Θ_i · n·normalize(r_i × r_{i+1}) (Lambert's polygon formula), with r_i the unit
/// vectors from p to the vertices in order. The sign makes it positive for a polygon
/// above the surface whichever winding it has.
fn polygon_irradiance(p: Vec3, n: Vec3, vertices: &[Vec3]) -> f32 {
    let r: Vec<Vec3> = vertices.iter().map(|v| (*v - p).normalize()).collect();
    let mut sum = 0.0;
    for i in 0..r.len() {
        let (a, b) = (r[i], r[(i + 1) % r.len()]);
        let theta = a.dot(b).clamp(-1.0, 1.0).acos();
        sum += theta * n.dot(a.cross(b).normalize());
    }
    (0.5 * sum).abs()
}

#[test]
fn reference_matches_the_closed_form_on_the_plane_light() {
    // jitter=false: the reference shades each pixel's rasterised surface point, whose exact
    // position we read back, so the closed form is evaluated at exactly that point.
    let mut r = common::renderer(
        "builtin:plane-light",
        48,
        48,
        Mode::Reference,
        common::settings(&["jitter=false", "reference_spp=128"]),
    );
    let img = common::accumulate(&mut r, 8);
    let surfaces = r.read_surfaces();
    let (albedo, radiance, half) = (0.5, 10.0, 0.1);
    let light = [
        Vec3::new(-half, 1.0, -half),
        Vec3::new(half, 1.0, -half),
        Vec3::new(half, 1.0, half),
        Vec3::new(-half, 1.0, half),
    ];
    let mut checked = 0;
    for (x, y) in [(24, 24), (10, 24), (24, 6), (40, 40), (5, 5), (30, 17)] {
        let s = surfaces[(y * 48 + x) as usize];
        let p = Vec3::from(s.position);
        assert!(
            s.depth > 0.0 && p.y.abs() < 1e-4,
            "pixel ({x},{y}) should see the plane"
        );
        let expected =
            albedo / std::f32::consts::PI * radiance * polygon_irradiance(p, Vec3::Y, &light);
        let got = img.rgb(x, y)[1];
        let rel = (got - expected).abs() / expected;
        // 1 %: the bound this test was set. 1024 light samples of a 0.2 m square at 1–1.4 m
        // distance have a relative standard error of ~0.1 %, so a 1 % miss is a real error.
        assert!(
            rel < 0.01,
            "pixel ({x},{y}) at {p}: {got} vs closed form {expected} ({:.3} %)",
            rel * 100.0
        );
        checked += 1;
    }
    assert_eq!(checked, 6);
}

#[test]
fn nee_and_ris_converge_to_the_reference_on_cornell() {
    let (w, h) = (48, 36);
    let base = ["jitter=false"];
    let mut r = common::renderer(
        "builtin:cornell",
        w,
        h,
        Mode::Reference,
        common::settings(&base),
    );
    let reference = common::reference(&mut r, 16, 256);
    for mode in [Mode::Nee, Mode::Ris] {
        r.set_mode(mode);
        let short = common::accumulate(&mut r, 16);
        let long = common::accumulate(&mut r, 64);
        let ratio = long.mean_luminance() / reference.mean_luminance();
        // 1 %: the bound this test was set; both estimators are unbiased and 64 frames of this
        // scene have a mean-luminance standard error far below 0.1 %.
        assert!(
            (ratio - 1.0).abs() < 0.01,
            "{mode:?}: luminance ratio {ratio}"
        );
        let e_short = rgb_rmse(&short, &reference).unwrap();
        let e_long = rgb_rmse(&long, &reference).unwrap();
        // 4× the frames should halve the error (1/√N). Bounds 0.35–0.65 leave room for
        // the reference's own noise (it makes the ratio drift up towards 1).
        let fall = e_long / e_short;
        assert!(
            (0.35..0.65).contains(&fall),
            "{mode:?}: RMSE {e_short} → {e_long} (ratio {fall})"
        );
    }
}

#[test]
fn ris_beats_nee_per_frame_on_many_lights() {
    let (w, h) = (64, 40);
    let mut r = common::renderer(
        "builtin:many-lights",
        w,
        h,
        Mode::Reference,
        common::settings(&["jitter=false"]),
    );
    let reference = common::reference(&mut r, 8, 64);
    let per_frame = |r: &mut restir_render::Renderer, mode: Mode| -> f64 {
        r.set_mode(mode);
        let mut sum = 0.0;
        for _ in 0..8 {
            r.render_frame().unwrap();
            sum += luma_rmse(&r.read_radiance(), &reference).unwrap();
        }
        sum / 8.0
    };
    let nee = per_frame(&mut r, Mode::Nee);
    let ris = per_frame(&mut r, Mode::Ris);
    // Measured ~4×; demand 2× so reference noise cannot flip it.
    assert!(ris * 2.0 < nee, "ris {ris} vs nee {nee}");
}

#[test]
fn both_real_world_scenes_render_without_nan() {
    let assets = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets");
    for file in [
        "blender-2.79-cornell/cornellBox-2.79-Cycles-gltf.gltf",
        "blender-2.80-cornell/cornellBox-2.80-Eevee-gltf.gltf",
    ] {
        let path = format!("{assets}/{file}");
        for mode in [Mode::Restir, Mode::Reference] {
            let mut r = common::renderer(&path, 48, 36, mode, Settings::default());
            for _ in 0..4 {
                r.render_frame().unwrap();
            }
            let reports = r.collect_reports(true);
            let img: LinearImage = r.read_accumulated();
            assert_eq!(img.non_finite_count(), 0, "{file} {mode:?}");
            assert!(img.mean_luminance() > 0.0, "{file} {mode:?} is black");
            let nonfinite: u64 = reports.iter().map(|r| r.counters.non_finite_total()).sum();
            assert_eq!(
                nonfinite, 0,
                "{file} {mode:?}: passes replaced non-finite values"
            );
        }
    }
}
