//! `render --stats`: the JSON document, one block per side with `--compare`, and the
//! scene-time block of an animated scene.

use std::path::Path;
use std::time::Instant;

use anyhow::Context;
use restir_render::stats::{FrameReport, StatsSummary};
use restir_render::{LinearImage, Mode, Renderer};
use serde::Serialize;

use super::display::read_image;
use super::job::Job;
use super::render_loop::{FrameUpdate, SideRun};

/// Writes the document for side A (and, with `--compare`, a block per side). `image` is
/// what was written, the split with `--compare`: the document's own non-finite count is
/// that image's.
pub(super) fn write(
    path: &Path,
    job: &Job,
    left: SideRun,
    right: Option<SideRun>,
    image: &LinearImage,
    divider: u32,
) -> anyhow::Result<()> {
    let side_of = |run: SideRun| Side {
        image: read_image(&run.renderer, job.accumulate),
        scene_time: run
            .scene
            .is_animated()
            .then(|| scene_time_stats(job, &run.updates, &run.renderer, run.scene.scene())),
        renderer: run.renderer,
        reports: run.reports,
    };
    let left = side_of(left);
    let right = right.map(side_of);
    let mut doc = side_stats(&left);
    doc.summary.nan_inf_pixels = image.non_finite_count() as u64;
    if let (Some(r), Some(b)) = (&right, &job.compare) {
        doc.compare = Some(Box::new(CompareStats {
            divider_column: divider,
            left: side_stats(&left),
            right_config: b.label.clone(),
            right: side_stats(r),
        }));
    }
    let text = serde_json::to_string_pretty(&doc)?;
    std::fs::write(path, text).with_context(|| format!("{}: cannot write stats", path.display()))
}

/// Scene time and the per-frame update cost of an animated scene (`--stats`).
#[derive(Clone, Serialize)]
struct SceneTimeStats {
    /// Scene time of the first and the last frame, seconds.
    first_time: f32,
    last_time: f32,
    fps: f32,
    /// Median CPU cost per frame of the scene update (posing, BVH refit, light table,
    /// upload), over frames that changed something.
    median_pose_ms: f64,
    median_bvh_ms: f64,
    median_lights_ms: f64,
    median_upload_ms: f64,
    updated_frames: usize,
    /// Frames whose update rebuilt the BVH (the refitted tree had degraded past
    /// `BVH_REBUILD_FACTOR`; render/src/gpu_scene/rebuild.rs), and the median BVH time of
    /// those frames and of the refit-only ones.
    bvh_rebuilds: usize,
    median_bvh_rebuild_frame_ms: f64,
    median_bvh_refit_frame_ms: f64,
    /// Refit against rebuild at the last frame: SAH cost of the renderer's tree, of a tree
    /// built from scratch over the same positions as the renderer builds it (moving
    /// triangles apart, `scene::bvh::split`), and that build's time.
    bvh_refit_sah_cost: f64,
    bvh_rebuilt_sah_cost: f64,
    bvh_rebuild_ms: f64,
}

#[derive(Serialize)]
struct LoadStats {
    phases: Vec<restir_render::load_phases::Phase>,
    total_ms: f64,
    pipelines: Vec<restir_render::renderer::PipelineCompile>,
}

