//! The references of a bench, one set per `max_bounces` its configurations use, and the
//! jitter phases a still, jittered shot needs references of.

use restir_render::Renderer;
use restir_render::renderer::{JITTER_PERIOD, jitter_phase};
use restir_render::timeline::AnimatedScene;

use super::references::{ReferencePlan, References, obtain};
use super::shot::Shot;

/// The jitter phases of the measured frames of every configuration when every seed runs
/// `measured` frames after `warmup` (ConfigRun::start renders two compile frames and the
/// warm-up on each configuration's own renderer, which renders nothing else), or every
/// phase when the frame count is not known in advance (equal time).
pub fn measured_phases(seeds: u32, warmup: u32, measured: Option<u32>) -> Vec<u32> {
    let Some(measured) = measured else {
        return (0..JITTER_PERIOD as u32).collect();
    };
    let per_seed = (2 + warmup + measured) as u64;
    let mut phases: Vec<u32> = (0..seeds as u64)
        .flat_map(|k| {
            (0..measured as u64).map(move |i| jitter_phase(k * per_seed + 2 + warmup as u64 + i))
        })
        .collect();
    phases.sort_unstable();
    phases.dedup();
    phases
}

/// The references of a bench: one set per `max_bounces` its configurations use, so each
/// configuration is scored against the integral it estimates (`path-2b` against a
/// 2-bounce reference, `ris` against the direct-light one).
pub struct ReferenceSets {
    /// (max_bounces, references), in the order the configurations first use them.
    sets: Vec<(u32, References)>,
}

impl ReferenceSets {
    /// [`obtain`] once per distinct value in `bounces` (the configurations' max_bounces).
    pub fn obtain(
        renderer: &mut Renderer,
        plan: &ReferencePlan,
        shot: &Shot,
        (first, count): (u32, u32),
        mut clock: Option<&mut AnimatedScene>,
        bounces: impl IntoIterator<Item = u32>,
    ) -> anyhow::Result<ReferenceSets> {
        let mut sets: Vec<(u32, References)> = Vec::new();
        for b in bounces {
            if sets.iter().any(|(have, _)| *have == b) {
                continue;
            }
            let plan = ReferencePlan {
                max_bounces: b,
                ..plan.clone()
            };
            let refs = obtain(renderer, &plan, shot, first, count, clock.as_deref_mut())?;
            sets.push((b, refs));
        }
        anyhow::ensure!(
            !sets.is_empty(),
            "no configuration to obtain references for"
        );
        Ok(ReferenceSets { sets })
    }

    /// The references of configurations with `max_bounces` (obtained for every one).
    pub fn for_bounces(&self, max_bounces: u32) -> &References {
        self.sets
            .iter()
            .find(|(b, _)| *b == max_bounces)
            .map(|(_, r)| r)
            .expect("references are obtained for every configuration's max_bounces")
    }

    /// The first configuration's references: what the report's reference line, the
    /// strip and the light events use.
    pub fn primary(&self) -> &References {
        &self.sets[0].1
    }

    /// The bounce counts with references, in order.
    pub fn bounces(&self) -> impl Iterator<Item = (u32, &References)> {
        self.sets.iter().map(|(b, r)| (*b, r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_measured_frames_phases_follow_each_renderers_frame_count() {
        // Two compile frames, then 3 measured: frames 2, 3, 4; the next seed starts at 5.
        assert_eq!(measured_phases(2, 0, Some(3)), vec![2, 3, 4, 7, 8, 9]);
        // 62 warm-up frames: the measured frames 64..67 wrap to phases 0..3.
        assert_eq!(measured_phases(1, 62, Some(4)), vec![0, 1, 2, 3]);
        assert_eq!(measured_phases(1, 0, None).len(), JITTER_PERIOD as usize);
    }
}
