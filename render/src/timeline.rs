//! Scene time for headless runs and the viewer: which scene time frame i shows
//! (`--time T --fps F`: T + i/F, F = 0 freezes time), and an animated scene kept posed at
//! the current time and in step with a renderer.

use crate::Renderer;
use crate::gpu_scene::SceneUpdateTimes;
use crate::scene::Scene;
use crate::scene::animation::{ClipChoice, SceneChange};

/// Frame i shows scene time `start + i / fps`; `fps == 0` freezes time at `start`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timeline {
    pub start: f32,
    pub fps: f32,
}

impl Default for Timeline {
    fn default() -> Self {
        Self {
            start: 0.0,
            fps: 30.0,
        }
    }
}

impl Timeline {
    /// Refuses non-finite times and negative rates (the CLI's one-line errors).
    pub fn new(start: f32, fps: f32) -> Result<Self, String> {
        if !start.is_finite() {
            return Err(format!(
                "--time {start}: expected a finite number of seconds"
            ));
        }
        if !(fps.is_finite() && fps >= 0.0) {
            return Err(format!(
                "--fps {fps}: expected 0 (frozen) or a positive rate"
            ));
        }
        Ok(Self { start, fps })
    }

    pub fn time_of(&self, frame: u32) -> f32 {
        if self.fps > 0.0 {
            self.start + frame as f32 / self.fps
        } else {
            self.start
        }
    }
}

/// A scene with its clock: posing it at a time updates the renderer's copy.
pub struct AnimatedScene {
    scene: Scene,
    choice: ClipChoice,
    time: Option<f32>,
}

impl AnimatedScene {
    pub fn new(scene: Scene) -> Self {
        Self {
            scene,
            choice: ClipChoice::All,
            time: None,
        }
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn is_animated(&self) -> bool {
        self.scene.animation.is_some()
    }

    pub fn clip_choice(&self) -> ClipChoice {
        self.choice
    }

    /// Plays all clips or one; the next `set_time` re-poses even at the same time.
    pub fn set_clip_choice(&mut self, choice: ClipChoice) {
        if choice != self.choice {
            self.choice = choice;
            self.time = None;
        }
    }

    /// The loop length (0 for a static scene).
    pub fn duration(&self) -> f32 {
        self.scene
            .animation
            .as_ref()
            .map_or(0.0, |a| a.duration(self.choice))
    }

    pub fn time(&self) -> f32 {
        self.time.unwrap_or(0.0)
    }

    /// Poses the scene at `time` and brings `renderer` up to date; a static scene or an
    /// unchanged time does nothing. Returns what changed and what the update cost.
    pub fn set_time(
        &mut self,
        renderer: &mut Renderer,
        time: f32,
    ) -> (SceneChange, SceneUpdateTimes) {
        if !self.is_animated() || self.time == Some(time) {
            return Default::default();
        }
        self.time = Some(time);
        let change = self.scene.pose(time, self.choice);
        let times = renderer.update_scene(&self.scene, change.clone());
        (change, times)
    }

    /// Uploads the whole posed scene to `renderer` (one that was made from, or last
    /// updated by, another copy of the scene), so it matches this clock exactly.
    pub fn sync(&self, renderer: &mut Renderer) {
        if self.is_animated() {
            let everything = SceneChange {
                geometry: true,
                lights: true,
                emission: true,
                camera: false,
                moved_vertices: None,
            };
            renderer.update_scene(&self.scene, everything);
        }
    }

    /// Poses the CPU scene only (for a renderer made from it afterwards).
    pub fn pose_only(&mut self, time: f32) -> SceneChange {
        self.time = Some(time);
        self.scene.pose(time, self.choice)
    }
}

/// Measured frames `1..times.len()` at which a light event happens (the bench's lag
/// figures and the pixel history share this rule): frame i shows event
/// clip time e when the clip time moved past e between frame i − 1 and frame i (`wrap`
/// maps scene time to clip time, `duration` is the loop). Compares the same f32 times the
/// sampler poses with, so the event frame is the first frame that shows the change.
pub fn event_frames(
    times: &[f32],
    events: &[f32],
    duration: f32,
    wrap: impl Fn(f32) -> f32,
) -> Vec<usize> {
    (1..times.len())
        .filter(|&i| {
            let (w0, w1) = (wrap(times[i - 1]), wrap(times[i]));
            let passed = |e: f32| {
                if times[i] - times[i - 1] >= duration {
                    true
                } else if w1 >= w0 {
                    w0 < e && e <= w1
                } else {
                    e > w0 || e <= w1
                }
            };
            times[i] > times[i - 1] && events.iter().any(|&e| passed(e))
        })
        .collect()
}
