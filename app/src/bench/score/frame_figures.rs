//! What scoring gives: one frame's numbers (`FrameScores`, with its time in `FrameRecord`)
//! and a run's (`ScoreSummary`; docs/src/measured/how-the-bench-measures.md, "How it
//! measures"), with the figures within a moving shot's masks and within the reference's
//! edges. `scoring.rs` computes them.

use restir_render::LinearImage;
use restir_render::metrics::LOW_FREQUENCY_TILE;
use restir_render::metrics::detail::{DetailFigures, Edges};
use restir_render::metrics::motion_masks::MaskedError;

/// One frame's numbers.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameScores {
    pub luma_rmse: Option<f64>,
    pub stability: Option<f64>,
    pub accumulated_rgb_rmse: Option<f64>,
}

/// One measured frame: its time and its scores (the run loop records it, the event
/// probe and the plots read it).
#[derive(Clone, Debug, PartialEq)]
pub struct FrameRecord {
    /// 0 = first measured frame.
    pub index: usize,
    /// Sum of the frame's pass times.
    pub ms: f64,
    pub cumulative_ms: f64,
    pub scores: FrameScores,
}

/// A run's numbers (docs/src/measured/how-the-bench-measures.md, "How it measures").
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScoreSummary {
    /// Per-frame accuracy: luma RMSE vs the reference (with jitter on, each frame's jitter
    /// phase's), mean over frames.
    pub mean_luma_rmse: f64,
    /// Jitter on: the same against the antialiased reference, which measures the pixel
    /// footprint more than the estimator (docs/src/viewer.md, "Accuracy with jitter on").
    pub antialiased_luma_rmse: Option<f64>,
    /// Frame-to-frame luma RMSE (of the error images with a moving camera), mean.
    pub mean_stability: f64,
    /// RGB RMSE of the running average (still camera only).
    pub accumulated_rgb_rmse: Option<f64>,
    /// Relative MSE of the running average (still camera only).
    pub accumulated_rel_mse: Option<f64>,
    /// mean luminance(average) / mean luminance(reference) (still camera), or the mean over
    /// frames of the per-frame ratio (moving camera).
    pub luma_ratio: f64,
    /// Signed bias, (mean luminance of a frame − the reference's) / the reference's, averaged
    /// over frames (each against its own reference with a moving camera).
    pub signed_bias: f64,
    /// Per frame, the fraction of pixels black where the reference is lit (speckles), mean.
    pub black_pixel_fraction: f64,
    /// Per-frame luma error averaged over 8 × 8 tiles, RMS over tiles, mean over frames:
    /// the correlated (blotchy) part of the error that RMSE cannot see
    /// (`metrics::low_frequency_rmse`).
    pub mean_low_frequency_rmse: f64,
    /// Non-finite pixels seen (each skipped by the metrics).
    pub non_finite_pixels: usize,
    /// Moving shot: the error in each frame's disoccluded pixels and in those near moving
    /// triangles (`metrics::motion_masks`; docs/src/measured/how-the-bench-measures.md, "Errors
    /// where the view moves").
    pub disoccluded: Option<MaskedFigures>,
    pub near_moving: Option<MaskedFigures>,
    /// Within the reference's strong edges (`metrics::detail`;
    /// docs/src/measured/how-the-bench-measures.md, "Shadow detail"), means over frames: their
    /// share of the pixels, the luma RMSE there and the detail each frame keeps (1 = as sharp
    /// as the reference) and FLIP there. None without edges.
    pub detail: Option<DetailSummary>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DetailSummary {
    pub share: f64,
    pub luma_rmse: f64,
    pub kept: f64,
    /// Mean FLIP within the edges (`metrics::flip`).
    pub flip: f64,
}

/// Per-frame detail figures, averaged at the end.
#[derive(Clone, Debug, Default)]
pub struct DetailTrack {
    share: Vec<f64>,
    frames: Vec<DetailFigures>,
}

impl DetailTrack {
    pub fn push(&mut self, edges: &Edges, frame: &LinearImage, reference: &LinearImage) {
        if let Some(f) = edges.figures(frame, reference) {
            self.share.push(edges.share());
            self.frames.push(f);
        }
    }

    pub fn summary(&self) -> Option<DetailSummary> {
        (!self.frames.is_empty()).then(|| DetailSummary {
            share: mean(&self.share),
            luma_rmse: mean(&self.frames.iter().map(|f| f.luma_rmse).collect::<Vec<_>>()),
            kept: mean(&self.frames.iter().map(|f| f.kept).collect::<Vec<_>>()),
            flip: mean(&self.frames.iter().map(|f| f.flip).collect::<Vec<_>>()),
        })
    }
}

/// One mask's numbers over a run's frames (pooled over its pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaskedFigures {
    /// Marked pixels over all pixels of the measured frames.
    pub share: f64,
    /// None where no pixel was marked.
    pub luma_rmse: Option<f64>,
    pub signed_bias: Option<f64>,
}

impl MaskedFigures {
    pub fn of(e: &MaskedError) -> MaskedFigures {
        MaskedFigures {
            share: e.share(),
            luma_rmse: e.luma_rmse(),
            signed_bias: e.signed_bias(),
        }
    }
}

impl ScoreSummary {
    /// 8 × low-frequency RMSE / RMSE: about 1 where the error is grain, up to 8 where it is
    /// blotches a tile wide (`metrics::error_correlation`, from the means over frames).
    pub fn error_correlation(&self) -> f64 {
        if self.mean_luma_rmse > 0.0 {
            LOW_FREQUENCY_TILE as f64 * self.mean_low_frequency_rmse / self.mean_luma_rmse
        } else {
            0.0
        }
    }
}

/// The mean of `v` (0 when empty).
pub fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        0.0
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}
