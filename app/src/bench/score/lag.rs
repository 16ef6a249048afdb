//! Lag and ghosting around a dynamic scene's light events (docs/src/dynamic-scenes.md, "Lag
//! and ghosting"): from a configuration's
//! per-frame error curve (luma RMSE of each frame against that frame's own reference) and
//! the frames right after the event, the numbers `results.csv` carries per event.
//!
//! Definitions (docs/src/measured/how-the-bench-measures.md, "Light events: lag and ghosting").
//! An event's *segment* is the measured frames from the event frame (the first frame that shows
//! the change) up to the next event or the end of the run.
//! - `steady_error`: the lower of (a) the median error of the segment's last
//!   `STEADY_FRAMES` frames — the level the configuration settles at in the changed scene —
//!   and (b) when the 5 frames before the event are measured and belong to no earlier
//!   event, their median error × (mean reference luminance of the segment / of those 5
//!   frames): the configuration's level before the event, carried over to the new image's
//!   brightness (absolute noise scales with brightness at a fixed relative error; a switch
//!   off halves it). (a) alone hides a lag that outlasts the run (its tail is still
//!   lagging); (b) alone is only as good as that scaling; the lower of the two keeps both
//!   a run that settles lower and a run that never settles honest.
//! - `peak_error`: the largest error in the segment; `peak_over_steady` = peak / steady.
//! - `recovery_frames`: the first k such that frames k..k+5 of the segment all have error
//!   ≤ 1.1 × steady (below the band counts: being better than steady is not lag); `None`
//!   ("never") when no such window exists.
//! - `lag_area`: Σ max(error − steady, 0) over the segment (luma RMSE × frames). Per-frame
//!   noise above the median adds a small floor (about a frame's noise spread × frames / 2).
//! - `signed_bias`: in the pixels whose reference changed by more than 10 % across the event,
//!   Σ(frame − reference) luminance / Σ reference luminance, averaged over the first
//!   `STEADY_FRAMES` frames of the segment: positive = ghosting (too bright, light that is
//!   gone), negative = dark lag.

use restir_render::LinearImage;
use restir_render::image::luminance;
pub use restir_render::timeline::event_frames;

/// Frames of the steady window, of the recovery window and of the signed-bias window.
pub const STEADY_FRAMES: usize = 5;
/// Recovered = within 10 % of the steady level (docs/src/measured/how-the-bench-measures.md,
/// "Light events: lag and ghosting").
pub const RECOVERY_TOLERANCE: f64 = 0.10;
/// A pixel "changed" when its reference luminance moved by more than 10 % of its value
/// before the event (docs/src/measured/how-the-bench-measures.md, "Light events: lag and
/// ghosting").
pub const CHANGE_THRESHOLD: f32 = 0.10;

/// Numbers from one event's error curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveMetrics {
    pub peak_error: f64,
    pub steady_error: f64,
    pub peak_over_steady: f64,
    pub recovery_frames: Option<usize>,
    pub lag_area: f64,
}

/// The curve metrics of `segment` (errors from the event frame on), `before` the level
/// carried over from before the event ((b) above) when there is one. `None` when the
/// segment is shorter than two windows (a steady level needs frames after the recovery) or
/// has a non-finite error.
pub fn curve_metrics(segment: &[f64], before: Option<f64>) -> Option<CurveMetrics> {
    if segment.len() < 2 * STEADY_FRAMES || segment.iter().any(|e| !e.is_finite()) {
        return None;
    }
    let tail = median(&segment[segment.len() - STEADY_FRAMES..]);
    let steady = before
        .filter(|b| b.is_finite())
        .map_or(tail, |b| b.min(tail));
    let peak = segment.iter().copied().fold(f64::MIN, f64::max);
    let band = (1.0 + RECOVERY_TOLERANCE) * steady;
    let recovery_frames = segment
        .windows(STEADY_FRAMES)
        .position(|w| w.iter().all(|&e| e <= band));
    let lag_area = segment.iter().map(|&e| (e - steady).max(0.0)).sum();
    Some(CurveMetrics {
        peak_error: peak,
        steady_error: steady,
        peak_over_steady: if steady > 0.0 {
            peak / steady
        } else {
            f64::NAN
        },
        recovery_frames,
        lag_area,
    })
}

pub fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        (s[n / 2 - 1] + s[n / 2]) / 2.0
    }
}

/// The pixels whose reference changed by more than `CHANGE_THRESHOLD` across an event:
/// `before` is the reference of the frame before the event, `after` the event frame's.
/// Luminances are 3×3 box-filtered first, so a modest-spp reference's per-pixel noise does
/// not pass for change (it drops by 3×; a light switching changes whole regions).
pub fn changed_mask(before: &LinearImage, after: &LinearImage) -> Vec<bool> {
    let (b, a) = (box3(before), box3(after));
    b.iter()
        .zip(&a)
        .map(|(&b, &a)| (a - b).abs() > CHANGE_THRESHOLD * b.max(0.0) && a != b)
        .collect()
}

/// Luminance averaged over each pixel's 3×3 neighbourhood (clipped at the borders).
fn box3(img: &LinearImage) -> Vec<f32> {
    let (w, h) = (img.width as i64, img.height as i64);
    let luma: Vec<f32> = img
        .pixels
        .iter()
        .map(|p| {
            let l = luminance([p[0], p[1], p[2]]);
            if l.is_finite() { l } else { 0.0 }
        })
        .collect();
    let mut out = Vec::with_capacity(luma.len());
    for y in 0..h {
        for x in 0..w {
            let (mut sum, mut n) = (0.0, 0.0);
            for yy in (y - 1).max(0)..=(y + 1).min(h - 1) {
                for xx in (x - 1).max(0)..=(x + 1).min(w - 1) {
                    sum += luma[(yy * w + xx) as usize];
                    n += 1.0;
                }
            }
            out.push(sum / n);
        }
    }
    out
}

