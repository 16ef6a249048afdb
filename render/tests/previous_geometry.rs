//! The temporal MIS term of this pixel's own sample at the previous pixel is
//! traced against last frame's geometry (`previous_geometry`): last frame's TLAS with ray
//! queries, last frame's BVH boxes and triangles with the software backend. Against this
//! frame's geometry (the shortcut before, kept as the setting's off state and as the planted
//! twin here) a moving occluder credits the previous pixel with samples it could not see,
//! and the image comes out dark: `builtin:dynamic:moving-occluder` was 0.980 of its
//! per-frame references (docs/src/measured/unbiased-reuse.md, "Animated scenes").
//!
//! The detector: the blade turning at 10 frames per second (9° a frame, three times the
//! 30-fps sweep of docs/src/measured/unbiased-reuse.md, so the bias is larger than at 30 fps and
//! the test can stay small), restir's running average over the frames against the average of
//! per-frame references, for both backends. Needs a device with ray queries
//! (docs/src/getting-started.md, "A machine without a GPU").

use crate::common;

use restir_render::timeline::AnimatedScene;
use restir_render::{LinearImage, Mode, Renderer, Settings, load_scene};

const SCENE: &str = "builtin:dynamic:moving-occluder";
const SIZE: (u32, u32) = (48, 32);
const START: f32 = 0.3;
const FPS: f32 = 10.0;
const FRAMES: u32 = 12;
const SEEDS: [u32; 2] = [1, 2];

fn time_of(frame: u32) -> f32 {
    START + frame as f32 / FPS
}

fn scene_at(time: f32) -> AnimatedScene {
    let mut scene = AnimatedScene::new(load_scene(SCENE).unwrap_or_else(|e| panic!("{e}")));
    scene.pose_only(time);
    scene
}

fn renderer(scene: &AnimatedScene, settings: Settings) -> Renderer {
    let gpu = common::gpu();
    assert!(
        gpu.ray_query,
        "this test traces with both backends and needs ray queries \
         (docs/src/getting-started.md, \"A machine without a GPU\")"
    );
    Renderer::new(gpu, scene.scene(), SIZE.0, SIZE.1, settings).unwrap_or_else(|e| panic!("{e:#}"))
}

/// The mean luminance of the per-frame references over the FRAMES frames (64 spp each).
fn reference_mean() -> f64 {
    static MEAN: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    *MEAN.get_or_init(|| {
        let mut scene = scene_at(START);
        let mut r = renderer(
            &scene,
            common::settings(&["jitter=false", "ray_backend=software"]),
        );
        let mut sum = 0.0;
        for frame in 0..FRAMES {
            scene.set_time(&mut r, time_of(frame));
            sum += common::reference(&mut r, 4, 16).mean_luminance();
        }
        sum / FRAMES as f64
    })
}

/// restir's mean luminance over the frames, averaged over the seeds, over the references'.
fn restir_ratio(backend: &str, previous_geometry: bool) -> f64 {
    let mut sum = 0.0;
    for seed in SEEDS {
        let mut scene = scene_at(START);
        let settings = common::settings(&[
            "jitter=false",
            &format!("ray_backend={backend}"),
            &format!("previous_geometry={previous_geometry}"),
        ]);
        let mut r = renderer(&scene, settings);
        r.set_mode(Mode::Restir);
        r.set_seed(seed);
        let mut frames: Vec<LinearImage> = Vec::new();
        for frame in 0..FRAMES {
            scene.set_time(&mut r, time_of(frame));
            r.render_frame().unwrap_or_else(|e| panic!("{e}"));
            frames.push(r.read_radiance());
        }
        sum += frames.iter().map(LinearImage::mean_luminance).sum::<f64>() / FRAMES as f64;
    }
    sum / SEEDS.len() as f64 / reference_mean()
}

#[test]
fn a_moving_occluder_leaves_the_image_unbiased_with_last_frames_geometry() {
    for backend in ["software", "ray-query"] {
        let ratio = restir_ratio(backend, true);
        let planted = restir_ratio(backend, false);
        eprintln!(
            "{backend}: previous geometry {ratio:.4}, current geometry (planted) {planted:.4}"
        );
        // Measured 1.004 with either backend, the twin 0.948. Tolerance: 2 seeds × 12 frames
        // at 48×32 against 12 references of 64 spp leave the ratio a noise of about 0.5 %
        // (docs/src/measured/unbiased-reuse.md's 4 seeds at 64×48: ± 0.2 %); 1.5 % is three of
        // those, and the twin is 5 % dark, more than twice the tolerance below the fix.
        assert!(
            (ratio - 1.0).abs() < 0.015,
            "{backend}: {ratio:.4} of the references"
        );
        assert!(
            planted < ratio - 0.03,
            "{backend}: detector silent, {planted:.4} vs {ratio:.4}"
        );
    }
}
