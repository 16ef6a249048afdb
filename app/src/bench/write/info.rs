//! What every writer states beside the results: the scene, size and camera, the frames,
//! seeds and warm-up, the device and what its times are, and the references.

use restir_render::Gpu;

use crate::bench::plan::Plan;
use crate::bench::plan::args::BenchArgs;
use crate::bench::plan::camera_path::CameraPath;
use crate::bench::run::Bench;
use crate::bench::run::reference_sets::ReferenceSets;
use crate::bench::run::references::References;

/// Everything the writers need besides the results.
pub struct BenchInfo {
    pub scene: String,
    pub size: (u32, u32),
    pub camera: CameraPath,
    pub frames: Option<u32>,
    pub warmup: u32,
    pub budget_ms: Option<f64>,
    pub seed: u32,
    pub device: String,
    pub device_is_cpu: bool,
    /// The spatial radius as set (px at 1080p) and as used at this height (px).
    pub radius: (f32, f32),
    pub jitter: bool,
    pub reference_spp: u32,
    /// The references' own noise: of the images the accumulated image is scored against,
    /// and (luma) of those every per-frame error is measured against, which differ with
    /// jitter on (`References::frame_noise_luma`).
    pub reference_noise_luma: Option<f64>,
    pub reference_noise_rgb: Option<f64>,
    pub frame_reference_noise_luma: Option<f64>,
    pub reference_count: usize,
    /// The `max_bounces` of the references (one set each; configurations are scored
    /// against the set of their own max_bounces).
    pub reference_bounces: Vec<u32>,
    /// Seeds every configuration ran (the image figures over seeds and the lag metrics rest
    /// on them), and where the events came from.
    pub seeds: u32,
    pub event_source: Option<&'static str>,
}

impl BenchInfo {
    /// The sentence that goes next to every time.
    pub fn timing_note(&self) -> &'static str {
        timing_note(self.device_is_cpu)
    }
}

pub fn timing_note(device_is_cpu: bool) -> &'static str {
    if device_is_cpu {
        "CPU adapter (lavapipe): pass times are CPU wall-clock; only ratios within one run are meaningful"
    } else {
        "GPU timestamp queries"
    }
}

impl BenchInfo {
    /// The conditions of a bench set up as `bench` from `args` and `plan`.
    pub fn of(args: &BenchArgs, plan: &Plan, bench: &Bench) -> BenchInfo {
        let sets = &bench.references;
        let refs = sets.primary();
        BenchInfo {
            scene: args.scene.clone(),
            size: plan.size,
            camera: plan.camera,
            frames: args.budget_ms.is_none().then_some(plan.measured),
            warmup: args.warmup,
            budget_ms: args.budget_ms,
            seed: args.pipeline.seed,
            device: device(&bench.gpu),
            device_is_cpu: bench.gpu.is_cpu(),
            radius: plan.radius,
            jitter: plan.base.jitter,
            reference_spp: refs.spp,
            reference_noise_luma: max_noise(sets, |r| r.noise_luma_rmse),
            reference_noise_rgb: max_noise(sets, |r| r.noise_rgb_rmse),
            frame_reference_noise_luma: max_noise(sets, References::frame_noise_luma),
            reference_count: refs.images.len(),
            reference_bounces: sets.bounces().map(|(b, _)| b).collect(),
            seeds: args.seeds,
            event_source: bench.events.as_ref().map(|e| e.source),
        }
    }
}

/// The adapter and its driver, as the tables name the device.
fn device(gpu: &Gpu) -> String {
    format!("{}, {}", gpu.adapter_name(), gpu.driver_info())
}

/// The largest estimated own noise among all references.
fn max_noise(sets: &ReferenceSets, of: impl Fn(&References) -> Option<f64>) -> Option<f64> {
    sets.bounces().filter_map(|(_, r)| of(r)).reduce(f64::max)
}
