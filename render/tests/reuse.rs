//! Issue "ReSTIR DI core, part 2": temporal and spatial reuse lower the error, stay within
//! their documented bias, record their rejections faithfully and keep M within its cap.
//!
//! Sizes are tiny (lavapipe on two cores). The spatial radius default, 30 px, is meant for
//! ~1080p; at 128 px wide it would reach across a quarter of the image, so these tests
//! scale it with the width: 8 px at 128, 6 px at 96 (README, "Measured bias and settings
//! at small sizes").

mod common;

use restir_render::gpu_types::GpuPixelDebug;
use restir_render::shader_constants::*;
use restir_render::{Mode, Renderer};

const SMALL_RADIUS: &str = "spatial_radius=8";

/// The spatial radius for a test image `width` pixels wide (8 px per 128).
fn radius_for(width: u32) -> String {
    format!("spatial_radius={}", (width / 16).max(4))
}

fn temporal_merged(d: &[GpuPixelDebug]) -> usize {
    d.iter()
        .filter(|p| p.flags & DEBUG_FLAG_TEMPORAL_MERGED != 0)
        .count()
}

#[test]
fn temporal_then_spatial_lower_per_frame_error_on_many_lights() {
    let mut r = common::renderer(
        "builtin:many-lights",
        128,
        80,
        Mode::Reference,
        common::settings(&["jitter=false", SMALL_RADIUS]),
    );
    let reference = common::reference(&mut r, 8, 64);
    let mut measure = |assign: &[&str]| {
        r.set_settings(common::settings(
            &[&["jitter=false", SMALL_RADIUS][..], assign].concat(),
        ));
        r.set_mode(Mode::Restir);
        common::per_frame_errors(&mut r, &reference, 24)
    };
    let (ris, ris_stability) = measure(&["temporal=false", "spatial=false"]);
    let (temporal, temporal_stability) = measure(&["spatial=false"]);
    let (both, _) = measure(&[]);
    eprintln!(
        "per-frame luma RMSE: ris {ris:.4}, +temporal {temporal:.4}, +spatial {both:.4}; stability {ris_stability:.4} → {temporal_stability:.4}"
    );
    // Measured (lavapipe): 0.387 → 0.313 → 0.270, stability 0.544 → 0.352. Each step must
    // win by 5 %: enough above run-to-run noise at 24 frames, with the same reference
    // noise in every number (it adds Var_ref to each MSE and cannot reorder them).
    assert!(temporal < ris * 0.95, "temporal {temporal} vs ris {ris}");
    assert!(
        both < temporal * 0.95,
        "temporal+spatial {both} vs temporal {temporal}"
    );
    assert!(
        temporal_stability < ris_stability * 0.95,
        "stability {temporal_stability} vs {ris_stability}"
    );
}

/// Accumulated bias of the default 1/M ReSTIR against the reference.
fn restir_luminance_ratio(scene: &str, size: (u32, u32), extra: &[&str]) -> f64 {
    let radius = radius_for(size.0);
    let assign = [&["jitter=false", radius.as_str()][..], extra].concat();
    let mut r = common::renderer(
        scene,
        size.0,
        size.1,
        Mode::Reference,
        common::settings(&assign),
    );
    let reference = common::reference(&mut r, 8, 64);
    r.set_mode(Mode::Restir);
    r.request_cut();
    let img = common::accumulate(&mut r, 64);
    img.mean_luminance() / reference.mean_luminance()
}

#[test]
fn accumulated_restir_stays_within_five_percent_of_the_reference() {
    for (scene, size) in [
        ("builtin:cornell", (64, 48)),
        ("builtin:many-lights", (96, 60)),
    ] {
        let ratio = restir_luminance_ratio(scene, size, &[]);
        eprintln!("{scene}: restir (1/M) mean luminance / reference = {ratio:.4}");
        // 5 %: the bound for the biased 1/M estimator. Measured: cornell 0.99,
        // many-lights 0.957 — darkening where a sample visible at the pixel that found it
        // (visibility reuse) is occluded at the pixel that reuses it while its M still
        // counts; without initial visibility it is 0.99 (README, "Measured bias").
        assert!((ratio - 1.0).abs() < 0.05, "{scene}: ratio {ratio}");
    }
}

