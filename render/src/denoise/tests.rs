//! The denoiser's model on synthetic frames: edges survive it, energy does, temporal
//! accumulation converges; each with the planted error it exists to catch.

use glam::{Vec2, Vec3, Vec4};

use super::model::{self, Frame, Params, Pixel, Planted};
use crate::test_hash::hash;

pub(super) const W: u32 = 48;
pub(super) const H: u32 = 32;
const PIXEL_ANGLE: f32 = 0.01;

/// A W × H frame whose surfaces did not move since the last one.
pub(super) fn still_frame<'a>(pixels: &'a [Pixel], radiance: &'a [Vec3]) -> Frame<'a> {
    Frame {
        width: W,
        height: H,
        pixels,
        previous: pixels,
        radiance,
    }
}

pub(super) fn params() -> Params {
    super::settings::model_params(&crate::Settings::default(), PIXEL_ANGLE)
}

/// A wall facing the camera at depth `depth(x)` per column, grey, not moving.
pub(super) fn wall(depth: impl Fn(u32) -> f32) -> Vec<Pixel> {
    let mut out = Vec::new();
    for y in 0..H {
        for x in 0..W {
            let z = depth(x);
            let ray = Vec3::new(
                (x as f32 + 0.5 - W as f32 / 2.0) * PIXEL_ANGLE,
                (y as f32 + 0.5 - H as f32 / 2.0) * PIXEL_ANGLE,
                -1.0,
            );
            out.push(Pixel {
                valid: true,
                position: ray * z,
                depth: z,
                normal: Vec3::Z,
                geo_normal: Vec3::Z,
                base_color: Vec3::splat(0.5),
                emission: Vec3::ZERO,
                throughput: Vec3::ONE,
                motion: Vec2::new(x as f32 + 0.5, y as f32 + 0.5),
            });
        }
    }
    out
}

fn spatial_only(f: &Frame, p: &Params, planted: Planted) -> Vec<Vec4> {
    let h = model::temporal(f, None, None, p);
    let mut filtered = model::variance(f, &h, p);
    for i in 0..p.iterations {
        filtered = model::atrous(f, &filtered, 1 << i, p, planted);
    }
    filtered
}

/// A converged wall with a depth step in the middle, bright on the near side and dark on
/// the far: after filtering, the columns either side of the step keep their brightness
/// within the noise (the planted blur without edge-stopping moves them by far more).
#[test]
fn edges_stop_the_filter_and_a_plain_blur_is_caught() {
    let pixels = wall(|x| if x < W / 2 { 1.0 } else { 3.0 });
    let noise = 0.02;
    let radiance: Vec<Vec3> = (0..W * H)
        .map(|i| {
            let base = if i % W < W / 2 { 0.5 } else { 0.1 };
            Vec3::splat(base * (1.0 + noise * (hash(i, 0) - 0.5)))
        })
        .collect();
    let f = still_frame(&pixels, &radiance);
    let p = params();
    // Mean illumination of the columns next to the step (demodulated: radiance / 0.5).
    let column_means = |filtered: &[Vec4]| {
        let mean = |x: u32| {
            (0..H)
                .map(|y| filtered[(y * W + x) as usize].x)
                .sum::<f32>()
                / H as f32
        };
        (mean(W / 2 - 1), mean(W / 2))
    };
    let (near, far) = column_means(&spatial_only(&f, &p, Planted::default()));
    // The noise is ±1 % of the level: the edge may move the columns by a few times that.
    assert!(
        (near - 1.0).abs() < 0.03,
        "near side at the edge: {near} (expected 1.0)"
    );
    assert!(
        (far - 0.2).abs() < 0.006,
        "far side at the edge: {far} (expected 0.2)"
    );
    let planted = Planted {
        no_edge_stopping: true,
        ..Default::default()
    };
    let (near, far) = column_means(&spatial_only(&f, &p, planted));
    assert!(
        near < 0.9 && far > 0.3,
        "a plain blur must smear the edge: near {near}, far {far}"
    );
}

/// A static wall lit by a heavy-tailed estimator (most frames dim, a few bright, mean 1),
/// denoised frame after frame: the denoised frames' mean stays within 2 % of the input
/// frames'. Gating the luminance by the centre's variance alone loses bright energy (a
/// pixel that just drew a bright sample has a large variance and averages its dark
/// neighbours in, while their small variances keep it out of theirs), and the test sees it.
#[test]
fn filtering_keeps_the_energy_and_a_centre_only_gate_is_caught() {
    let pixels = wall(|_| 2.0);
    let p = params();
    let ratio = |planted: Planted| {
        let (mut input, mut output) = (0.0f64, 0.0f64);
        let mut history: Option<Vec<crate::gpu_types::GpuDenoiseHistory>> = None;
        for frame in 0..48 {
            // 2 % of samples carry 25 × the rest's value: mean 0.98 a + 0.5 a = 1.48 a = 1.
            let a = 1.0 / 1.48;
            let radiance: Vec<Vec3> = (0..W * H)
                .map(|i| Vec3::splat(0.5 * if hash(i, frame) < 0.02 { 25.0 * a } else { a }))
                .collect();
            let f = still_frame(&pixels, &radiance);
            let (h, out) = model::denoise(&f, history.as_deref(), None, &p, planted);
            history = Some(h);
            // After the history has filled (the temporal blend alone is unbiased).
            if frame >= 16 {
                input += radiance.iter().map(|r| r.x as f64).sum::<f64>();
                output += out.iter().map(|r| r.x as f64).sum::<f64>();
            }
        }
        output / input
    };
    // The output is made of the input's own samples, so the ratio carries little of their
    // noise: measured 1.0001 (this gate) and 0.960 (the centre-only gate), and 0.993 /
    // 0.924 with rarer, brighter samples (1 % at 50 ×). 2 % sits between.
    let kept = ratio(Planted::default());
    assert!(
        (kept - 1.0).abs() < 0.02,
        "the filter moved the mean by {:+.2} %",
        (kept - 1.0) * 100.0
    );
    let planted = ratio(Planted {
        centre_variance_gate: true,
        ..Default::default()
    });
    assert!(
        planted < 0.98,
        "a centre-only gate must lose bright energy: kept {planted}"
    );
}

