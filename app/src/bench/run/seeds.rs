//! Every seed runs every configuration: seeds S..S+K one after another, each running all
//! configurations interleaved on their own renderers (run_loop.rs) from a clean history,
//! each configuration scored against the references of its own max_bounces.

use restir_render::Renderer;
use restir_render::metrics::motion_masks::MotionMasks;

use super::Bench;
use super::events::LagProbe;
use super::references::References;
use super::run_loop::{ConfigRun, RunPlan, run_interleaved};
use super::shot::Shot;
use crate::bench::plan::configs::Config;
use crate::bench::score::result::ConfigResult;
use crate::bench::score::scoring::Scoring;

/// `seeds` runs of every configuration of `configs`: `[configuration][seed]`. The
/// renderers come back to `bench` after each seed, holding its last frames.
pub fn every_seed(
    bench: &mut Bench,
    configs: &[Config],
    seeds: u32,
) -> anyhow::Result<Vec<Vec<ConfigResult>>> {
    let mut per_seed: Vec<Vec<ConfigResult>> = vec![Vec::new(); configs.len()];
    for k in 0..seeds {
        let plan = RunPlan {
            seed: bench.run_plan.seed.wrapping_add(k),
            ..bench.run_plan.clone()
        };
        if seeds > 1 {
            eprintln!("seed {} ({}/{})", plan.seed, k + 1, seeds);
        }
        let renderers = std::mem::take(&mut bench.renderers);
        let (seed_results, back) = one_seed(bench, renderers, configs, &plan, k == 0)?;
        bench.renderers = back;
        for (all, r) in per_seed.iter_mut().zip(seed_results) {
            all.push(r);
        }
    }
    Ok(per_seed)
}

/// One seed's run of every configuration, each on its renderer of `renderers`; the
/// results and the renderers back. The first seed keeps the frames of the event strip and,
/// for a still shot, each configuration's last frame (the strip's).
fn one_seed(
    bench: &Bench,
    renderers: Vec<Renderer>,
    configs: &[Config],
    plan: &RunPlan,
    first_seed: bool,
) -> anyhow::Result<(Vec<ConfigResult>, Vec<Renderer>)> {
    let runs = configs
        .iter()
        .zip(renderers)
        .map(|(c, r)| {
            let own = bench.references.for_bounces(c.settings.reference_bounces());
            let probe = bench
                .events
                .as_ref()
                .map(|e| LagProbe::new(e, &own.images, first_seed));
            let scoring = scoring_for(own, &bench.shot, &bench.masks);
            let run = ConfigRun::start(r, c, plan, scoring, bench.clock(), probe)?;
            Ok((c.name.clone(), run))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let mut done = run_interleaved(runs, plan)?;
    // Seed S's last frames for the strip, before the next seed renders over them.
    if first_seed && !bench.shot.moves() {
        for (result, renderer) in &mut done {
            result.last_frame = Some(renderer.read_radiance());
        }
    }
    Ok(done.into_iter().unzip())
}

/// A still shot scores every frame against one reference (with jitter on, against its
/// jitter phase's); a moving one each frame against its own, within the masks.
fn scoring_for<'a>(refs: &'a References, shot: &Shot, masks: &'a [MotionMasks]) -> Scoring<'a> {
    let noise = refs.noise_luma_rmse.unwrap_or(0.0);
    if shot.moves() {
        Scoring::moving(&refs.images, masks, noise)
    } else {
        Scoring::still(&refs.images[0], refs.phases.as_ref(), noise)
    }
}
