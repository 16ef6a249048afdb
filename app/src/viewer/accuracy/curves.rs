//! The accuracy panel's curves: one per pipeline configuration (mode + parameters), a
//! point per measured frame. A new configuration starts a new curve; the previous few
//! stay for comparison, labelled by what changed ("temporal off"), which is the question
//! the panel answers: what did this change remove in error, and what did it cost in time.

use std::collections::VecDeque;

use restir_render::settings::PARAMS;
use restir_render::stats::{FrameReport, StatsSummary};
use restir_render::{Mode, Settings};

/// What a curve measures. View settings (debug view, exposure, accumulation) are not
/// part of it: they never change the estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct Config {
    pub mode: Mode,
    pub settings: Settings,
}

/// One measured frame.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePoint {
    /// Frames since the curve started, from 1; throttled measuring leaves gaps.
    pub x: u64,
    /// The renderer's frame index (what `FrameReport::frame` names).
    pub frame: u64,
    /// Per-frame accuracy: luma RMSE of this frame against the reference.
    pub luma_rmse: f64,
    /// Luma RMSE against the previous measured frame (None for the first).
    pub stability: Option<f64>,
    /// RGB RMSE of the average of the measured frames so far.
    pub accumulated_rgb_rmse: f64,
    /// Mean luminance of that average over the reference's (1 = no energy bias).
    pub luma_ratio: f64,
    /// Signed bias: (mean luminance − the reference's) / the reference's, per measured frame,
    /// averaged over the curve so far (0 = none, negative = too dark).
    pub signed_bias: f64,
    /// The frame's pass times, filled in when its report comes back (a frame or two
    /// later); empty when passes are not timed.
    pub pass_ms: Vec<(&'static str, f64)>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Unique while the viewer runs: picks the curve's colour, which it keeps when dimmed.
    pub id: u64,
    pub label: String,
    pub config: Config,
    /// The renderer frame index of the curve's first frame.
    pub first_frame: u64,
    pub points: Vec<CurvePoint>,
}

impl Curve {
    pub fn last(&self) -> Option<&CurvePoint> {
        self.points.last()
    }

    pub fn mean_luma_rmse(&self) -> Option<f64> {
        mean(self.points.iter().map(|p| p.luma_rmse))
    }

    pub fn mean_stability(&self) -> Option<f64> {
        mean(self.points.iter().filter_map(|p| p.stability))
    }

    /// Median per-pass and per-frame milliseconds over the points whose times came back,
    /// summarised exactly as the Stats panel and `--stats` do.
    pub fn time_summary(&self) -> StatsSummary {
        let reports: Vec<FrameReport> = self
            .points
            .iter()
            .filter(|p| !p.pass_ms.is_empty())
            .map(|p| FrameReport {
                frame: p.frame,
                pass_ms: p.pass_ms.clone(),
                ..Default::default()
            })
            .collect();
        StatsSummary::from_reports(&reports, 0)
    }
}

fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

/// The current curve and the ones kept for comparison.
#[derive(Clone, Debug, Default)]
pub struct Curves {
    pub current: Option<Curve>,
    /// Earlier curves, newest first (drawn dimmed).
    pub previous: VecDeque<Curve>,
    next_id: u64,
    /// Why the current curve ended, for the next label when the configuration did not
    /// change (e.g. a new reference).
    ended_because: Option<String>,
}

impl Curves {
    /// Earlier curves kept: enough to compare a few toggles, few enough to read.
    pub const KEEP: usize = 3;

    /// The id of the curve a frame of `config` (renderer frame `frame`) belongs to: the
    /// current curve, or a new one when the configuration differs from it.
    pub fn curve_for(&mut self, config: &Config, frame: u64) -> u64 {
        if let Some(current) = &self.current
            && current.config == *config
        {
            return current.id;
        }
        self.end_current(None);
        let label = match self.previous.front() {
            Some(before) => {
                let change = describe_change(&before.config, config);
                match (change.is_empty(), self.ended_because.take()) {
                    (false, _) => change,
                    (true, Some(reason)) => format!("{} ({reason})", config.mode.name()),
                    (true, None) => config.mode.name().to_string(),
                }
            }
            None => config.mode.name().to_string(),
        };
        self.ended_because = None;
        let id = self.next_id;
        self.next_id += 1;
        self.current = Some(Curve {
            id,
            label,
            config: config.clone(),
            first_frame: frame,
            points: Vec::new(),
        });
        id
    }

    /// Ends the current curve (kept as the newest previous one if it has points);
    /// `reason` labels the next curve if its configuration is the same.
    pub fn end_current(&mut self, reason: Option<&str>) {
        if let Some(curve) = self.current.take()
            && !curve.points.is_empty()
        {
            self.previous.push_front(curve);
            self.previous.truncate(Self::KEEP);
        }
        if let Some(reason) = reason {
            self.ended_because = Some(reason.to_string());
        }
    }

    /// Adds a point to the current curve (started by `curve_for`).
    pub fn push(&mut self, point: CurvePoint) {
        if let Some(current) = &mut self.current {
            current.points.push(point);
        }
    }

    /// Files a frame report's pass times under the point of that frame, if measured.
    pub fn record_report(&mut self, report: &FrameReport) {
        let curves = self.current.iter_mut().chain(self.previous.iter_mut());
        if let Some(point) = curves
            .flat_map(|c| c.points.iter_mut().rev())
            .find(|p| p.frame == report.frame)
        {
            point.pass_ms = report.pass_ms.clone();
        }
    }

