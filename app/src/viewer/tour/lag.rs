//! The tour's live lag, without a reference (a per-frame reference is far too slow to
//! render live on a CPU): after each light event of the scene, the frames the image's
//! mean luminance takes to settle, and how far from the settled value it starts. One
//! meter per side, fed every rendered frame while the step shows `lag`; a segment (event
//! to next event) is scored when it ends, so the numbers are the last segment's.

/// Frames at the end of a segment whose median is its settled level.
const SETTLED_FRAMES: usize = 5;
/// A frame has settled when its mean luminance is within this fraction of the level
/// (the mean over ~40 000 pixels moves by well under 1 % from frame to frame).
const TOLERANCE: f64 = 0.03;
/// Segments shorter than this have no settled level.
const MIN_FRAMES: usize = 10;

/// What the last finished segment measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settling {
    /// Frames from the event until the mean stays within TOLERANCE of the level (`None`:
    /// it never did before the next event).
    pub frames: Option<usize>,
    /// (mean of the event's first 3 frames − level) / level: positive = too bright
    /// (ghosting), negative = too dark.
    pub start_offset: f64,
    /// The segment's length.
    pub segment: usize,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct LagMeter {
    /// Mean luminance per frame since the last event (`None` before the first event).
    segment: Option<Vec<f64>>,
    pub last: Option<Settling>,
}

impl LagMeter {
    /// One rendered frame: its mean luminance and whether a light event came before it.
    pub fn push(&mut self, mean_luminance: f64, event: bool) {
        if event {
            if let Some(segment) = self.segment.take() {
                self.last = settle(&segment).or(self.last);
            }
            self.segment = Some(Vec::new());
        }
        if let Some(segment) = &mut self.segment {
            segment.push(mean_luminance);
        }
    }

    /// Frames since the last event (`None` before the first).
    pub fn frames_since_event(&self) -> Option<usize> {
        self.segment.as_ref().map(Vec::len)
    }
}

fn settle(segment: &[f64]) -> Option<Settling> {
    if segment.len() < MIN_FRAMES {
        return None;
    }
    let mut tail: Vec<f64> = segment[segment.len() - SETTLED_FRAMES..].to_vec();
    tail.sort_by(f64::total_cmp);
    let level = tail[SETTLED_FRAMES / 2];
    // Not positive, or NaN: no level to settle at.
    if level.is_nan() || level <= 0.0 {
        return None;
    }
    let off = |x: f64| (x - level).abs() > TOLERANCE * level;
    // The first frame after which every frame is within the tolerance.
    let frames = match segment.iter().rposition(|&x| off(x)) {
        None => Some(0),
        // Settled only with SETTLED_FRAMES calm frames at the end.
        Some(i) if i + 1 + SETTLED_FRAMES <= segment.len() => Some(i + 1),
        Some(_) => None,
    };
    let start = segment[..3].iter().sum::<f64>() / 3.0;
    Some(Settling {
        frames,
        start_offset: (start - level) / level,
        segment: segment.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ghost_that_fades_settles_after_it_fades() {
        let mut m = LagMeter::default();
        m.push(1.0, false);
        assert_eq!(
            m.frames_since_event(),
            None,
            "nothing before the first event"
        );
        // The lights go off: the level is 0.5, the image starts at 0.9 and halves its
        // excess every frame.
        let mut excess = 0.4;
        m.push(0.5 + excess, true);
        for _ in 0..19 {
            excess *= 0.5;
            m.push(0.5 + excess, false);
        }
        assert_eq!(m.last, None, "scored when the segment ends");
        m.push(1.0, true);
        let s = m.last.unwrap();
        // 0.4 · 0.5^k ≤ 0.015 from k = 5 on.
        assert_eq!((s.frames, s.segment), (Some(5), 20));
        assert!((s.start_offset - (0.4 + 0.2 + 0.1) / 3.0 / 0.5).abs() < 1e-4);
        // A segment too short to settle keeps the last result.
        for _ in 0..3 {
            m.push(1.0, false);
        }
        m.push(0.5, true);
        assert_eq!(m.last, Some(s));
    }

    #[test]
    fn a_lag_that_outlasts_the_segment_never_settles() {
        let mut m = LagMeter::default();
        m.push(1.0, true);
        for k in 1..12 {
            m.push(1.0 - 0.05 * k as f64, false);
        }
        m.push(1.0, true);
        assert_eq!(m.last.unwrap().frames, None);
    }
}
