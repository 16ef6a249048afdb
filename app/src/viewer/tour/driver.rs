//! The viewer's side of its teaching tools (the pixel history, a tour's live numbers, the
//! recording), beside the frame loop (`frame.rs` calls in): what each rendered frame feeds
//! them, and the actions that need the renderer or the file system. What they keep between
//! frames is `teaching.rs`.

use super::teaching::Teaching;
use crate::probe;
use crate::recording::{RecordedFrame, Recorder, RecordingPlan};
use crate::tour::LiveNumber;
use crate::viewer::state::ViewerState;
use crate::viewer::window::Viewer;

impl Viewer {
    /// Right after a frame is rendered: its facts for the pixel history, the tour's lag
    /// meters, and the recording.
    pub(in crate::viewer) fn frame_rendered(&mut self, event: bool) {
        let frame = self.renderer.frame_index().saturating_sub(1);
        let time = (self.state.time.duration > 0.0).then_some(self.state.time.time);
        self.teaching.push_frame(frame, time, event);
        if self
            .state
            .tour
            .as_ref()
            .is_some_and(|t| t.shows(LiveNumber::Lag))
        {
            let a = self.renderer.read_radiance().mean_luminance();
            let b = self
                .compare
                .as_ref()
                .map(|c| c.renderer.read_radiance().mean_luminance());
            if let Some(tour) = &mut self.state.tour {
                tour.numbers.a.lag.push(a, event);
                if let Some(b) = b {
                    tour.numbers.b.lag.push(b, event);
                }
            }
        }
        if let Err(e) = self.record_frame() {
            self.state.recording.message = Some(format!("recording stopped: {e:#}"));
            self.stop_recording();
        }
    }

    /// Whether the tour's step wants the Accuracy reference (its rmse or bias numbers).
    pub(in crate::viewer) fn tour_wants_reference(&self) -> bool {
        self.state
            .tour
            .as_ref()
            .is_some_and(|t| t.shows(LiveNumber::Rmse) || t.shows(LiveNumber::Bias))
    }

    /// The split screen's labels and the tour's rmse and bias.
    /// Each side is read back a few times a second, and with jitter on only on frames whose
    /// phase has its reference (`accuracy/side_scores.rs`); meanwhile the last numbers stay.
    pub(in crate::viewer) fn score_sides(&mut self) {
        let a = self.accuracy.side_score(0, &self.renderer);
        let b = match &self.compare {
            Some(c) => self.accuracy.side_score(1, &c.renderer),
            None => None,
        };
        let state = &mut self.state;
        state.compare.errors = match (self.compare.is_some(), a, b) {
            (true, Some(a), Some(b)) => Some((a.0, b.0)),
            _ => None,
        };
        if let Some(tour) = &mut state.tour {
            let n = &mut tour.numbers;
            (n.a.rmse, n.a.bias) = (a.map(|s| s.0), a.map(|s| s.1));
            (n.b.rmse, n.b.bias) = (b.map(|s| s.0), b.map(|s| s.1));
        }
    }

    /// A tour step's scene arrived (`after_load` applies its camera and time).
    pub(in crate::viewer) fn tour_scene_loaded(&mut self) {
        if let Some(index) = self.state.tour.as_ref().and_then(|t| t.pending) {
            super::after_load(&mut self.state, index);
        }
    }

    /// The Pixel inspector's Export: the history as CSV.
    pub(in crate::viewer) fn export_pixel_history(&mut self) {
        let inspector = &mut self.state.inspector;
        let path = std::path::PathBuf::from(&inspector.history_path);
        inspector.history_message = Some(match inspector.history.pixel {
            None => "No pixel history yet: pick a pixel first.".to_string(),
            Some(pixel) => match probe::write_csv(&path, pixel, inspector.history.samples.iter()) {
                Ok(()) => format!(
                    "{} frames of pixel {}, {} → {}",
                    inspector.history.samples.len(),
                    pixel.0,
                    pixel.1,
                    path.display()
                ),
                Err(e) => format!("{e:#}"),
            },
        });
    }