/// A static wall, noisy frames of mean 1: the temporal history converges to the mean
/// (its exponential average is unbiased), its length to the cap, and the moments'
/// variance to the noise's.
#[test]
fn temporal_accumulation_converges_to_the_mean() {
    let pixels = wall(|_| 2.0);
    let p = params();
    let mut history: Option<Vec<crate::gpu_types::GpuDenoiseHistory>> = None;
    for frame in 0..64 {
        // Uniform in [0, 2] (mean 1, variance 1/3), demodulated by 0.5.
        let radiance: Vec<Vec3> = (0..W * H).map(|i| Vec3::splat(hash(i, frame))).collect();
        let f = still_frame(&pixels, &radiance);
        history = Some(model::temporal(&f, history.as_deref(), None, &p));
    }
    let h = history.unwrap();
    let mean = h.iter().map(|p| p.illumination[0] as f64).sum::<f64>() / h.len() as f64;
    // Each pixel averages ~2/α − 1 = 9 frames of variance 1/3 (σ 0.19 each), over 1536
    // pixels: the image mean's σ is ~0.005; 0.03 is six of those.
    assert!((mean - 1.0).abs() < 0.03, "history mean {mean}");
    assert!(h.iter().all(|p| p.length == p_cap(&p)));
    let var = h
        .iter()
        .map(|p| (p.moments[1] - p.moments[0] * p.moments[0]) as f64)
        .sum::<f64>()
        / h.len() as f64;
    assert!(
        (var - 1.0 / 3.0).abs() < 0.08,
        "moments' variance {var} (noise 1/3)"
    );

    fn p_cap(_: &crate::gpu_types::GpuDenoiseHistory) -> f32 {
        crate::Settings::default().denoise_history_cap as f32
    }
}

/// A history read without reprojection under motion leaves a trail: a bright square moved
/// 2 px right per frame is, after reprojection, where it is now and nowhere else.
#[test]
fn reprojection_follows_the_motion() {
    let p = params();
    let square = |frame: u32, x: u32, y: u32| {
        let x0 = 8 + 2 * frame;
        (x0..x0 + 6).contains(&x) && (12..18).contains(&y)
    };
    let mut history: Option<Vec<crate::gpu_types::GpuDenoiseHistory>> = None;
    let frames = 8;
    for frame in 0..frames {
        // A wall seen by a camera panning left: the point at pixel x was at x − 2 last
        // frame. The lighting is painted on the wall, so it moves with it.
        let mut pixels = wall(|_| 2.0);
        for (i, px) in pixels.iter_mut().enumerate() {
            let (x, y) = (i as u32 % W, i as u32 / W);
            px.motion = Vec2::new(x as f32 - 2.0 + 0.5, y as f32 + 0.5);
        }
        let radiance: Vec<Vec3> = (0..W * H)
            .map(|i| {
                Vec3::splat(if square(frame, i % W, i / W) {
                    1.0
                } else {
                    0.05
                })
            })
            .collect();
        let f = still_frame(&pixels, &radiance);
        history = Some(model::temporal(&f, history.as_deref(), None, &p));
    }
    let h = history.unwrap();
    // Where the square was two frames ago but is not now: 0.1 (dark, demodulated).
    let behind = h[(14 * W + 8 + 2 * (frames - 3)) as usize].illumination[0];
    assert!(
        (behind - 0.1).abs() < 1e-3,
        "trail behind the square: {behind}"
    );
}

/// Pixels without a surface pass through; finite in, finite out for extreme inputs.
#[test]
fn the_sky_passes_through_and_extremes_stay_finite() {
    let mut pixels = wall(|x| if x % 7 == 0 { 1e-4 } else { 1e4 });
    for px in pixels.iter_mut().step_by(5) {
        px.valid = false;
    }
    let radiance: Vec<Vec3> = (0..W * H)
        .map(|i| {
            Vec3::splat(if i % 3 == 0 {
                1e30
            } else if i % 3 == 1 {
                0.0
            } else {
                1e-30
            })
        })
        .collect();
    let f = still_frame(&pixels, &radiance);
    let (h, out) = model::denoise(&f, None, None, &params(), Planted::default());
    let (_, out2) = model::denoise(&f, Some(&h), None, &params(), Planted::default());
    for (i, (a, b)) in out.iter().zip(&out2).enumerate() {
        assert!(a.is_finite() && b.is_finite(), "pixel {i}: {a} {b}");
        if !pixels[i].valid {
            assert_eq!(*a, radiance[i]);
        }
    }
}
