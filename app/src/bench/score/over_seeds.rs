//! Scoring over the seeds, once every seed ran every configuration: each configuration's
//! result is seed S's run (its times, frames and strip), with the image figures over every
//! seed (`seed_figures.rs`; docs/src/results.md, "Error bars"), every seed's median frame
//! time, the lag around each light event averaged over the seeds (`lag.rs`), and its ratios
//! to `nee` (`vs_nee.rs`).

use restir_render::LinearImage;

use super::lag::{SeedEvent, average};
use super::result::ConfigResult;
use super::seed_figures::{SeedRun, of_seeds};
use super::vs_nee::compare_with_nee;

/// The reference a configuration's figures over seeds are scored against (the still
/// camera's, or a moving camera's first) and its own per-pixel luma noise, and the noise of
/// the references its per-frame errors were measured against (with jitter on, the phases').
pub struct SeedReference<'a> {
    pub image: &'a LinearImage,
    pub noise: Option<f64>,
    pub frame_noise: Option<f64>,
}

/// The light events of a dynamic scene: the measured frame and scene time of each.
pub struct EventTimes<'a> {
    pub frames: &'a [usize],
    pub times: &'a [f32],
}

/// One result per configuration from `per_seed[configuration][seed]`, the configurations
/// scored against `references` (one each).
pub fn over_seeds(
    per_seed: &[Vec<ConfigResult>],
    references: &[SeedReference],
    events: Option<EventTimes>,
) -> Vec<ConfigResult> {
    // Seed S's run carries the times, frames and strip; every seed's goes into the figures.
    let mut results: Vec<ConfigResult> = per_seed.iter().map(|runs| runs[0].clone()).collect();
    for ((r, runs), own) in results.iter_mut().zip(per_seed).zip(references) {
        let runs: Vec<SeedRun> = runs
            .iter()
            .map(|r| SeedRun {
                scores: r.scores.as_ref(),
                moments: r.moments.as_ref(),
                frames: r.frames.len(),
            })
            .collect();
        r.over_seeds = of_seeds(&runs, own.image, own.noise);
        r.frame_reference_noise = own.frame_noise;
    }
    for (r, runs) in results.iter_mut().zip(per_seed) {
        r.seed_frame_ms = runs.iter().filter_map(|r| r.median_frame_ms()).collect();
    }
    if let Some(events) = events {
        for (r, runs) in results.iter_mut().zip(per_seed) {
            let seeds: Vec<Vec<SeedEvent>> = runs.iter().map(|r| r.seed_events.clone()).collect();
            r.lag = average(events.frames, events.times, &seeds);
        }
    }
    compare_with_nee(&mut results);
    results
}
