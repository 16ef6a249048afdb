//! Keyframe tracks and their interpolation, exactly as glTF 2.0 defines them (spec §3.11
//! "Animations" and Appendix C "Interpolation"): STEP holds the previous key, LINEAR
//! interpolates (rotations by shortest-path slerp, renormalised), CUBICSPLINE is a cubic
//! Hermite spline whose stored in/out tangents are scaled by the keyframe interval.
//! Before the first key a track holds its first value, after the last its last value.

use glam::{Quat, Vec3};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    Step,
    Linear,
    CubicSpline,
}

/// A value a track can animate. `lerp` is LINEAR, `hermite` the CUBICSPLINE segment, and
/// `finish` what the spec asks after either (quaternions are renormalised).
pub trait Animatable: Copy + std::fmt::Debug {
    fn lerp(a: Self, b: Self, s: f32) -> Self;
    /// p(s) = (2s³−3s²+1)·v0 + (s³−2s²+s)·td·b0 + (−2s³+3s²)·v1 + (s³−s²)·td·a1
    fn hermite(v0: Self, out0: Self, v1: Self, in1: Self, s: f32, td: f32) -> Self;
    fn is_finite(&self) -> bool;
    fn finish(self) -> Self {
        self
    }
}

/// The four cubic Hermite basis weights at s, the tangent ones already scaled by td.
fn hermite_weights(s: f32, td: f32) -> [f32; 4] {
    let (s2, s3) = (s * s, s * s * s);
    [
        2.0 * s3 - 3.0 * s2 + 1.0,
        (s3 - 2.0 * s2 + s) * td,
        -2.0 * s3 + 3.0 * s2,
        (s3 - s2) * td,
    ]
}

/// Scalars and vectors: LINEAR and CUBICSPLINE are plain component-wise arithmetic.
macro_rules! vector_animatable {
    ($($t:ty),*) => {$(
        impl Animatable for $t {
            fn lerp(a: Self, b: Self, s: f32) -> Self {
                a + (b - a) * s
            }
            fn hermite(v0: Self, out0: Self, v1: Self, in1: Self, s: f32, td: f32) -> Self {
                let [h0, h1, h2, h3] = hermite_weights(s, td);
                v0 * h0 + out0 * h1 + v1 * h2 + in1 * h3
            }
            fn is_finite(&self) -> bool {
                <$t>::is_finite(*self)
            }
        }
    )*};
}
vector_animatable!(f32, Vec3);

impl Animatable for Quat {
    fn lerp(a: Self, b: Self, s: f32) -> Self {
        slerp_shortest(a, b, s)
    }
    fn hermite(v0: Self, out0: Self, v1: Self, in1: Self, s: f32, td: f32) -> Self {
        // The spec interpolates the four components and normalises the result (`finish`).
        let [h0, h1, h2, h3] = hermite_weights(s, td);
        let v = glam::Vec4::from(v0) * h0
            + glam::Vec4::from(out0) * h1
            + glam::Vec4::from(v1) * h2
            + glam::Vec4::from(in1) * h3;
        Quat::from_vec4(v)
    }
    fn is_finite(&self) -> bool {
        Quat::is_finite(*self)
    }
    fn finish(self) -> Self {
        let length = self.length();
        if length > 0.0 && length.is_finite() {
            self / length
        } else {
            // A zero quaternion (bad data or tangents cancelling exactly) has no rotation to
            // keep; identity is the safe fallback rather than NaN on screen.
            Quat::IDENTITY
        }
    }
}

/// Spherical linear interpolation along the shorter arc (q and −q are the same rotation,
/// glTF spec Appendix C), normalised; nearly parallel quaternions fall back to a
/// normalised lerp, where slerp's sin(θ) denominator loses precision.
pub fn slerp_shortest(a: Quat, b: Quat, s: f32) -> Quat {
    let (a4, mut b4) = (glam::Vec4::from(a), glam::Vec4::from(b));
    let mut dot = a4.dot(b4);
    if dot < 0.0 {
        b4 = -b4;
        dot = -dot;
    }
    let v = if dot > 0.9995 {
        a4 + (b4 - a4) * s
    } else {
        let theta0 = dot.acos();
        let (sin_theta0, theta) = (theta0.sin(), theta0 * s);
        a4 * ((theta0 - theta).sin() / sin_theta0) + b4 * (theta.sin() / sin_theta0)
    };
    Quat::from_vec4(v).finish()
}