#[test]
fn pairwise_mis_is_closer_to_unbiased_than_one_over_m() {
    let one_over_m = restir_luminance_ratio("builtin:many-lights", (96, 60), &[]);
    let pairwise = restir_luminance_ratio(
        "builtin:many-lights",
        (96, 60),
        &["bias_correction=pairwise"],
    );
    eprintln!("luminance ratio: 1/M {one_over_m:.4}, pairwise {pairwise:.4}");
    assert!(
        (pairwise - 1.0).abs() < (one_over_m - 1.0).abs(),
        "pairwise {pairwise} vs 1/M {one_over_m}"
    );
    // Pairwise MIS with unshadowed cross terms is unbiased up to the (documented) bias of
    // visibility reuse; 2 % covers that plus the reference's noise.
    assert!((pairwise - 1.0).abs() < 0.02, "pairwise {pairwise}");
}

fn warm_up(r: &mut Renderer, frames: u32) {
    for _ in 0..frames {
        r.render_frame().unwrap();
    }
}

#[test]
fn a_camera_cut_rejects_every_temporal_sample() {
    let mut r = common::renderer(
        "builtin:cornell",
        64,
        48,
        Mode::Restir,
        common::settings(&[]),
    );
    warm_up(&mut r, 4);
    assert!(
        temporal_merged(&r.read_debug()) > 0,
        "a static camera should reuse history"
    );
    let camera = r.camera();
    r.set_camera(restir_render::Camera::look_at(
        camera.position + glam::Vec3::new(0.5, 0.3, -1.5),
        glam::Vec3::new(0.0, 1.0, 0.0),
        camera.yfov,
    ));
    r.request_cut();
    r.render_frame().unwrap();
    let debug = r.read_debug();
    let surfaces = r.read_surfaces();
    let lit: Vec<_> = debug
        .iter()
        .zip(&surfaces)
        .filter(|(_, s)| s.depth > 0.0)
        .map(|(d, _)| d)
        .collect();
    let invalid = lit
        .iter()
        .filter(|d| d.temporal_mask & (REJECT_OFFSCREEN | REJECT_SURFACE) != 0)
        .count();
    assert!(
        invalid as f64 >= 0.99 * lit.len() as f64,
        "{invalid} of {} pixels flagged",
        lit.len()
    );
    assert_eq!(temporal_merged(&debug), 0);
    let reports = r.collect_reports(true);
    let last = reports.last().unwrap();
    assert_eq!(last.counters.get(STAT_TEMPORAL_ACCEPTED), 0);
    assert_eq!(last.counters.get(STAT_SOURCE + SOURCE_TEMPORAL), 0);
}

#[test]
fn turning_a_check_off_removes_its_bit_everywhere() {
    for (param, bit) in [
        ("check_surface", REJECT_SURFACE),
        ("check_depth", REJECT_DEPTH),
        ("check_normal", REJECT_NORMAL),
    ] {
        let mut r = common::renderer(
            "builtin:many-lights",
            64,
            40,
            Mode::Restir,
            common::settings(&[]),
        );
        warm_up(&mut r, 2);
        // An orbit and a cut produce plenty of every geometric rejection.
        r.set_camera(restir_render::Camera {
            yfov: r.camera().yfov,
            ..r.camera()
        });
        let cam = r.camera();
        r.set_camera(restir_render::Camera::look_at(
            cam.position + cam.right() * 1.0,
            cam.position + cam.forward() * 3.0,
            cam.yfov,
        ));
        r.request_cut();
        r.render_frame().unwrap();
        let with: usize = r
            .read_debug()
            .iter()
            .filter(|d| d.temporal_mask & bit != 0)
            .count();
        r.set_settings(common::settings(&[&format!("{param}=false")]));
        warm_up(&mut r, 2);
        let cam = r.camera();
        r.set_camera(restir_render::Camera::look_at(
            cam.position - cam.right() * 1.0,
            cam.position + cam.forward() * 3.0,
            cam.yfov,
        ));
        r.request_cut();
        r.render_frame().unwrap();
        let debug = r.read_debug();
        let without = debug
            .iter()
            .filter(|d| d.temporal_mask & bit != 0 || d.spatial_mask & bit != 0)
            .count();
        assert!(
            with > 0 || bit != REJECT_SURFACE,
            "{param}: the cut should set the bit first"
        );
        assert_eq!(
            without, 0,
            "{param}=false still sets its bit on {without} pixels"
        );
    }
}

