//! Every image figure of a configuration over `--seeds K` (docs/src/results.md, "Error
//! bars"): each seed's number, then their mean with a 95 % interval, the accumulated
//! image's error split into squared bias and variance per pixel, how many independent
//! frames it is worth, and the bias matrix's verdict. One seed gives figures without
//! intervals, marked "(one seed)" wherever they are printed.

use restir_render::LinearImage;
use restir_render::metrics::pixel_moments::PixelMoments;
use restir_render::metrics::seeds::{
    BIAS_TOLERANCE, Interval, PixelSpread, Verdict, frames_to_tolerance, luminance_of, pixel_spread,
};

use super::frame_figures::ScoreSummary;

/// One configuration's figures over its seeds.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SeedFigures {
    pub seeds: usize,
    /// Measured frames per seed.
    pub frames: usize,
    pub frame_luma_rmse: Interval,
    /// Each seed's mean per-frame luma RMSE, in seed order (the equal-time gain's input,
    /// `equal_time_gain.rs`).
    #[serde(default)]
    pub frame_luma_rmse_by_seed: Vec<f64>,
    pub low_frequency_rmse: Interval,
    /// RGB RMSE of each seed's running average (still camera only).
    pub accumulated_rgb_rmse: Option<Interval>,
    /// Mean luminance of each seed's running average over the reference's (still camera),
    /// or of its frames averaged (moving camera).
    pub luma_ratio: Interval,
    /// luma ratio − 1, the interval widened by the reference's own uncertainty.
    pub signed_bias: Interval,
    pub black_pixel_fraction: Interval,
    /// The accumulated image's squared bias and variance per pixel (still camera, K ≥ 2).
    pub spread: Option<PixelSpread>,
    /// Share of pixels the `bias` view flags at the end of a seed's run (still camera).
    pub bias_view_flagged: Option<Interval>,
    /// Frames one seed needs for its mean luminance to lie within ±0.5 % at 95 %.
    pub frames_to_half_percent: Option<f64>,
    pub verdict: Verdict,
    /// Non-finite pixels over every seed and frame.
    pub non_finite_pixels: usize,
    /// Mean luminance of the reference (the first, for a moving camera).
    pub reference_mean_luma: f64,
    /// Moving shot: luma RMSE in the disoccluded pixels and near moving triangles
    /// (frame_figures.rs, `MaskedFigures`), over the seeds.
    #[serde(default)]
    pub disoccluded_luma_rmse: Option<Interval>,
    #[serde(default)]
    pub near_moving_luma_rmse: Option<Interval>,
    /// The detail each frame keeps across the reference's edges, over the seeds
    /// (frame_figures.rs, `DetailSummary`).
    #[serde(default)]
    pub detail_kept: Option<Interval>,
    /// Mean FLIP within the reference's edges, over the seeds (`metrics::flip`).
    #[serde(default)]
    pub detail_flip: Option<Interval>,
}

/// Below this mean luminance a reference counts as black: no light reaches the camera
/// (`hard:no-emitters`), and a ratio to it means nothing.
const BLACK_REFERENCE: f64 = 1e-9;

/// What the figures read of one seed's run (the bench's `ConfigResult`).
pub struct SeedRun<'a> {
    pub scores: Option<&'a ScoreSummary>,
    pub moments: Option<&'a PixelMoments>,
    pub frames: usize,
}

/// The figures of one configuration from its runs, one per seed (in seed order), scored
/// against `reference` (the still camera's, or the first of a moving camera's) whose own
/// per-pixel luma noise is `reference_noise`.
pub fn of_seeds(
    runs: &[SeedRun],
    reference: &LinearImage,
    reference_noise: Option<f64>,
) -> Option<SeedFigures> {
    let scores: Vec<&ScoreSummary> = runs.iter().filter_map(|r| r.scores).collect();
    if scores.is_empty() {
        return None;
    }
    let each = |f: &dyn Fn(&ScoreSummary) -> f64| -> Interval {
        Interval::of(&scores.iter().map(|s| f(s)).collect::<Vec<_>>())
    };
    // A masked figure over the seeds, where every seed has one.
    let masked = |f: &dyn Fn(&ScoreSummary) -> Option<f64>| -> Option<Interval> {
        scores
            .iter()
            .map(|s| f(s))
            .collect::<Option<Vec<f64>>>()
            .map(|v| Interval::of(&v))
    };
    let ratios: Vec<f64> = scores.iter().map(|s| s.luma_ratio).collect();
    let luma_ratio = Interval::of(&ratios);
    let reference_luma = luminance_of(reference);
    let reference_mean = reference.mean_luminance();
    let noise = reference_noise.unwrap_or(0.0);
    // The reference's own noise in its mean luminance, relative: independent pixels of
    // RMSE σ average to σ/√N.
    let reference_sd = if reference_mean > 0.0 {
        noise / (reference_luma.len().max(1) as f64).sqrt() / reference_mean
    } else {
        0.0
    };
    let signed_bias = luma_ratio.shifted(1.0).widened_by(reference_sd);
    let moments: Vec<&PixelMoments> = runs.iter().filter_map(|r| r.moments).collect();
    let still = moments.len() == runs.len();
    let frames = runs.first().map_or(0, |r| r.frames);
    let verdict = if reference_mean < BLACK_REFERENCE {
        Verdict::NoLight
    } else {
        Verdict::of(&signed_bias)
    };
    Some(SeedFigures {
        seeds: scores.len(),
        frames,
        frame_luma_rmse: each(&|s| s.mean_luma_rmse),
        frame_luma_rmse_by_seed: scores.iter().map(|s| s.mean_luma_rmse).collect(),
        low_frequency_rmse: each(&|s| s.mean_low_frequency_rmse),
        accumulated_rgb_rmse: scores
            .iter()
            .map(|s| s.accumulated_rgb_rmse)
            .collect::<Option<Vec<f64>>>()
            .map(|v| Interval::of(&v)),
        luma_ratio,
        signed_bias,
        black_pixel_fraction: each(&|s| s.black_pixel_fraction),
        spread: still
            .then(|| pixel_spread(&moments, &reference_luma, noise))
            .flatten(),
        bias_view_flagged: still.then(|| {
            Interval::of(
                &moments
                    .iter()
                    .map(|m| m.flagged_share(&reference_luma, noise))
                    .collect::<Vec<_>>(),
            )
        }),
        frames_to_half_percent: frames_to_tolerance(&ratios, frames, BIAS_TOLERANCE),
        verdict,
        non_finite_pixels: scores.iter().map(|s| s.non_finite_pixels).sum(),
        reference_mean_luma: reference_mean,
        disoccluded_luma_rmse: masked(&|s| s.disoccluded.and_then(|m| m.luma_rmse)),
        near_moving_luma_rmse: masked(&|s| s.near_moving.and_then(|m| m.luma_rmse)),
        detail_kept: masked(&|s| s.detail.map(|d| d.kept)),
        detail_flip: masked(&|s| s.detail.map(|d| d.flip)),
    })
}
