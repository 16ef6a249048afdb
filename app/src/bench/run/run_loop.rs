//! Running configurations: each on its own renderer, from a clean history with the same
//! seed, along the camera path, with per-frame pass times from `collect_reports` and the
//! scores of every measured frame.
//!
//! The runs are **interleaved**: one frame of each configuration in turn, rather than all
//! frames of one and then the next. On a shared machine (lavapipe runs on the same CPU
//! cores as everything else) the background load drifts during a bench; interleaving
//! exposes every configuration to the same load, so their time *ratios* stay meaningful.

use std::io::Write;

use restir_render::effects::EffectSet;
use restir_render::flicker::Flicker;
use restir_render::stats::{FrameReport, StatsSummary};
use restir_render::timeline::AnimatedScene;
use restir_render::{LinearImage, Renderer};

use super::events::LagProbe;
use super::shot::Shot;
use crate::bench::plan::budget::{Budget, BudgetClock};
use crate::bench::plan::configs::Config;
use crate::bench::score::frame_figures::{FrameRecord, FrameScores};
use crate::bench::score::result::ConfigResult;
use crate::bench::score::scoring::Scoring;

/// How every configuration is run.
#[derive(Clone)]
pub struct RunPlan {
    /// Measured frames (fixed mode); ignored with a budget.
    pub frames: u32,
    /// Frames rendered first so history builds up; neither timed nor scored.
    pub warmup: u32,
    pub budget: Option<Budget>,
    pub shot: Shot,
    pub seed: u32,
    /// `--effects` when forced.
    pub effects: Option<EffectSet>,
}

/// One configuration in progress on its own renderer.
pub struct ConfigRun<'a> {
    pub renderer: Renderer,
    config: Config,
    scoring: Scoring<'a>,
    clock: Option<BudgetClock>,
    /// An animated scene's clock: this configuration's renderer is posed per frame.
    scene_clock: Option<AnimatedScene>,
    records: Vec<FrameRecord>,
    reports: Vec<FrameReport>,
    lag: Option<LagProbe<'a>>,
    flicker: Flicker,
}

