//! Frames in, the numbers of docs/src/measured/how-the-bench-measures.md ("How it measures")
//! out, using the renderer's metrics (`SequenceMetrics` for a still camera). With a moving
//! camera each frame has its own reference: per-frame accuracy is measured against it,
//! stability is the luma RMSE between consecutive *error* images (frame − its reference; for a
//! still camera that is exactly the frame-to-frame RMSE, and with motion it leaves out the true
//! change of the image), the luma ratio is averaged over frames, and the running average is not
//! defined (n/a).

use restir_render::LinearImage;
use restir_render::metrics::detail::Edges;
use restir_render::metrics::motion_masks::{MaskedError, MotionMasks};
use restir_render::metrics::pixel_moments::PixelMoments;
use restir_render::metrics::{
    SequenceMetrics, black_pixel_fraction, low_frequency_rmse, luma_ratio, luma_rmse, rel_mse,
};
use restir_render::phase_references::PhaseReferences;

use super::frame_figures::{DetailTrack, FrameScores, MaskedFigures, ScoreSummary, mean};

pub enum Scoring<'a> {
    /// Timing only (the light-count sweep).
    Off,
    Still {
        reference: &'a LinearImage,
        sequence: SequenceMetrics,
        low_frequency: Vec<f64>,
        /// Per pixel, what the figures over seeds need (seed_figures.rs).
        moments: PixelMoments,
        /// Jitter on: each frame's per-frame error is measured against its jitter phase's
        /// reference (docs/src/viewer.md, "Accuracy with jitter on"), kept here.
        phases: Option<&'a PhaseReferences>,
        phase_luma: Vec<f64>,
        edges: Edges,
        detail: DetailTrack,
    },
    Moving {
        /// One per measured frame.
        references: &'a [LinearImage],
        /// One per measured frame, or none (no masks asked for).
        masks: &'a [MotionMasks],
        /// The references' own per-pixel luma noise.
        noise: f64,
        disoccluded: MaskedError,
        near_moving: MaskedError,
        detail: DetailTrack,
        previous_error: Option<LinearImage>,
        series: MovingSeries,
    },
}

/// A moving shot's figures, one entry per measured frame (the non-finite pixels summed).
#[derive(Default)]
pub struct MovingSeries {
    luma: Vec<f64>,
    stability: Vec<f64>,
    ratios: Vec<f64>,
    black: Vec<f64>,
    low_frequency: Vec<f64>,
    non_finite: usize,
}