/// Σ(frame − reference) / Σ reference luminance over the `mask` pixels: the frame's signed
/// bias where the event changed the image. `None` without changed pixels or light there.
pub fn signed_bias(frame: &LinearImage, reference: &LinearImage, mask: &[bool]) -> Option<f64> {
    let (mut diff, mut sum) = (0.0f64, 0.0f64);
    for ((f, r), &m) in frame.pixels.iter().zip(&reference.pixels).zip(mask) {
        let (lf, lr) = (luminance([f[0], f[1], f[2]]), luminance([r[0], r[1], r[2]]));
        if m && lf.is_finite() {
            diff += (lf - lr) as f64;
            sum += lr as f64;
        }
    }
    (sum > 0.0).then(|| diff / sum)
}

/// Frames where the reference itself changes, for a scene without an event list (changes
/// of emission that are not STEP keys): the mean absolute change of 8×8-block mean
/// luminance between consecutive references, relative to the earlier reference's mean,
/// above `DETECT_THRESHOLD`; a run of such frames counts once, at its first frame. Block
/// means keep the references' noise (64 spp: ~10 % per pixel) from passing for change.
pub fn detected_event_frames(references: &[LinearImage]) -> Vec<usize> {
    let changed: Vec<bool> = references
        .windows(2)
        .map(|p| block_change(&p[0], &p[1]) > DETECT_THRESHOLD)
        .collect();
    (1..references.len())
        .filter(|&i| changed[i - 1] && (i == 1 || !changed[i - 2]))
        .collect()
}

/// 5 % of the mean luminance: half the per-pixel 10 % of [`CHANGE_THRESHOLD`], since block means of
/// a partly changed block dilute the change.
pub const DETECT_THRESHOLD: f64 = 0.05;

fn block_change(a: &LinearImage, b: &LinearImage) -> f64 {
    let means = |img: &LinearImage| {
        let (bw, bh) = (img.width.div_ceil(8), img.height.div_ceil(8));
        let mut sums = vec![(0.0f64, 0u32); (bw * bh) as usize];
        for y in 0..img.height {
            for x in 0..img.width {
                let l = img.luminance_at(x, y);
                let cell = &mut sums[((y / 8) * bw + x / 8) as usize];
                if l.is_finite() {
                    cell.0 += l as f64;
                    cell.1 += 1;
                }
            }
        }
        sums.into_iter()
            .map(|(s, n)| s / n.max(1) as f64)
            .collect::<Vec<_>>()
    };
    let (ma, mb) = (means(a), means(b));
    let mean = ma.iter().sum::<f64>() / ma.len().max(1) as f64;
    if mean <= 0.0 {
        return if mb.iter().any(|&v| v > 0.0) {
            f64::INFINITY
        } else {
            0.0
        };
    }
    ma.iter().zip(&mb).map(|(x, y)| (x - y).abs()).sum::<f64>() / ma.len() as f64 / mean
}

/// One seed's numbers for one event.
#[derive(Clone, Copy, Debug)]
pub struct SeedEvent {
    pub curve: Option<CurveMetrics>,
    pub signed_bias: Option<f64>,
}

/// One event's numbers averaged over seeds (`None`: not measurable, e.g. a segment too
/// short for a steady level).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EventLag {
    pub frame: usize,
    pub time: f32,
    pub seeds: usize,
    pub peak_error: Option<f64>,
    pub steady_error: Option<f64>,
    pub peak_over_steady: Option<f64>,
    /// `Some(None)`: some seed never recovered ("never").
    pub recovery_frames: Option<Option<f64>>,
    pub lag_area: Option<f64>,
    pub signed_bias: Option<f64>,
}

/// Averages each event's per-seed numbers (`per_seed[seed][event]`), the events being at
/// measured frames `frames` and scene times `times`. A recovery counts as "never" if any
/// seed never recovered: the mean of finite counts would hide it.
pub fn average(frames: &[usize], times: &[f32], per_seed: &[Vec<SeedEvent>]) -> Vec<EventLag> {
    (0..frames.len())
        .map(|k| {
            let seeds: Vec<&SeedEvent> = per_seed.iter().filter_map(|s| s.get(k)).collect();
            let curves: Option<Vec<CurveMetrics>> = seeds.iter().map(|s| s.curve).collect();
            let mean = |f: &dyn Fn(&CurveMetrics) -> f64| {
                curves
                    .as_ref()
                    .filter(|c| !c.is_empty())
                    .map(|c| c.iter().map(f).sum::<f64>() / c.len() as f64)
            };
            let recovery = curves.as_ref().filter(|c| !c.is_empty()).map(|c| {
                let r: Option<Vec<f64>> = c
                    .iter()
                    .map(|m| m.recovery_frames.map(|r| r as f64))
                    .collect();
                r.map(|r| r.iter().sum::<f64>() / r.len() as f64)
            });
            let biases: Option<Vec<f64>> = seeds.iter().map(|s| s.signed_bias).collect();
            EventLag {
                frame: frames[k],
                time: times[k],
                seeds: seeds.len(),
                peak_error: mean(&|m| m.peak_error),
                steady_error: mean(&|m| m.steady_error),
                peak_over_steady: mean(&|m| m.peak_over_steady),
                recovery_frames: recovery,
                lag_area: mean(&|m| m.lag_area),
                signed_bias: biases
                    .filter(|b| !b.is_empty())
                    .map(|b| b.iter().sum::<f64>() / b.len() as f64),
            }
        })
        .collect()
}

#[cfg(test)]
#[path = "lag_tests.rs"]
mod tests;