/// The `--stats` JSON document.
#[derive(Serialize)]
struct StatsFile<'a> {
    scene: &'a restir_render::gpu_scene::SceneInfo,
    adapter: String,
    /// The driver and its version (lavapipe: "llvmpipe Mesa 25.0.7…"), so every figure
    /// can say which driver made it.
    driver: String,
    /// "lavapipe timings are CPU timings": true when the adapter is a CPU implementation.
    adapter_is_cpu: bool,
    /// What traced the rays: "software" (the BVH in WGSL) or "ray-query" (hardware).
    ray_backend: Option<restir_render::tracing::RayBackend>,
    /// Whether the device could run the ray-query backend.
    ray_query_available: bool,
    /// From file to first frame: each phase (loader, upload, the first frame's pipelines),
    /// their total and every pipeline compiled (docs/src/load-time.md, "The phases").
    load: LoadStats,
    mode: Mode,
    size: [u32; 2],
    /// The last frame's camera.
    camera: CameraStats,
    effects: String,
    effect_reasons: Vec<(String, String)>,
    passes: Vec<&'static str>,
    settings: std::collections::BTreeMap<String, String>,
    /// `spatial_radius` is set at 1080p; this is the radius used at this height.
    effective_spatial_radius_px: f32,
    mean_luminance: f64,
    /// The light samplers' structures: BVH build and refit times, memory
    /// (docs/src/light-samplers.md).
    light_sampler: restir_render::light_sampler::LightSamplerStats,
    /// `light_sampler=auto`'s probe: its points and how many times fewer samples a sampler
    /// by distance would need than the power table, in hundredths (light_probe.rs).
    light_probe: Option<restir_render::light_probe::LightProbe>,
    /// `denoise_auto_depth`'s choice: the depth and each depth's error against a held-out
    /// frame (docs/src/denoiser.md, "Choosing the depth").
    #[serde(skip_serializing_if = "Option::is_none")]
    denoise_depth: Option<restir_render::denoise::depth_probe::DepthChoice>,
    #[serde(skip_serializing_if = "Option::is_none")]
    scene_time: Option<SceneTimeStats>,
    /// With the boiling or survivor-change view: the temporal window's figures.
    #[serde(skip_serializing_if = "Option::is_none")]
    temporal_window: Option<WindowStats>,
    #[serde(flatten)]
    summary: StatsSummary,
    /// With `--compare`: a block per side (left = this configuration, right = B).
    #[serde(skip_serializing_if = "Option::is_none")]
    compare: Option<Box<CompareStats<'a>>>,
}

#[derive(Serialize)]
struct CompareStats<'a> {
    /// First column of the right side.
    divider_column: u32,
    left: StatsFile<'a>,
    right_config: String,
    right: StatsFile<'a>,
}

/// Where the camera was (position, unit quaternion x y z w, vertical field of view).
#[derive(Clone, Serialize)]
struct CameraStats {
    position: [f32; 3],
    rotation: [f32; 4],
    yfov_degrees: f32,
}

/// The temporal window of the boiling views at the last frame, over the pixels that see
/// a surface (docs/src/debug-views.md, "Boiling and survivor change").
#[derive(Clone, Serialize)]
struct WindowStats {
    frames: u32,
    /// Mean over pixels of σ/mean of luminance in the window.
    mean_boiling: f64,
    /// Share of pixels whose σ/mean exceeds `BOILING_THRESHOLD`.
    boiling_share: f64,
    boiling_threshold: f32,
    /// Mean over pixels of the share of frames whose survivor's light changed.
    mean_survivor_change: f64,
}

fn window_stats(renderer: &Renderer) -> Option<WindowStats> {
    use restir_render::renderer::TemporalWindow;
    let window = renderer.read_temporal_window()?;
    let surface: Vec<bool> = renderer
        .read_surfaces()
        .iter()
        .map(|s| s.depth > 0.0)
        .collect();
    Some(WindowStats {
        frames: window.frames,
        mean_boiling: TemporalWindow::mean(&window.rel_std, Some(&surface)),
        boiling_share: window.boiling_share(Some(&surface)),
        boiling_threshold: restir_render::shader_constants::BOILING_THRESHOLD,
        mean_survivor_change: TemporalWindow::mean(&window.change_fraction, Some(&surface)),
    })
}

/// One side's renderer and what it produced.
struct Side {
    renderer: Renderer,
    reports: Vec<FrameReport>,
    image: LinearImage,
    /// Scene time and update costs, for an animated scene.
    scene_time: Option<SceneTimeStats>,
}

fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn scene_time_stats(
    job: &Job,
    updates: &[FrameUpdate],
    renderer: &Renderer,
    scene: &restir_render::Scene,
) -> SceneTimeStats {
    let timeline = job.timeline;
    let of = |f: fn(&FrameUpdate) -> f64| median(updates.iter().map(f).collect());
    let positions: Vec<_> = (0..scene.triangles.len())
        .map(|t| scene.triangle_positions(t))
        .collect();
    let moving = scene.moving_triangles();
    let build = Instant::now();
    let (rebuilt, _) = restir_render::scene::bvh::Bvh::build_split(&positions, &moving);
    let bvh_rebuild_ms = build.elapsed().as_secs_f64() * 1e3;
    SceneTimeStats {
        first_time: timeline.time_of(0),
        last_time: timeline.time_of(job.frames - 1),
        fps: timeline.fps,
        median_pose_ms: of(|u| u.0),
        median_bvh_ms: of(|u| u.1.bvh_ms),
        median_lights_ms: of(|u| u.1.lights_ms),
        median_upload_ms: of(|u| u.1.upload_ms),
        updated_frames: updates.len(),
        bvh_rebuilds: updates.iter().filter(|u| u.1.bvh_rebuilt).count(),
        median_bvh_rebuild_frame_ms: median(
            updates
                .iter()
                .filter(|u| u.1.bvh_rebuilt)
                .map(|u| u.1.bvh_ms)
                .collect(),
        ),
        median_bvh_refit_frame_ms: median(
            updates
                .iter()
                .filter(|u| !u.1.bvh_rebuilt)
                .map(|u| u.1.bvh_ms)
                .collect(),
        ),
        bvh_refit_sah_cost: renderer.bvh_sah_cost(),
        bvh_rebuilt_sah_cost: rebuilt.sah_cost(),
        bvh_rebuild_ms,
    }
}

fn side_stats(side: &Side) -> StatsFile<'_> {
    let renderer = &side.renderer;
    let effects = renderer
        .last_effects()
        .cloned()
        .unwrap_or_else(restir_render::effects::EffectSet::all);
    let settings = renderer.effective_settings();
    let (_, height) = renderer.size();
    StatsFile {
        scene: renderer.scene_info(),
        adapter: renderer.gpu().adapter_name(),
        driver: renderer.gpu().driver_info(),
        adapter_is_cpu: renderer.gpu().is_cpu(),
        ray_backend: renderer.last_ray_backend(),
        ray_query_available: renderer.gpu().ray_query,
        load: {
            let phases = renderer.load_phases();
            LoadStats {
                total_ms: phases.total_ms(),
                phases: phases.phases,
                pipelines: renderer.pipeline_compiles().to_vec(),
            }
        },
        mode: renderer.mode(),
        size: [renderer.size().0, height],
        camera: {
            let c = renderer.camera();
            CameraStats {
                position: c.position.into(),
                rotation: c.rotation.into(),
                yfov_degrees: c.yfov.to_degrees(),
            }
        },
        effects: effects.to_string(),
        effect_reasons: effects
            .reasons
            .iter()
            .map(|(e, r)| (e.name().to_string(), r.clone()))
            .collect(),
        passes: renderer.last_passes().to_vec(),
        settings: restir_render::settings::PARAMS
            .iter()
            .map(|p| {
                (
                    p.name.to_string(),
                    settings
                        .get(p.name)
                        .map(|v| v.to_string())
                        .unwrap_or_default(),
                )
            })
            .collect(),
        effective_spatial_radius_px: settings.effective_spatial_radius(height),
        mean_luminance: side.image.mean_luminance(),
        light_sampler: renderer.light_sampler_stats(),
        light_probe: renderer.light_probe(),
        denoise_depth: renderer.denoise_depth_choice().cloned(),
        scene_time: side.scene_time.clone(),
        temporal_window: window_stats(renderer),
        summary: StatsSummary::from_reports(&side.reports, side.image.non_finite_count() as u64),
        compare: None,
    }
}
