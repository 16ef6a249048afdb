//! The shot a bench renders: the scene's camera moved along the `--camera` path, and an
//! animated scene's time, for every frame counted from the first warm-up frame.

use glam::Vec3;
use restir_render::Camera;
use restir_render::timeline::Timeline;

use crate::bench::plan::camera_path::CameraPath;
use crate::cli::camera_path::{orbit, pan, walk};

/// The camera of every frame: the scene's camera moved along the path; and, for an
/// animated scene, the scene time of every frame.
#[derive(Clone, Copy, Debug)]
pub struct Shot {
    pub start: Camera,
    pub center: Vec3,
    pub path: CameraPath,
    /// `--time`/`--fps` of an animated scene (`None` for a static one).
    pub timeline: Option<Timeline>,
}

impl Shot {
    pub fn of(renderer_start: Camera, center: Vec3, path: CameraPath) -> Shot {
        Shot {
            start: renderer_start,
            center,
            path,
            timeline: None,
        }
    }

    /// The same shot of an animated scene, whose frame i shows `timeline.time_of(i)`.
    pub fn with_time(self, timeline: Timeline) -> Shot {
        Shot {
            timeline: Some(timeline),
            ..self
        }
    }

    /// Scene time at frame `frame` (counted from the first warm-up frame).
    pub fn time(&self, frame: u32) -> f32 {
        self.timeline.map_or(0.0, |t| t.time_of(frame))
    }

    /// Whether frames differ from each other: a moving camera or running scene time. Then
    /// every measured frame has its own reference.
    pub fn moves(&self) -> bool {
        self.path != CameraPath::Static || self.timeline.is_some_and(|t| t.fps > 0.0)
    }

    /// The camera at frame `frame` (counted from the first warm-up frame).
    pub fn camera(&self, frame: u32) -> Camera {
        match self.path {
            CameraPath::Static => self.start,
            CameraPath::Orbit(d) => orbit(self.start, self.center, d * frame as f32),
            CameraPath::Pan(d) => pan(self.start, d * frame as f32),
            CameraPath::Walk(m) => walk(self.start, m * frame as f32),
        }
    }
}
