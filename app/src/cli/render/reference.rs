//! The reference that `render --debug-view error|bias` compares with: the same scene, size,
//! camera, jitter and scene time, from the reference cache (rendered on a renderer of its
//! own and stored there when it is missing, as the bench does).

use std::io::Write;

use anyhow::bail;
use restir_render::reference_cache::{Progress, ReferenceCache, ReferenceRequest};
use restir_render::{DebugView, Gpu, LinearImage, Renderer};

use super::job::Job;
use super::render_loop::SideRun;

/// Why a view cannot be compared with one reference, if it cannot: the bias view scores a
/// running average, which is one image only for a still camera at one moment.
pub fn check_comparable(job: &Job, animated: bool) -> anyhow::Result<()> {
    if job.view != DebugView::Bias {
        return Ok(());
    }
    if job.motion.orbit != 0.0 || job.motion.cut_at.is_some() {
        bail!(
            "--debug-view bias compares a running average with one reference: it needs a still camera (no --orbit, no --cut-at)"
        );
    }
    if animated && job.timeline.fps != 0.0 {
        bail!(
            "--debug-view bias compares a running average with one reference: an animated scene needs --fps 0 (one moment)"
        );
    }
    Ok(())
}

/// The reference of a side's last frame (same scene time, camera, size, jitter, bounces and
/// reference light sampling) and its own noise (luma RMSE), for `set_reference_image`.
pub fn reference_of(run: &SideRun, gpu: &Gpu, job: &Job) -> anyhow::Result<(LinearImage, f32)> {
    let settings = run.renderer.settings().clone();
    let mut request = ReferenceRequest::new(
        &job.scene,
        run.scene.scene(),
        run.renderer.camera(),
        run.renderer.size(),
        job.reference_spp,
        settings.jitter,
    )
    .with_light_bvh(settings.reference_light_bvh, run.scene.scene())
    .with_max_bounces(settings.reference_bounces())
    .with_light_samples(settings.reference_light_samples);
    if let Some(e) = &job.effects {
        request.effects = e.clone();
    }
    let cache = match &job.cache_dir {
        Some(dir) => ReferenceCache::new(dir),
        None => ReferenceCache::at_default_dir(),
    };
    let (w, h) = run.renderer.size();
    let mut reference_renderer = Renderer::new(gpu.clone(), run.scene.scene(), w, h, settings)?;
    let mut progress = |p: &Progress| {
        eprint!(
            "\rreference: {}/{} spp ({:.1} s)   ",
            p.samples_done,
            p.samples_total,
            p.elapsed.as_secs_f64()
        );
        let _ = std::io::stderr().flush();
        true
    };
    let reference = cache.get_or_render(&mut reference_renderer, &request, &mut progress)?;
    if !reference.from_cache {
        eprintln!();
    }
    let noise = reference.meta.noise_luma_rmse.unwrap_or(0.0) as f32;
    Ok((reference.image, noise))
}