impl<'a> Scoring<'a> {
    /// A still camera's scoring against `reference`; with `phases` (jitter on) each
    /// frame's per-frame error against its jitter phase's reference instead.
    /// `noise`: the reference's own per-pixel luma noise (the detail figures' edges stand
    /// above it).
    pub fn still(
        reference: &'a LinearImage,
        phases: Option<&'a PhaseReferences>,
        noise: f64,
    ) -> Scoring<'a> {
        Scoring::Still {
            reference,
            sequence: SequenceMetrics::new(reference.clone()),
            low_frequency: Vec::new(),
            moments: PixelMoments::new(reference.width, reference.height),
            phases,
            phase_luma: Vec::new(),
            edges: Edges::of(reference, noise),
            detail: DetailTrack::default(),
        }
    }

    /// A moving shot's scoring, each measured frame against its own reference and, where
    /// `masks` are given (one per measured frame), also within them.
    pub fn moving(
        references: &'a [LinearImage],
        masks: &'a [MotionMasks],
        noise: f64,
    ) -> Scoring<'a> {
        Scoring::Moving {
            references,
            noise,
            masks,
            disoccluded: MaskedError::default(),
            near_moving: MaskedError::default(),
            detail: DetailTrack::default(),
            previous_error: None,
            series: MovingSeries::default(),
        }
    }

    pub fn wants_images(&self) -> bool {
        !matches!(self, Scoring::Off)
    }

    /// Scores measured frame `index`, which the renderer rendered as its frame
    /// `frame_index` (its jitter phase's).
    pub fn push(
        &mut self,
        index: usize,
        frame_index: u64,
        frame: &LinearImage,
    ) -> anyhow::Result<FrameScores> {
        match self {
            Scoring::Off => Ok(FrameScores::default()),
            Scoring::Still {
                reference,
                sequence,
                low_frequency,
                moments,
                phases,
                phase_luma,
                edges,
                detail,
            } => {
                sequence.push(frame)?;
                moments.push(frame);
                detail.push(edges, frame, reference);
                if let Some(phases) = phases {
                    let own = phases.for_frame(frame_index).ok_or_else(|| {
                        anyhow::anyhow!("no reference for jitter phase of frame {frame_index}")
                    })?;
                    phase_luma.push(luma_rmse(frame, own)?);
                }
                low_frequency.push(low_frequency_rmse(frame, reference)?);
                let report = sequence.report();
                Ok(FrameScores {
                    luma_rmse: match phases {
                        Some(_) => phase_luma.last().copied(),
                        None => report.per_frame_luma_rmse.last().copied(),
                    },
                    stability: report
                        .per_frame_stability_rmse
                        .get(index.wrapping_sub(1))
                        .copied(),
                    accumulated_rgb_rmse: Some(report.accumulated_rgb_rmse),
                })
            }
            Scoring::Moving {
                references,
                masks,
                noise,
                disoccluded,
                near_moving,
                detail,
                previous_error,
                series,
            } => {
                let reference = references
                    .get(index)
                    .ok_or_else(|| anyhow::anyhow!("no reference for measured frame {index}"))?;
                if let Some(m) = masks.get(index) {
                    disoccluded.push(frame, reference, &m.disoccluded);
                    near_moving.push(frame, reference, &m.near_moving);
                }
                detail.push(&Edges::of(reference, *noise), frame, reference);
                let error = difference(frame, reference);
                series.non_finite += frame.non_finite_count();
                series.luma.push(luma_rmse(frame, reference)?);
                series.ratios.push(luma_ratio(frame, reference)?);
                series.black.push(black_pixel_fraction(frame, reference)?);
                series
                    .low_frequency
                    .push(low_frequency_rmse(frame, reference)?);
                let step = match previous_error {
                    Some(previous) => Some(luma_rmse(&error, previous)?),
                    None => None,
                };
                series.stability.extend(step);
                *previous_error = Some(error);
                Ok(FrameScores {
                    luma_rmse: series.luma.last().copied(),
                    stability: step,
                    accumulated_rgb_rmse: None,
                })
            }
        }
    }

    pub fn summary(&self) -> anyhow::Result<Option<ScoreSummary>> {
        Ok(match self {
            Scoring::Off => None,
            Scoring::Still {
                reference,
                sequence,
                low_frequency,
                phases,
                phase_luma,
                detail,
                ..
            } => {
                let report = sequence.report();
                Some(ScoreSummary {
                    mean_luma_rmse: match phases {
                        Some(_) => mean(phase_luma),
                        None => report.mean_luma_rmse,
                    },
                    antialiased_luma_rmse: phases.map(|_| report.mean_luma_rmse),
                    mean_stability: report.mean_stability_rmse,
                    accumulated_rgb_rmse: Some(report.accumulated_rgb_rmse),
                    accumulated_rel_mse: Some(rel_mse(&sequence.accumulated(), reference)?),
                    luma_ratio: report.accumulated_luma_ratio,
                    signed_bias: report.mean_signed_bias,
                    black_pixel_fraction: report.mean_black_pixel_fraction,
                    mean_low_frequency_rmse: mean(low_frequency),
                    non_finite_pixels: report.non_finite_pixels,
                    disoccluded: None,
                    near_moving: None,
                    detail: detail.summary(),
                })
            }
            Scoring::Moving {
                masks,
                disoccluded,
                near_moving,
                detail,
                series,
                ..
            } => Some(ScoreSummary {
                disoccluded: (!masks.is_empty()).then(|| MaskedFigures::of(disoccluded)),
                near_moving: (!masks.is_empty()).then(|| MaskedFigures::of(near_moving)),
                detail: detail.summary(),
                mean_luma_rmse: mean(&series.luma),
                antialiased_luma_rmse: None,
                mean_stability: mean(&series.stability),
                accumulated_rgb_rmse: None,
                accumulated_rel_mse: None,
                luma_ratio: mean(&series.ratios),
                signed_bias: mean(&series.ratios) - 1.0,
                black_pixel_fraction: mean(&series.black),
                mean_low_frequency_rmse: mean(&series.low_frequency),
                non_finite_pixels: series.non_finite,
            }),
        })
    }
}

impl Scoring<'_> {
    /// A still camera's per-pixel moments of the frames scored (None otherwise).
    pub fn into_moments(self) -> Option<PixelMoments> {
        match self {
            Scoring::Still { moments, .. } => Some(moments),
            _ => None,
        }
    }
}

/// frame − reference per channel (alpha 1): luminance is linear, so the luma RMSE of two
/// such images is the RMSE of the change of the luma error.
fn difference(frame: &LinearImage, reference: &LinearImage) -> LinearImage {
    let pixels = frame
        .pixels
        .iter()
        .zip(&reference.pixels)
        .map(|(f, r)| [f[0] - r[0], f[1] - r[1], f[2] - r[2], 1.0])
        .collect();
    LinearImage {
        width: frame.width,
        height: frame.height,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(v: f32) -> LinearImage {
        LinearImage::from_fn(4, 2, |_, _| [v, v, v, 1.0])
    }

    #[test]
    fn bench_moving_stability_ignores_the_true_change_of_the_image() {
        // Each frame is its reference + 0.1: the error never changes.
        let refs = [flat(1.0), flat(2.0), flat(3.0)];
        let mut s = Scoring::moving(&refs, &[], 0.0);
        for (i, r) in refs.iter().enumerate() {
            s.push(i, i as u64, &flat(r.pixels[0][0] + 0.1)).unwrap();
        }
        let summary = s.summary().unwrap().unwrap();
        assert!((summary.mean_luma_rmse - 0.1).abs() < 1e-6);
        assert!(summary.mean_stability.abs() < 1e-6);
        assert!(summary.accumulated_rgb_rmse.is_none());
    }

    #[test]
    fn bench_still_scores_match_sequence_metrics() {
        let reference = flat(1.0);
        let mut s = Scoring::still(&reference, None, 0.0);
        let a = s.push(0, 0, &flat(1.5)).unwrap();
        let b = s.push(1, 1, &flat(0.5)).unwrap();
        assert_eq!(a.stability, None);
        assert!((b.stability.unwrap() - 1.0).abs() < 1e-6);
        // The running average is exact after two frames.
        assert!(b.accumulated_rgb_rmse.unwrap() < 1e-6);
        let summary = s.summary().unwrap().unwrap();
        assert!((summary.luma_ratio - 1.0).abs() < 1e-6);
    }
}
