//! Per-frame counters read back from the GPU (rejections by reason, selection sources,
//! M-cap hits, permutation fallbacks, non-finite values per pass) and their summary
//! over a run, as written to `--stats` JSON.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::shader_constants::*;

/// The raw counters of one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameCounters(pub Vec<u32>);

impl FrameCounters {
    pub fn get(&self, index: u32) -> u64 {
        self.0.get(index as usize).copied().unwrap_or(0) as u64
    }

    pub fn add(&mut self, other: &FrameCounters) {
        if self.0.len() < other.0.len() {
            self.0.resize(other.0.len(), 0);
        }
        for (a, b) in self.0.iter_mut().zip(&other.0) {
            *a = a.saturating_add(*b);
        }
    }

    pub fn surface_pixels(&self) -> u64 {
        self.get(STAT_SURFACE_PIXELS)
    }

    pub fn non_finite_total(&self) -> u64 {
        let di: u64 = (0..GUARDED_PASS_NAMES.len() as u32)
            .map(|p| self.get(STAT_NONFINITE + p))
            .sum();
        let gi: u64 = (0..INDIRECT_GUARDED_PASS_NAMES.len() as u32)
            .map(|p| self.get(STAT_INDIRECT_NONFINITE + p))
            .sum();
        di + gi
    }
}

