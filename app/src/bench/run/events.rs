//! The light events of a bench on a dynamic scene and what each configuration measured
//! around them: which measured frames show an event (from the scene's own event list, else
//! detected where the references change), the changed-pixel mask of each, a probe that
//! records the signed bias of the frames after every event (and keeps the first event's
//! frames for `event_strip.png`) and gives one seed's metrics (score/lag.rs, which also
//! averages them over `--seeds`).

use restir_render::LinearImage;
use restir_render::scene::Scene;
use restir_render::scene::animation::ClipChoice;

use super::shot::Shot;
use crate::bench::score::frame_figures::FrameRecord;
use crate::bench::score::lag::{
    STEADY_FRAMES, SeedEvent, changed_mask, curve_metrics, detected_event_frames, event_frames,
    median, signed_bias,
};

/// Offsets after the first event whose frames go into `event_strip.png`.
pub const STRIP_OFFSETS: [usize; 3] = [0, 4, 12];

/// The events of the measured frames.
pub struct Events {
    /// Measured frame index of each event (the first frame that shows it).
    pub frames: Vec<usize>,
    /// Scene time of each event frame.
    pub times: Vec<f32>,
    /// "scene" (the animation's STEP light keys) or "detected" (the references changed).
    pub source: &'static str,
    /// Per event: the pixels whose reference changed by more than 10 % across it.
    masks: Vec<Vec<bool>>,
    /// Per event: mean reference luminance of its segment / of the `STEADY_FRAMES` frames
    /// before it (when those are measured and after any earlier event).
    brightness: Vec<Option<f64>>,
}

impl Events {
    /// The events among `measured` frames after `warmup` of an animated scene whose
    /// `references` are one per measured frame; `None` when there are none (a static
    /// scene, frozen time, or an animation without a light change in the window).
    pub fn find(
        scene: &Scene,
        shot: &Shot,
        warmup: u32,
        references: &[LinearImage],
    ) -> Option<Events> {
        let anim = scene.animation.as_ref()?;
        if !shot.timeline.is_some_and(|t| t.fps > 0.0) || references.len() < 2 {
            return None;
        }
        let times: Vec<f32> = (0..references.len() as u32)
            .map(|i| shot.time(warmup + i))
            .collect();
        let listed = anim.light_events(ClipChoice::All);
        let (frames, source) = if listed.is_empty() {
            (detected_event_frames(references), "detected")
        } else {
            let duration = anim.duration(ClipChoice::All);
            let wrap = |t: f32| anim.wrap(t, ClipChoice::All);
            (event_frames(&times, &listed, duration, wrap), "scene")
        };
        if frames.is_empty() {
            return None;
        }
        let masks = frames
            .iter()
            .map(|&f| changed_mask(&references[f - 1], &references[f]))
            .collect();
        let mut events = Events {
            times: frames.iter().map(|&f| times[f]).collect(),
            frames,
            source,
            masks,
            brightness: Vec::new(),
        };
        events.brightness = (0..events.frames.len())
            .map(|k| {
                let before = events.before(k)?;
                let after = events.segment(k, references.len());
                let mean = |r: std::ops::Range<usize>| {
                    let n = r.len() as f64;
                    references[r].iter().map(mean_luminance).sum::<f64>() / n
                };
                let (b, a) = (mean(before), mean(after));
                (b > 0.0).then(|| a / b)
            })
            .collect();
        Some(events)
    }

    /// The `STEADY_FRAMES` frames before event `k`, when they are measured and after any
    /// earlier event frame.
    fn before(&self, k: usize) -> Option<std::ops::Range<usize>> {
        let e = self.frames[k];
        let floor = if k == 0 { 0 } else { self.frames[k - 1] };
        (e >= floor + STEADY_FRAMES).then(|| e - STEADY_FRAMES..e)
    }

    /// The frames of event `k`'s segment: to the next event or `measured`.
    fn segment(&self, k: usize, measured: usize) -> std::ops::Range<usize> {
        let end = self.frames.get(k + 1).copied().unwrap_or(measured);
        self.frames[k]..end.min(measured)
    }
}

fn mean_luminance(img: &LinearImage) -> f64 {
    let sum: f64 = (0..img.height)
        .flat_map(|y| (0..img.width).map(move |x| (x, y)))
        .map(|(x, y)| img.luminance_at(x, y) as f64)
        .filter(|l| l.is_finite())
        .sum();
    sum / (img.width as f64 * img.height as f64).max(1.0)
}

/// Watches one configuration's frames for the signed bias after each event.
pub struct LagProbe<'a> {
    events: &'a Events,
    references: &'a [LinearImage],
    /// Per event: the signed bias of each frame in its bias window.
    biases: Vec<Vec<f64>>,
    keep_strip: bool,
    /// The first event's frames at `STRIP_OFFSETS` (when `keep_strip`).
    pub strip: Vec<(usize, LinearImage)>,
}

impl<'a> LagProbe<'a> {
    pub fn new(events: &'a Events, references: &'a [LinearImage], keep_strip: bool) -> Self {
        LagProbe {
            events,
            references,
            biases: vec![Vec::new(); events.frames.len()],
            keep_strip,
            strip: Vec::new(),
        }
    }

    /// Records measured frame `index`.
    pub fn push(&mut self, index: usize, frame: &LinearImage) {
        for (k, &e) in self.events.frames.iter().enumerate() {
            let window = e..(e + STEADY_FRAMES).min(self.events.segment(k, usize::MAX).end);
            if window.contains(&index) {
                let b = signed_bias(frame, &self.references[index], &self.events.masks[k]);
                self.biases[k].extend(b);
            }
        }
        let first = self.events.frames[0];
        if self.keep_strip && STRIP_OFFSETS.iter().any(|&o| first + o == index) {
            self.strip.push((index, frame.clone()));
        }
    }

    /// One seed's metrics per event from the configuration's frames.
    pub fn finish(self, frames: &[FrameRecord]) -> (Vec<SeedEvent>, Vec<(usize, LinearImage)>) {
        let errors: Vec<f64> = frames
            .iter()
            .map(|f| f.scores.luma_rmse.unwrap_or(f64::NAN))
            .collect();
        let per_event = (0..self.events.frames.len())
            .map(|k| {
                let segment = self.events.segment(k, errors.len());
                let b = &self.biases[k];
                // The level before the event, carried over to the new brightness.
                let before = self.events.before(k).and_then(|r| {
                    let level = median(errors.get(r)?);
                    Some(level * self.events.brightness[k]?)
                });
                SeedEvent {
                    curve: curve_metrics(errors.get(segment).unwrap_or(&[]), before),
                    signed_bias: (!b.is_empty()).then(|| b.iter().sum::<f64>() / b.len() as f64),
                }
            })
            .collect();
        (per_event, self.strip)
    }
}
