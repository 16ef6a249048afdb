//! What one configuration measured in one seed's run, and what scoring adds once every
//! seed ran: the run loop (run/run_loop.rs) fills in its frames, times and scores, the
//! stage over the seeds (`over_seeds.rs`) its figures over seeds, lag and ratios to `nee`.

use restir_render::LinearImage;
use restir_render::metrics::pixel_moments::PixelMoments;
use restir_render::stats::StatsSummary;
use restir_render::tracing::RayBackend;

use super::frame_figures::{FrameRecord, ScoreSummary};
use super::lag::{EventLag, SeedEvent};
use super::seed_figures::SeedFigures;
use crate::bench::plan::budget::BudgetClock;
use crate::bench::plan::configs::Config;

/// What one configuration measured.
#[derive(Clone, Debug)]
pub struct ConfigResult {
    pub config: Config,
    pub frames: Vec<FrameRecord>,
    /// Median per-frame and per-pass times.
    pub times: StatsSummary,
    pub scores: Option<ScoreSummary>,
    /// Equal-time mode: the clock when it stopped.
    pub budget: Option<BudgetClock>,
    /// Filled in once every configuration ran (`vs_nee.rs`): median frame time, per-frame
    /// luma MSE and (equal-time mode) the running average's MSE, each relative to `nee`.
    pub time_vs_nee: Option<f64>,
    pub frame_mse_vs_nee: Option<f64>,
    pub budget_mse_vs_nee: Option<f64>,
    /// A dynamic scene's events: this run's numbers per event, the first event's frames
    /// for `event_strip.png` (index, image), and (filled in by `over_seeds.rs` once every
    /// seed ran) the numbers averaged over seeds.
    pub seed_events: Vec<SeedEvent>,
    pub event_frames: Vec<(usize, LinearImage)>,
    pub lag: Vec<EventLag>,
    /// A still shot's last frame of this run, read back from its renderer before the next
    /// seed renders on it (run/seeds.rs; none for later seeds): `strip.png`'s picture, the
    /// same run as the error it is labelled with.
    pub last_frame: Option<LinearImage>,
    /// The temporal-stability figure: mean |Δ luma| between consecutive measured frames
    /// over the reference's luminance (`restir_render::flicker`; none without scoring).
    pub flicker: Option<f64>,
    /// What traced the configuration's rays (`ray_backend` resolved on the device).
    pub ray_backend: Option<RayBackend>,
    /// The à-trous depth `denoise_auto_depth`'s probe chose (none: off, or not yet run).
    pub denoise_auto_depth: Option<u32>,
    /// A still camera's per-pixel moments of this seed's frames (seed_figures.rs).
    pub moments: Option<PixelMoments>,
    /// Filled in by `over_seeds.rs` once every seed ran: the image figures over the seeds.
    pub over_seeds: Option<SeedFigures>,
    /// Filled in by `over_seeds.rs` once every seed ran: each seed's median frame time, in seed
    /// order (`times` is seed S's alone). The seeds' frames interleave the configurations
    /// alike, so a cost ratio read seed by seed shows how far the load moved it.
    pub seed_frame_ms: Vec<f64>,
    /// Filled in by `over_seeds.rs`: the luma noise of the references this configuration's
    /// per-frame errors were measured against (`References::frame_noise_luma`).
    pub frame_reference_noise: Option<f64>,
}

impl ConfigResult {
    pub fn median_frame_ms(&self) -> Option<f64> {
        self.times.frame_gpu_ms_median
    }

    /// The error equal-time mode compares: the running average's RGB RMSE.
    pub fn final_accumulated_rmse(&self) -> Option<f64> {
        self.scores.as_ref()?.accumulated_rgb_rmse
    }
}

/// A result of configuration `name` with a per-frame luma RMSE and nothing else measured:
/// what the writers' tests draw and label.
#[cfg(test)]
pub fn planted(name: &str, mean_luma_rmse: f64) -> ConfigResult {
    let settings = restir_render::Settings::default();
    let config = crate::bench::plan::configs::parse_configs(name, &settings)
        .expect("a built-in configuration")
        .remove(0);
    ConfigResult {
        config,
        frames: Vec::new(),
        times: StatsSummary::default(),
        scores: Some(ScoreSummary {
            mean_luma_rmse,
            ..Default::default()
        }),
        budget: None,
        time_vs_nee: None,
        frame_mse_vs_nee: None,
        budget_mse_vs_nee: None,
        seed_events: Vec::new(),
        event_frames: Vec::new(),
        lag: Vec::new(),
        last_frame: None,
        flicker: None,
        ray_backend: None,
        denoise_auto_depth: None,
        moments: None,
        over_seeds: None,
        seed_frame_ms: Vec::new(),
        frame_reference_noise: None,
    }
}