#[test]
fn target_ratio_clamp_one_rejects_every_changed_target() {
    // Static camera, no jitter, no permutation: every pixel re-reads its own history at
    // the same surface point, so the re-evaluated target equals the stored one bit for
    // bit and clamp 1 accepts. Then an orbit changes every target: clamp 1 rejects all.
    let base = [
        "jitter=false",
        "permutation=false",
        "target_ratio_clamp=1",
        "spatial=false",
    ];
    let mut r = common::renderer(
        "builtin:cornell",
        64,
        48,
        Mode::Restir,
        common::settings(&base),
    );
    warm_up(&mut r, 3);
    let debug = r.read_debug();
    let ratio_rejected = debug
        .iter()
        .filter(|d| d.temporal_mask & REJECT_TARGET_RATIO != 0)
        .count();
    assert_eq!(ratio_rejected, 0, "unchanged targets must pass clamp 1");
    assert!(temporal_merged(&debug) > 0);

    let center = r.scene_bounds().center();
    let cam = r.camera();
    let q = glam::Quat::from_rotation_y(2f32.to_radians());
    r.set_camera(restir_render::Camera {
        position: center + q * (cam.position - center),
        rotation: q * cam.rotation,
        yfov: cam.yfov,
    });
    r.render_frame().unwrap();
    let debug = r.read_debug();
    assert_eq!(
        temporal_merged(&debug),
        0,
        "every target changed, clamp 1 must reject every temporal sample"
    );
    let only_ratio = debug
        .iter()
        .filter(|d| d.temporal_mask == REJECT_TARGET_RATIO)
        .count();
    assert!(
        only_ratio > 100,
        "the ratio test should be what rejects ({only_ratio} pixels)"
    );
}

#[test]
fn m_never_exceeds_its_cap_and_nothing_is_non_finite() {
    for cap in ["0", "1", "5", "20"] {
        let mut r = common::renderer(
            "builtin:many-lights",
            48,
            32,
            Mode::Restir,
            common::settings(&[&format!("m_cap={cap}"), "spatial_passes=2"]),
        );
        warm_up(&mut r, 6);
        let cap: f32 = cap.parse().unwrap();
        for d in r.read_debug() {
            for m in [d.m_initial, d.m_temporal, d.m_spatial] {
                assert!(m.is_finite() && m <= cap.max(1.0), "M {m} with cap {cap}");
            }
            assert!(
                d.m_temporal <= cap && d.m_spatial <= cap,
                "M after reuse above cap {cap}"
            );
        }
        for res in r.read_final_reservoirs() {
            assert!(
                res.m <= cap
                    && res.weight.is_finite()
                    && res.w_sum.is_finite()
                    && res.p_hat.is_finite()
            );
        }
        let img = r.read_radiance();
        assert_eq!(img.non_finite_count(), 0);
        let nonfinite: u64 = r
            .collect_reports(true)
            .iter()
            .map(|r| r.counters.non_finite_total())
            .sum();
        assert_eq!(nonfinite, 0, "cap {cap}");
    }
}

/// CPU visibility of scene points from a camera position, with the renderer's own BVH
/// builder and an independent traversal (scene/bvh/traverse.rs).
struct CpuVisibility {
    bvh: restir_render::scene::bvh::Bvh,
    triangles: Vec<[glam::Vec3; 3]>,
}

impl CpuVisibility {
    fn new(scene: &restir_render::Scene) -> CpuVisibility {
        let soup: Vec<[glam::Vec3; 3]> = (0..scene.triangles.len())
            .map(|t| scene.triangle_positions(t))
            .collect();
        let bvh = restir_render::scene::bvh::Bvh::build(&soup);
        let triangles = bvh
            .triangle_order
            .iter()
            .map(|&i| soup[i as usize])
            .collect();
        CpuVisibility { bvh, triangles }
    }

    /// True when nothing blocks the segment from `p` (nudged along `n`) to `eye`.
    fn visible(&self, p: glam::Vec3, n: glam::Vec3, eye: glam::Vec3, scale: f32) -> bool {
        let origin = p + n * scale * 1e-4;
        let ray = restir_render::scene::bvh::Ray {
            origin,
            dir: eye - origin,
            t_max: 0.999,
        };
        !self.bvh.any_hit(&self.triangles, &ray)
    }
}

