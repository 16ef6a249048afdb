//! Shared set-up of the GPU tests: every test needs an adapter (lavapipe in CI) and fails
//! with a clear message when there is none; none of them skips silently.
#![allow(dead_code)]

pub mod blocks;
pub mod furnace;
pub mod indirect;
pub mod scene_parts;

use restir_render::{Gpu, LinearImage, Mode, Renderer, Settings, load_scene};

pub fn gpu() -> Gpu {
    match Gpu::new_headless() {
        Ok(g) => g,
        Err(e) => panic!("GPU tests need a wgpu adapter: {e}"),
    }
}

pub fn renderer(scene: &str, width: u32, height: u32, mode: Mode, settings: Settings) -> Renderer {
    let scene = load_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    let mut r =
        Renderer::new(gpu(), &scene, width, height, settings).unwrap_or_else(|e| panic!("{e:#}"));
    r.set_mode(mode);
    r
}

/// Renders `frames` frames and returns the average of them.
pub fn accumulate(r: &mut Renderer, frames: u32) -> LinearImage {
    r.reset_accumulation();
    for _ in 0..frames {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
    }
    r.read_accumulated()
}

/// The `--stats` summary of the next `frames` frames.
pub fn stats_of(r: &mut Renderer, frames: u32) -> restir_render::stats::StatsSummary {
    let _ = r.collect_reports(true);
    let mut reports = Vec::new();
    for _ in 0..frames {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
        reports.extend(r.collect_reports(true));
    }
    restir_render::stats::StatsSummary::from_reports(&reports, 0)
}

/// A converged reference of the renderer's current scene and camera.
pub fn reference(r: &mut Renderer, frames: u32, spp: u32) -> LinearImage {
    let mode = r.mode();
    let settings = r.settings().clone();
    let mut s = settings.clone();
    s.reference_spp = spp;
    r.set_settings(s);
    r.set_mode(Mode::Reference);
    let img = accumulate(r, frames);
    r.set_mode(mode);
    r.set_settings(settings);
    img
}

/// Renders one frame with `pixel` inspected and returns what the inspector captured.
pub fn inspect_next_frame(
    r: &mut Renderer,
    pixel: (u32, u32),
) -> restir_render::renderer::PixelInspection {
    r.set_inspected_pixel(Some(pixel));
    r.render_frame().unwrap_or_else(|e| panic!("{e}"));
    r.collect_reports(true)
        .into_iter()
        .rev()
        .find_map(|f| f.inspection)
        .expect("an inspected frame")
}

/// Settings from `key=value` assignments on top of the defaults.
pub fn settings(assignments: &[&str]) -> Settings {
    let mut s = Settings::default();
    s.apply_assignments(assignments.iter().copied())
        .expect("valid test settings");
    s
}

/// Mean per-frame luma RMSE and mean frame-to-frame luma RMSE over `frames` frames,
/// starting from a clean history.
pub fn per_frame_errors(r: &mut Renderer, reference: &LinearImage, frames: u32) -> (f64, f64) {
    use restir_render::metrics::luma_rmse;
    r.request_cut();
    let (mut accuracy, mut stability) = (0.0, 0.0);
    let mut previous: Option<LinearImage> = None;
    for _ in 0..frames {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
        let frame = r.read_radiance();
        accuracy += luma_rmse(&frame, reference).unwrap();
        if let Some(p) = &previous {
            stability += luma_rmse(&frame, p).unwrap();
        }
        previous = Some(frame);
    }
    (
        accuracy / frames as f64,
        stability / (frames - 1).max(1) as f64,
    )
}

/// The spatial radius for a test image `width` × `height`: the figures of these tests were
/// measured with 8 px per 128 of width (at least 4 px), set here as the 1080p value that
/// gives exactly that effective radius (the radius follows the height, settings/pixel_units.rs).
pub fn radius_for(width: u32, height: u32) -> String {
    radius_px((width / 16).max(4) as f32, height)
}

/// `spatial_radius=` the 1080p value whose effective radius at `height` is `pixels`.
pub fn radius_px(pixels: f32, height: u32) -> String {
    let r = restir_render::settings::pixel_units::at_1080p(pixels, height);
    format!("spatial_radius={r}")
}

/// The mean of each colour channel over the image.
pub fn channel_means(img: &LinearImage) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for p in &img.pixels {
        for c in 0..3 {
            sum[c] += p[c] as f64;
        }
    }
    sum.map(|s| s / img.pixels.len() as f64)
}

/// The region a scene change changed: the pixels whose reference luminance moved by more
/// than 10 % of the larger of the two.
pub fn changed_pixels(before: &LinearImage, after: &LinearImage) -> Vec<usize> {
    let luma = |p: [f32; 4]| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    (0..before.pixels.len())
        .filter(|&i| {
            let (a, b) = (luma(before.pixels[i]), luma(after.pixels[i]));
            (a - b).abs() > 0.1 * a.max(b) && a.max(b) > 0.0
        })
        .collect()
}