impl<'a> ConfigRun<'a> {
    /// Sets `renderer` up for `config` and renders the unmeasured frames: two that compile
    /// every pipeline variant the run will use (still, then moved one step), so no measured
    /// frame pays for a shader compile, then a clean history and the warm-up frames.
    pub fn start(
        mut renderer: Renderer,
        config: &Config,
        plan: &RunPlan,
        scoring: Scoring<'a>,
        mut scene_clock: Option<AnimatedScene>,
        lag: Option<LagProbe<'a>>,
    ) -> anyhow::Result<ConfigRun<'a>> {
        if let Some(c) = &scene_clock {
            // The renderer may have rendered references at other times.
            c.sync(&mut renderer);
        }
        let mut pose = |renderer: &mut Renderer, frame: u32| {
            if let Some(c) = &mut scene_clock {
                c.set_time(renderer, plan.shot.time(frame));
            }
        };
        renderer.set_mode(config.mode);
        renderer.set_settings(config.settings.clone());
        renderer.set_seed(plan.seed);
        renderer.force_effects(plan.effects.clone());
        for frame in 0..2 {
            pose(&mut renderer, frame);
            renderer.set_camera(plan.shot.camera(frame));
            renderer.render_frame()?;
            renderer.collect_reports(true);
        }
        renderer.request_cut();
        renderer.reset_accumulation();
        for frame in 0..plan.warmup {
            pose(&mut renderer, frame);
            renderer.set_camera(plan.shot.camera(frame));
            renderer.render_frame()?;
            renderer.collect_reports(true);
        }
        renderer.reset_accumulation();
        Ok(ConfigRun {
            renderer,
            config: config.clone(),
            scoring,
            clock: plan.budget.map(BudgetClock::new),
            scene_clock,
            records: Vec::new(),
            reports: Vec::new(),
            lag,
            flicker: Flicker::new(),
        })
    }

    pub fn done(&self, plan: &RunPlan) -> bool {
        match &self.clock {
            Some(c) => c.done(),
            None => self.records.len() as u32 >= plan.frames,
        }
    }

    /// Renders, times and scores the next measured frame.
    pub fn step(&mut self, plan: &RunPlan) -> anyhow::Result<()> {
        let index = self.records.len();
        let frame = plan.warmup + index as u32;
        if let Some(c) = &mut self.scene_clock {
            c.set_time(&mut self.renderer, plan.shot.time(frame));
        }
        self.renderer.set_camera(plan.shot.camera(frame));
        self.renderer.render_frame()?;
        let report = self
            .renderer
            .collect_reports(true)
            .into_iter()
            .next_back()
            .unwrap_or_default();
        let ms = report.gpu_ms();
        let cumulative_ms = self.records.last().map_or(0.0, |r| r.cumulative_ms) + ms;
        if let Some(c) = &mut self.clock {
            c.add(ms);
        }
        let scores = if self.scoring.wants_images() {
            let image = self.renderer.read_radiance();
            if let Some(lag) = &mut self.lag {
                lag.push(index, &image);
            }
            if let Some(reference) = reference_of(&self.scoring, index) {
                self.flicker.push(&image, reference)?;
            }
            let frame_index = self.renderer.frame_index() - 1;
            self.scoring.push(index, frame_index, &image)?
        } else {
            FrameScores::default()
        };
        self.records.push(FrameRecord {
            index,
            ms,
            cumulative_ms,
            scores,
        });
        self.reports.push(report);
        Ok(())
    }

    pub fn finish(self) -> anyhow::Result<(ConfigResult, Renderer)> {
        let (seed_events, event_frames) = match self.lag {
            Some(probe) => probe.finish(&self.records),
            None => Default::default(),
        };
        let result = ConfigResult {
            seed_events,
            event_frames,
            lag: Vec::new(),
            last_frame: None,
            times: StatsSummary::from_reports(&self.reports, 0),
            scores: self.scoring.summary()?,
            moments: self.scoring.into_moments(),
            over_seeds: None,
            seed_frame_ms: Vec::new(),
            frame_reference_noise: None,
            config: self.config,
            frames: self.records,
            budget: self.clock,
            time_vs_nee: None,
            frame_mse_vs_nee: None,
            budget_mse_vs_nee: None,
            flicker: self.flicker.mean(),
            ray_backend: self.renderer.last_ray_backend(),
            denoise_auto_depth: self.renderer.denoise_depth_choice().map(|c| c.iterations),
        };
        Ok((result, self.renderer))
    }
}

/// The reference measured frame `index` is scored against.
fn reference_of<'a>(scoring: &Scoring<'a>, index: usize) -> Option<&'a LinearImage> {
    match scoring {
        Scoring::Off => None,
        Scoring::Still { reference, .. } => Some(reference),
        Scoring::Moving { references, .. } => references.get(index),
    }
}

/// Runs every started configuration to its end, one frame of each in turn.
pub fn run_interleaved<'a>(
    mut runs: Vec<(String, ConfigRun<'a>)>,
    plan: &RunPlan,
) -> anyhow::Result<Vec<(ConfigResult, Renderer)>> {
    let mut round = 0;
    while runs.iter().any(|(_, r)| !r.done(plan)) {
        for (_, run) in runs.iter_mut().filter(|(_, r)| !r.done(plan)) {
            run.step(plan)?;
        }
        round += 1;
        let active: Vec<&str> = runs
            .iter()
            .filter(|(_, r)| !r.done(plan))
            .map(|(l, _)| l.as_str())
            .collect();
        let total = if plan.budget.is_some() {
            "?".to_string()
        } else {
            plan.frames.to_string()
        };
        eprint!(
            "\rframe {round}/{total}, {} configurations still running   ",
            active.len()
        );
        let _ = std::io::stderr().flush();
    }
    eprintln!();
    runs.into_iter().map(|(_, r)| r.finish()).collect()
}