    /// The View section's Record: a new folder `recording-N` in the chosen one, with the
    /// frames and/or `recording.gif`.
    pub(in crate::viewer) fn start_recording(&mut self) {
        let rec = &mut self.state.recording;
        let base = std::path::PathBuf::from(&rec.dir);
        let dir = (1..)
            .map(|n| base.join(format!("recording-{n}")))
            .find(|d| !d.exists())
            .expect("a free name");
        let plan = RecordingPlan {
            sequence: rec.sequence.map(|f| (dir.clone(), f)),
            gif: rec.gif.then(|| dir.join("recording.gif")),
            fps: self.state.time.frame_fps.unwrap_or(30.0),
        };
        let started = std::fs::create_dir_all(&dir)
            .map_err(anyhow::Error::from)
            .and_then(|_| Recorder::start(&plan));
        match started {
            Ok(r) => {
                rec.active = true;
                rec.message = Some(format!("recording into {}", dir.display()));
                self.teaching.recorder = Some(r);
            }
            Err(e) => {
                rec.active = false;
                rec.message = Some(format!("{}: {e:#}", dir.display()));
            }
        }
    }

    pub(in crate::viewer) fn stop_recording(&mut self) {
        self.state.recording.active = false;
        if let Some(r) = self.teaching.recorder.take() {
            let message = match r.finish() {
                Ok(written) => format!("wrote {written}"),
                Err(e) => format!("{e:#}"),
            };
            self.state.recording.message = Some(message);
        }
    }

    /// The frame as shown: A, or the split screen at its divider (B left when flipped).
    fn record_frame(&mut self) -> anyhow::Result<()> {
        let Some(recorder) = &mut self.teaching.recorder else {
            return Ok(());
        };
        let (w, h) = self.renderer.size();
        let compare = &self.state.compare;
        let b = self.compare.as_ref().filter(|_| compare.enabled);
        let divider = crate::compare::divider_column(w, compare.divider);
        let flipped = compare.flipped;
        let rgba = recorder.wants_display().then(|| {
            let a = self.renderer.read_display_rgba8();
            match b {
                // Four bytes per pixel: the divider and the width in bytes.
                Some(b) => {
                    let b = b.renderer.read_display_rgba8();
                    shown_split(a, b, flipped, w * 4, divider * 4)
                }
                None => a,
            }
        });
        let linear = recorder.wants_linear().then(|| {
            let a = self.renderer.read_radiance();
            match b {
                Some(b) => restir_render::LinearImage {
                    width: w,
                    height: h,
                    pixels: shown_split(
                        a.pixels,
                        b.renderer.read_radiance().pixels,
                        flipped,
                        w,
                        divider,
                    ),
                },
                None => a,
            }
        });
        recorder.push(&RecordedFrame {
            width: w,
            height: h,
            rgba: rgba.as_deref(),
            linear: linear.as_ref(),
        })
    }
}

/// The split screen as the window shows it: A left of the divider, B right (swapped when
/// flipped).
fn shown_split<T: Copy>(a: Vec<T>, b: Vec<T>, flipped: bool, width: u32, divider: u32) -> Vec<T> {
    let (left, right) = if flipped { (b, a) } else { (a, b) };
    crate::compare::split_columns(&left, &right, width, divider)
}

/// The pixel history's row of an inspection that came back: the frame's facts and the
/// reference there (`reference`: the Accuracy reference's luminance at a pixel).
pub fn push_history(
    state: &mut ViewerState,
    teaching: &Teaching,
    inspection: &restir_render::renderer::PixelInspection,
    reference: Option<f32>,
) {
    let (time, event) = teaching.facts_of(inspection.frame);
    let sample = probe::ProbeSample::from_inspection(inspection, time, reference, event);
    state.inspector.history.push(inspection.pixel, sample);
}