    /// Forgets every curve (the view changed: they measured another image).
    pub fn clear(&mut self) {
        self.current = None;
        self.previous.clear();
        self.ended_because = None;
    }

    /// Every curve, oldest first (so the current one is drawn on top), with whether it
    /// is the current one.
    pub fn all(&self) -> impl Iterator<Item = (&Curve, bool)> {
        let previous = self.previous.iter().rev().map(|c| (c, false));
        previous.chain(self.current.iter().map(|c| (c, true)))
    }

    pub fn is_empty(&self) -> bool {
        self.all().next().is_none()
    }
}

/// The differences of `new` from `old` in the parameter table's names: "temporal off",
/// "m_cap 5", "mode ris"; at most three, then "+N more".
pub fn describe_change(old: &Config, new: &Config) -> String {
    let mut changes = Vec::new();
    if old.mode != new.mode {
        changes.push(format!("mode {}", new.mode.name()));
    }
    for def in PARAMS {
        let (before, after) = (old.settings.get(def.name), new.settings.get(def.name));
        if before == after {
            continue;
        }
        changes.push(match after {
            Some(restir_render::settings::ParamValue::Bool(on)) => {
                format!("{} {}", def.name, if on { "on" } else { "off" })
            }
            Some(value) => format!("{} {value}", def.name),
            None => def.name.to_string(),
        });
    }
    const SHOWN: usize = 3;
    if changes.len() > SHOWN {
        let more = changes.len() - (SHOWN - 1);
        changes.truncate(SHOWN - 1);
        changes.push(format!("+{more} more"));
    }
    changes.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(edit: impl FnOnce(&mut Settings)) -> Config {
        let mut settings = Settings::default();
        edit(&mut settings);
        Config {
            mode: Mode::Restir,
            settings,
        }
    }

    fn point(x: u64, frame: u64) -> CurvePoint {
        CurvePoint {
            x,
            frame,
            luma_rmse: 0.1,
            stability: None,
            accumulated_rgb_rmse: 0.05,
            luma_ratio: 1.0,
            signed_bias: 0.0,
            pass_ms: Vec::new(),
        }
    }

    #[test]
    fn changes_are_named_as_in_the_parameter_table() {
        let base = config(|_| {});
        let off = config(|s| s.temporal = false);
        assert_eq!(describe_change(&base, &off), "temporal off");
        assert_eq!(describe_change(&off, &base), "temporal on");
        let capped = config(|s| s.m_cap = 5.0);
        assert_eq!(describe_change(&base, &capped), "m_cap 5");
        let ris = Config {
            mode: Mode::Ris,
            ..base.clone()
        };
        assert_eq!(describe_change(&base, &ris), "mode ris");
        let many = config(|s| {
            s.temporal = false;
            s.spatial = false;
            s.jitter = false;
            s.m_cap = 5.0;
        });
        assert_eq!(describe_change(&base, &many).matches(", ").count(), 2);
        assert!(describe_change(&base, &many).ends_with("+2 more"));
    }

    #[test]
    fn a_new_configuration_starts_a_curve_and_keeps_a_few_old_ones() {
        let mut curves = Curves::default();
        let base = config(|_| {});
        let first = curves.curve_for(&base, 10);
        curves.push(point(1, 10));
        assert_eq!(curves.curve_for(&base, 11), first, "same configuration");
        let off = config(|s| s.temporal = false);
        let second = curves.curve_for(&off, 12);
        assert_ne!(second, first);
        assert_eq!(curves.current.as_ref().unwrap().label, "temporal off");
        assert_eq!(curves.previous.len(), 1);
        // An empty curve is replaced, not kept.
        curves.curve_for(&base, 13);
        assert_eq!(curves.previous.len(), 1);
        for i in 0..2 * Curves::KEEP as u64 {
            curves.curve_for(&config(|s| s.m_cap = i as f32 + 2.0), 20 + i);
            curves.push(point(1, 20 + i));
        }
        assert_eq!(curves.previous.len(), Curves::KEEP);
        assert_eq!(curves.all().count(), Curves::KEEP + 1);
        assert!(
            curves.all().last().unwrap().1,
            "the current curve comes last"
        );
    }

    #[test]
    fn a_new_reference_restarts_the_curve_with_a_reason() {
        let mut curves = Curves::default();
        let base = config(|_| {});
        curves.curve_for(&base, 0);
        curves.push(point(1, 0));
        curves.end_current(Some("new reference"));
        curves.curve_for(&base, 5);
        assert_eq!(
            curves.current.as_ref().unwrap().label,
            "restir (new reference)"
        );
    }

    #[test]
    fn reports_fill_in_the_pass_times_of_their_frame() {
        let mut curves = Curves::default();
        curves.curve_for(&config(|_| {}), 7);
        curves.push(point(1, 7));
        curves.push(point(2, 8));
        curves.record_report(&FrameReport {
            frame: 8,
            pass_ms: vec![("shade", 2.0), ("initial", 1.0)],
            ..Default::default()
        });
        let curve = curves.current.as_ref().unwrap();
        assert!(curve.points[0].pass_ms.is_empty());
        let summary = curve.time_summary();
        assert_eq!(summary.frame_gpu_ms_median, Some(3.0));
        assert_eq!(summary.pass_ms_median["shade"], 2.0);
    }
}