/// One frame's report: its counters, per-pass times (when timing is on) and, while a
/// pixel is inspected, that pixel's reservoirs.
#[derive(Clone, Debug, Default)]
pub struct FrameReport {
    pub frame: u64,
    pub counters: FrameCounters,
    pub pass_ms: Vec<(&'static str, f64)>,
    pub inspection: Option<super::PixelInspection>,
}

impl FrameReport {
    pub fn gpu_ms(&self) -> f64 {
        self.pass_ms.iter().map(|(_, ms)| ms).sum()
    }
}

/// Summary of a run of frames, the shape of `--stats` JSON.
#[derive(Clone, Debug, Default, Serialize)]
pub struct StatsSummary {
    pub frames: u64,
    /// Median over frames of each pass's GPU time (missing when timestamps are unsupported).
    pub pass_ms_median: BTreeMap<String, f64>,
    pub frame_gpu_ms_median: Option<f64>,
    /// Pixels of the output image with a NaN or infinite channel.
    pub nan_inf_pixels: u64,
    /// Non-finite values each pass produced or read (and replaced), summed over frames.
    pub non_finite_by_pass: BTreeMap<String, u64>,
    pub temporal_rejections: BTreeMap<String, u64>,
    pub spatial_rejections: BTreeMap<String, u64>,
    /// ReSTIR GI's counters, when it ran (`gi` in the JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gi: Option<IndirectStats>,
    /// ReSTIR PT's counters, when it ran (`pt` in the JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pt: Option<IndirectStats>,
    /// Fraction of surface pixels whose survivor came from each source.
    pub source_fractions: BTreeMap<String, f64>,
    /// Fraction of surface pixels where the temporal or spatial M cap fired.
    pub temporal_cap_fired_fraction: f64,
    pub spatial_cap_fired_fraction: f64,
    pub temporal_accepted_fraction: f64,
    pub fallback_tried: u64,
    pub fallback_used: u64,
    pub boiling_dropped: u64,
    pub surface_pixels: u64,
    /// Shadow rays per surface pixel and frame, by DI pass (passes that traced none are left
    /// out), and their total.
    pub shadow_rays_per_pixel: BTreeMap<String, f64>,
    pub shadow_rays_per_pixel_total: f64,
    /// The share of DI's light candidates with a non-zero unshadowed contribution: how much
    /// of the light sampler's work can pay (docs/src/light-samplers.md).
    pub useful_candidate_share: f64,
    /// DI's initial light candidates per surface pixel and frame: with the shadow rays, the
    /// hardware-neutral cost of a configuration (docs/src/measured/how-the-bench-measures.md,
    /// "Equal error").
    pub light_candidates_per_pixel: f64,
    /// MCMC mutation steps per surface pixel and frame, and the share accepted (0 with
    /// none tried; docs/src/mcmc-mutation.md).
    pub mutations_per_pixel: f64,
    pub mutation_acceptance: f64,
}

/// What an indirect technique (ReSTIR GI or PT) counted: its block of `--stats`, under
/// the technique's name.
#[derive(Clone, Debug, Default, Serialize)]
pub struct IndirectStats {
    /// Frames it shaded.
    pub frames: u64,
    /// Its temporal and spatial rejections by reason (DI's reasons, then GI's
    /// reconnection ones).
    pub temporal_rejections: BTreeMap<String, u64>,
    pub spatial_rejections: BTreeMap<String, u64>,
    /// Fraction of surface pixels whose temporal candidate was merged.
    pub temporal_accepted_fraction: f64,
    /// Retries of the plain reprojection after a failed permuted read, and those that passed.
    pub fallback_tried: u64,
    pub fallback_used: u64,
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// `part / whole`, 0 when there is no whole.
fn share_of(part: u64, whole: u64) -> f64 {
    if whole > 0 {
        part as f64 / whole as f64
    } else {
        0.0
    }
}

impl StatsSummary {
    pub fn from_reports(reports: &[FrameReport], nan_inf_pixels: u64) -> StatsSummary {
        let mut total = FrameCounters::default();
        let mut per_pass: BTreeMap<String, Vec<f64>> = BTreeMap::new();
        for r in reports {
            total.add(&r.counters);
            // A pass recorded several times in a frame (spatial passes) counts as its sum.
            let mut frame: BTreeMap<&str, f64> = BTreeMap::new();
            for (name, ms) in &r.pass_ms {
                *frame.entry(name).or_default() += ms;
            }
            for (name, ms) in frame {
                per_pass.entry(name.to_string()).or_default().push(ms);
            }
        }
        let frame_times: Vec<f64> = reports
            .iter()
            .filter(|r| !r.pass_ms.is_empty())
            .map(|r| r.gpu_ms())
            .collect();
        let surface = total.surface_pixels();
        let fraction = |n: u64| {
            if surface > 0 {
                n as f64 / surface as f64
            } else {
                0.0
            }
        };
        let named = |base: u32| -> BTreeMap<String, u64> {
            REJECT_REASON_NAMES
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), total.get(base + i as u32)))
                .collect()
        };
        let gi_named = |base: u32| -> BTreeMap<String, u64> {
            GI_REJECT_REASON_NAMES
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), total.get(base + i as u32)))
                .collect()
        };
        // The indirect technique that ran (GI and PT never run together): its block, and the
        // name its passes' counters go under.
        let frames_of = |technique: u32| total.get(STAT_INDIRECT_FRAMES + technique);
        let indirect = |technique: u32| {
            (frames_of(technique) > 0).then(|| IndirectStats {
                frames: frames_of(technique),
                temporal_rejections: gi_named(STAT_INDIRECT_TEMPORAL_REJECT),
                spatial_rejections: gi_named(STAT_INDIRECT_SPATIAL_REJECT),
                temporal_accepted_fraction: fraction(total.get(STAT_INDIRECT_TEMPORAL_ACCEPTED)),
                fallback_tried: total.get(STAT_INDIRECT_FALLBACK_TRIED),
                fallback_used: total.get(STAT_INDIRECT_FALLBACK_USED),
            })
        };
        let indirect_name =
            INDIRECT_NAMES[(frames_of(INDIRECT_PT) > frames_of(INDIRECT_GI)) as usize];
        // Surface pixels are counted every frame, so this is per pixel and frame.
        let rays: BTreeMap<String, f64> = GUARDED_PASS_NAMES
            .iter()
            .enumerate()
            .map(|(i, n)| (n, total.get(STAT_SHADOW_RAYS + i as u32)))
            .filter(|(_, count)| *count > 0)
            .map(|(n, count)| (n.to_string(), fraction(count)))
            .collect();
        StatsSummary {
            frames: reports.len() as u64,
            pass_ms_median: per_pass
                .into_iter()
                .filter_map(|(k, v)| Some((k, median(v)?)))
                .collect(),
            frame_gpu_ms_median: median(frame_times),
            nan_inf_pixels,
            non_finite_by_pass: GUARDED_PASS_NAMES
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), total.get(STAT_NONFINITE + i as u32)))
                .chain(
                    INDIRECT_GUARDED_PASS_NAMES
                        .iter()
                        .enumerate()
                        .map(|(i, n)| {
                            (
                                format!("{indirect_name} {n}"),
                                total.get(STAT_INDIRECT_NONFINITE + i as u32),
                            )
                        }),
                )
                .collect(),
            gi: indirect(INDIRECT_GI),
            pt: indirect(INDIRECT_PT),
            temporal_rejections: named(STAT_TEMPORAL_REJECT),
            spatial_rejections: named(STAT_SPATIAL_REJECT),
            source_fractions: SOURCE_NAMES
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), fraction(total.get(STAT_SOURCE + i as u32))))
                .collect(),
            temporal_cap_fired_fraction: fraction(total.get(STAT_TEMPORAL_CAP)),
            spatial_cap_fired_fraction: fraction(total.get(STAT_SPATIAL_CAP)),
            temporal_accepted_fraction: fraction(total.get(STAT_TEMPORAL_ACCEPTED)),
            fallback_tried: total.get(STAT_FALLBACK_TRIED),
            fallback_used: total.get(STAT_FALLBACK_USED),
            boiling_dropped: total.get(STAT_BOILING_DROPPED),
            surface_pixels: surface,
            shadow_rays_per_pixel: rays.clone(),
            // From +0: an empty f64 sum is −0, which the CSV would print as "-0".
            shadow_rays_per_pixel_total: rays.values().fold(0.0, |a, b| a + b),
            light_candidates_per_pixel: fraction(total.get(STAT_LIGHT_CANDIDATES)),
            useful_candidate_share: share_of(
                total.get(STAT_USEFUL_CANDIDATES),
                total.get(STAT_LIGHT_CANDIDATES),
            ),
            mutations_per_pixel: fraction(total.get(STAT_MUTATIONS_TRIED)),
            mutation_acceptance: share_of(
                total.get(STAT_MUTATIONS_ACCEPTED),
                total.get(STAT_MUTATIONS_TRIED),
            ),
        }
    }

    pub fn non_finite_total(&self) -> u64 {
        self.non_finite_by_pass.values().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_fractions_and_medians() {
        let mut c = vec![0u32; STAT_COUNT as usize];
        c[STAT_SURFACE_PIXELS as usize] = 100;
        c[(STAT_SOURCE + SOURCE_TEMPORAL) as usize] = 60;
        c[(STAT_SOURCE + SOURCE_INITIAL) as usize] = 40;
        c[(STAT_TEMPORAL_REJECT + 1) as usize] = 7;
        c[(STAT_SHADOW_RAYS + PASS_SPATIAL) as usize] = 250;
        let reports: Vec<_> = [1.0, 3.0, 2.0]
            .iter()
            .enumerate()
            .map(|(i, ms)| FrameReport {
                frame: i as u64,
                counters: FrameCounters(c.clone()),
                pass_ms: vec![("shade", *ms)],
                inspection: None,
            })
            .collect();
        let s = StatsSummary::from_reports(&reports, 0);
        assert_eq!(s.frames, 3);
        assert_eq!(s.pass_ms_median["shade"], 2.0);
        assert!((s.source_fractions["temporal"] - 0.6).abs() < 1e-12);
        assert_eq!(s.temporal_rejections["surface_invalid"], 21);
        assert_eq!(s.non_finite_total(), 0);
        // 250 rays over 100 surface pixels each frame: 2.5 per pixel, the only pass listed.
        assert_eq!(s.shadow_rays_per_pixel.len(), 1);
        assert!((s.shadow_rays_per_pixel["spatial"] - 2.5).abs() < 1e-12);
        assert!((s.shadow_rays_per_pixel_total - 2.5).abs() < 1e-12);
        // No indirect technique ran: no block.
        assert!(s.gi.is_none() && s.pt.is_none());
        assert!(s.non_finite_by_pass.contains_key("gi initial"));
    }

    /// The indirect counters go under the technique that ran (PT's used to read as GI's).
    #[test]
    fn the_indirect_block_is_named_after_the_technique_that_ran() {
        let mut c = vec![0u32; STAT_COUNT as usize];
        c[STAT_SURFACE_PIXELS as usize] = 10;
        c[(STAT_INDIRECT_FRAMES + INDIRECT_PT) as usize] = 1;
        c[(STAT_INDIRECT_TEMPORAL_REJECT + 1) as usize] = 3;
        c[(STAT_INDIRECT_NONFINITE + INDIRECT_PASS_SPATIAL) as usize] = 2;
        let report = FrameReport {
            frame: 0,
            counters: FrameCounters(c),
            pass_ms: vec![],
            inspection: None,
        };
        let s = StatsSummary::from_reports(&[report], 0);
        assert!(s.gi.is_none());
        let pt = s.pt.as_ref().expect("pt ran");
        assert_eq!(
            (pt.frames, pt.temporal_rejections["surface_invalid"]),
            (1, 3)
        );
        assert_eq!(s.non_finite_by_pass["pt spatial"], 2);
        let json = serde_json::to_value(&s).unwrap();
        assert!(
            json.get("pt").is_some() && json.get("gi").is_none(),
            "{json}"
        );
    }
}