#[test]
fn moving_camera_keeps_temporal_gains_and_rejects_only_at_disocclusions() {
    let (w, h) = (96, 60);
    let scene = restir_render::load_scene("builtin:many-lights").unwrap();
    let base = ["jitter=false", SMALL_RADIUS, "spatial=false"];
    let make = |extra: &[&str], mode: Mode| {
        let mut r = Renderer::new(
            common::gpu(),
            &scene,
            w,
            h,
            common::settings(&[&base[..], extra].concat()),
        )
        .unwrap();
        r.set_mode(mode);
        r
    };
    let mut reference = make(&["reference_spp=64"], Mode::Reference);
    let mut with_temporal = make(&[], Mode::Restir);
    let mut without = make(&["temporal=false"], Mode::Restir);
    let cpu = CpuVisibility::new(&scene);
    let center = reference.scene_bounds().center();
    let start = reference.camera();
    let scale = reference.scene_scale();
    let (mut err_with, mut err_without) = (0.0, 0.0);
    let (mut false_rejections, mut surface_pixels) = (0usize, 0usize);
    let frames = 10;
    let mut prev_camera: Option<restir_render::Camera> = None;
    let mut prev_surfaces: Vec<restir_render::gpu_types::GpuSurface> = Vec::new();
    for f in 0..frames {
        // 1° of orbit per frame about the room's vertical axis.
        let q = glam::Quat::from_rotation_y((f as f32).to_radians());
        let pivot = glam::Vec3::new(center.x, start.position.y, center.z);
        let camera = restir_render::Camera {
            position: pivot + q * (start.position - pivot),
            rotation: q * start.rotation,
            yfov: start.yfov,
        };
        for r in [&mut reference, &mut with_temporal, &mut without] {
            r.set_camera(camera);
            r.reset_accumulation();
            r.render_frame().unwrap();
        }
        let truth = reference.read_radiance();
        if f >= 2 {
            err_with +=
                restir_render::metrics::luma_rmse(&with_temporal.read_radiance(), &truth).unwrap();
            err_without +=
                restir_render::metrics::luma_rmse(&without.read_radiance(), &truth).unwrap();
        }
        // Every pixel whose temporal candidate failed a geometric check must be a point
        // the previous camera could not see (occluded or outside its view).
        if let (Some(prev), true) = (prev_camera, f >= 1) {
            let view_proj =
                prev.projection_matrix(w as f32 / h as f32, scale * 1e-5) * prev.view_matrix();
            let geometric =
                REJECT_OFFSCREEN | REJECT_SURFACE | REJECT_MATERIAL | REJECT_NORMAL | REJECT_DEPTH;
            for (d, s) in with_temporal
                .read_debug()
                .iter()
                .zip(with_temporal.read_surfaces())
            {
                if s.depth <= 0.0 {
                    continue;
                }
                surface_pixels += 1;
                if d.temporal_mask & geometric == 0 {
                    continue;
                }
                let p = glam::Vec3::from(s.position);
                let clip = view_proj * p.extend(1.0);
                let ndc = clip.truncate() / clip.w;
                // A margin of two pixels: points within it may legitimately reproject
                // off-screen or onto the neighbouring surface.
                let margin = glam::Vec2::new(4.0 / w as f32, 4.0 / h as f32);
                let inside =
                    clip.w > 0.0 && ndc.x.abs() < 1.0 - margin.x && ndc.y.abs() < 1.0 - margin.y;
                let normal = (prev.position - p).normalize();
                // Away from edges: the previous frame shows this surface's material all
                // around the reprojected position. At an edge (a light in front of the
                // ceiling covering part of a pixel, say) the centre sample legitimately
                // saw another surface.
                let (qx, qy) = (
                    ((ndc.x * 0.5 + 0.5) * w as f32) as i32,
                    ((0.5 - ndc.y * 0.5) * h as f32) as i32,
                );
                let same_surface_around = (-1..=1).all(|dy| {
                    (-1..=1).all(|dx| {
                        let (x, y) = (
                            (qx + dx).clamp(0, w as i32 - 1),
                            (qy + dy).clamp(0, h as i32 - 1),
                        );
                        let q = &prev_surfaces[(y as u32 * w + x as u32) as usize];
                        q.depth > 0.0 && q.material == s.material
                    })
                });
                if inside && same_surface_around && cpu.visible(p, normal, prev.position, scale) {
                    false_rejections += 1;
                }
            }
        }
        prev_camera = Some(camera);
        prev_surfaces = with_temporal.read_surfaces();
    }
    let (err_with, err_without) = (
        err_with / (frames - 2) as f64,
        err_without / (frames - 2) as f64,
    );
    let false_fraction = false_rejections as f64 / surface_pixels as f64;
    eprintln!(
        "orbit 1°/frame: per-frame luma RMSE {err_with:.4} with temporal, {err_without:.4} without; geometric rejections of points the previous camera saw: {:.2} %",
        false_fraction * 100.0
    );
    assert!(
        err_with < err_without,
        "temporal {err_with} vs {err_without}"
    );
    // Measured ~0.1 %: what remains are grazing floor pixels whose neighbour in the previous
    // frame is further away than the depth threshold. 1 % would mean the checks reject
    // visible, interior history.
    assert!(
        false_fraction < 0.01,
        "{:.2} % of pixels rejected although visible before",
        false_fraction * 100.0
    );
}