/// One track: key times (seconds, strictly increasing) and values. For CUBICSPLINE the
/// values are triples (in-tangent, value, out-tangent) per key, as stored in glTF.
#[derive(Clone, Debug, PartialEq)]
pub struct Keyframes<T> {
    times: Vec<f32>,
    values: Vec<T>,
    interpolation: Interpolation,
}

/// Why a track was refused (the loader turns it into a `SceneError` naming the channel).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TrackError {
    #[error("has no keyframes")]
    Empty,
    #[error("key time {0} is not finite")]
    NonFiniteTime(usize),
    #[error("key times are not strictly increasing at key {0}")]
    NotIncreasing(usize),
    #[error("has {values} output values for {keys} keys (expected {expected})")]
    CountMismatch {
        keys: usize,
        values: usize,
        expected: usize,
    },
    #[error("output value {0} is not finite")]
    NonFiniteValue(usize),
}

impl<T: Animatable> Keyframes<T> {
    pub fn new(
        times: Vec<f32>,
        values: Vec<T>,
        interpolation: Interpolation,
    ) -> Result<Self, TrackError> {
        if times.is_empty() {
            return Err(TrackError::Empty);
        }
        if let Some(i) = times.iter().position(|t| !t.is_finite()) {
            return Err(TrackError::NonFiniteTime(i));
        }
        if let Some(i) = times.windows(2).position(|w| w[1] <= w[0]) {
            return Err(TrackError::NotIncreasing(i + 1));
        }
        let per_key = if interpolation == Interpolation::CubicSpline {
            3
        } else {
            1
        };
        if values.len() != times.len() * per_key {
            return Err(TrackError::CountMismatch {
                keys: times.len(),
                values: values.len(),
                expected: times.len() * per_key,
            });
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(TrackError::NonFiniteValue(i));
        }
        Ok(Self {
            times,
            values,
            interpolation,
        })
    }

    /// The time of the last key (a clip loops over its longest track).
    pub fn end_time(&self) -> f32 {
        *self.times.last().expect("tracks are never empty")
    }

    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// The value of key `k` (the middle of the triple for CUBICSPLINE).
    fn key(&self, k: usize) -> T {
        match self.interpolation {
            Interpolation::CubicSpline => self.values[3 * k + 1],
            _ => self.values[k],
        }
    }

    /// The track's value at time `t` (seconds, not wrapped).
    pub fn sample(&self, t: f32) -> T {
        let n = self.times.len();
        if n == 1 || t <= self.times[0] || t.is_nan() {
            return self.key(0).finish();
        }
        if t >= self.times[n - 1] {
            return self.key(n - 1).finish();
        }
        // times[k] <= t < times[k + 1]
        let k = self.times.partition_point(|&key| key <= t) - 1;
        let td = self.times[k + 1] - self.times[k];
        let s = (t - self.times[k]) / td;
        let value = match self.interpolation {
            Interpolation::Step => self.values[k],
            Interpolation::Linear => T::lerp(self.values[k], self.values[k + 1], s),
            Interpolation::CubicSpline => T::hermite(
                self.values[3 * k + 1],
                self.values[3 * k + 2],
                self.values[3 * (k + 1) + 1],
                self.values[3 * (k + 1)],
                s,
                td,
            ),
        };
        value.finish()
    }

    /// Key times at which a STEP track changes value (the scene's own light events).
    pub fn step_changes(&self) -> impl Iterator<Item = f32> + '_
    where
        T: PartialEq,
    {
        let step = self.interpolation == Interpolation::Step;
        (1..self.times.len())
            .filter(move |&k| step && self.values[k] != self.values[k - 1])
            .map(|k| self.times[k])
    }
}
