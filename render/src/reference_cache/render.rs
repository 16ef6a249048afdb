//! Rendering a reference: frames of `Mode::Reference` with the same spp each, averaged,
//! with the half-way average kept for the noise estimate (see the parent module).

use std::time::Instant;

use super::{Cancelled, Progress, ReferenceMeta, ReferenceRequest};
use crate::Renderer;
use crate::gpu::timing::TimingMode;
use crate::image::LinearImage;
use crate::metrics::{luma_rmse, rgb_rmse};
use crate::settings::Settings;
use crate::view::Mode;

/// Aim for about this many pixel-samples per frame while rendering a reference: a frame is
/// then a fraction of a second on lavapipe at small sizes and progress moves smoothly.
const SAMPLES_PER_FRAME_TARGET: u64 = 1 << 20;
/// The most samples per pixel one reference frame takes (the `reference_spp` range).
const MAX_SPP_PER_FRAME: u32 = 256;

/// The settings of a reference frame: defaults (the reference reads only these).
pub(super) fn reference_settings(
    jitter: bool,
    spp_per_frame: u32,
    max_bounces: u32,
    light_bvh: bool,
    light_samples: u32,
) -> Settings {
    Settings {
        jitter,
        reference_spp: spp_per_frame,
        max_bounces,
        reference_light_bvh: light_bvh,
        reference_light_samples: light_samples,
        ..Settings::default()
    }
    .for_reference()
}

/// Samples per pixel per frame: the largest divisor of `spp` near the per-frame target, so
/// every frame has the same weight in the average, and at most half of `spp`, so there are
/// two halves to estimate the reference's own noise from.
pub fn spp_per_frame(spp: u32, pixels: u64) -> u32 {
    let target =
        (SAMPLES_PER_FRAME_TARGET / pixels.max(1)).clamp(1, MAX_SPP_PER_FRAME as u64) as u32;
    let limit = target.min((spp / 2).max(1));
    (1..=limit)
        .rev()
        .find(|&d| spp.is_multiple_of(d))
        .unwrap_or(1)
}

/// Renders `request` on `renderer` (see [`super::ReferenceCache::get_or_render`]), without the cache.
pub fn render_reference(
    renderer: &mut Renderer,
    request: &ReferenceRequest,
    progress: &mut dyn FnMut(&Progress) -> bool,
) -> anyhow::Result<(LinearImage, ReferenceMeta)> {
    let spp = request.spp.max(1);
    let per_frame = spp_per_frame(spp, request.width as u64 * request.height as u64);
    let frames = spp / per_frame;
    renderer.resize(request.width, request.height)?;
    renderer.set_settings(reference_settings(
        request.jitter,
        per_frame,
        request.max_bounces,
        request.light_bvh,
        request.light_samples,
    ));
    renderer.set_mode(Mode::Reference);
    renderer.set_camera(request.camera);
    renderer.set_seed(request.seed);
    renderer.force_effects(Some(request.effects.clone()));
    renderer.set_reference_phase(request.jitter_phase);
    // Per-pass timing would only slow it down (one submission per pass on CPU adapters).
    let timing = renderer.timing_mode();
    renderer.set_timing_mode(TimingMode::Off);
    let result = accumulate(renderer, spp, per_frame, frames, progress);
    renderer.set_timing_mode(timing);
    // Any later `Mode::Reference` frame on this renderer rasterises at the pixel centres again.
    renderer.set_reference_phase(None);
    let (image, half, seconds) = result?;
    let half_frames = frames / 2;
    // RMSE(f) ≈ RMSE(a, f)·√(k/(n−k)) (module docs).
    let scale = (half_frames as f64 / (frames - half_frames).max(1) as f64).sqrt();
    let noise = |metric: fn(&LinearImage, &LinearImage) -> Result<f64, _>| {
        half.as_ref()
            .and_then(|a| metric(a, &image).ok())
            .map(|r| r * scale)
    };
    let meta = ReferenceMeta {
        key: request.key()?.description,
        spp,
        frames,
        spp_per_frame: per_frame,
        noise_luma_rmse: noise(luma_rmse),
        noise_rgb_rmse: noise(rgb_rmse),
        render_seconds: seconds,
        adapter: renderer.gpu().adapter_name(),
    };
    Ok((image, meta))
}

/// Renders the frames; returns the average, the average after the first half (None for a
/// single frame) and the seconds taken.
fn accumulate(
    renderer: &mut Renderer,
    spp: u32,
    per_frame: u32,
    frames: u32,
    progress: &mut dyn FnMut(&Progress) -> bool,
) -> anyhow::Result<(LinearImage, Option<LinearImage>, f64)> {
    renderer.request_cut();
    renderer.reset_accumulation();
    let start = Instant::now();
    let report = |done: u32| Progress {
        samples_done: done,
        samples_total: spp,
        elapsed: start.elapsed(),
    };
    if !progress(&report(0)) {
        return Err(Cancelled.into());
    }
    let mut half = None;
    for frame in 1..=frames {
        renderer.render_frame()?;
        // Waits for the frame: progress is then real, and reports never pile up.
        renderer.collect_reports(true);
        if frame == frames / 2 {
            half = Some(renderer.read_accumulated());
        }
        if !progress(&report(frame * per_frame)) {
            return Err(Cancelled.into());
        }
    }
    Ok((
        renderer.read_accumulated(),
        half,
        start.elapsed().as_secs_f64(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_split_the_spp_evenly_near_the_target() {
        // 160×100: ~65 spp per frame allowed.
        assert_eq!(spp_per_frame(1024, 16_000), 64);
        assert_eq!(spp_per_frame(1000, 16_000), 50);
        // A prime takes one sample per frame; tiny images are capped.
        assert_eq!(spp_per_frame(1031, 16_000), 1);
        assert_eq!(spp_per_frame(4096, 48 * 32), 256);
        assert_eq!(spp_per_frame(3, 1920 * 1080), 1);
        assert_eq!(spp_per_frame(0, 100), 1);
        // Always two frames or more, for the noise estimate.
        assert_eq!(spp_per_frame(16, 48 * 32), 8);
        assert_eq!(spp_per_frame(1, 100), 1);
    }
}
