//! The fly camera: WASD in the view plane, Q/E (or Ctrl/Space) down/up in world space,
//! right-drag to look, wheel for speed, Shift faster; saved viewpoints; and an optional
//! automatic orbit/dolly for looking at ghosting and boiling under steady motion.
//! Pure state + maths: `scene_view.rs` turns egui input into a `FlyInput`.

use glam::{Quat, Vec2, Vec3};
use restir_render::Camera;
use restir_render::scene::Aabb;
use restir_render::scene::camera::frame_from_direction;

use crate::cli::camera_path::orbit;

/// Radians of turn per pixel of mouse drag.
const LOOK_RADIANS_PER_PIXEL: f32 = 0.004;
/// Speed factor per wheel step, and with Shift held.
const WHEEL_STEP: f32 = 1.2;
const FAST_FACTOR: f32 = 4.0;
/// Looking closer than this to straight up or down makes yaw ill-defined.
const MAX_ABS_FORWARD_Y: f32 = 0.995;

/// One frame of camera input.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlyInput {
    /// -1..1 along the view direction, the right vector and world up.
    pub forward: f32,
    pub right: f32,
    pub up: f32,
    /// Mouse drag in pixels (x right, y down).
    pub look: Vec2,
    /// Wheel steps (positive: faster).
    pub wheel: f32,
    pub fast: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Viewpoint {
    pub name: String,
    pub camera: Camera,
}

/// Automatic camera motion, advanced once per rendered frame (so it is reproducible and
/// matches `render --orbit DEG`, which also counts per frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoMotion {
    pub orbit: bool,
    /// Degrees about the vertical axis through the scene centre per frame.
    pub orbit_degrees: f32,
    pub dolly: bool,
    /// Dolly amplitude as a fraction of the scene size.
    pub dolly_amount: f32,
    /// Frames per dolly cycle (in and out).
    pub dolly_period: u32,
    frame: u32,
}

impl Default for AutoMotion {
    fn default() -> Self {
        AutoMotion {
            orbit: false,
            orbit_degrees: 0.5,
            dolly: false,
            dolly_amount: 0.3,
            dolly_period: 120,
            frame: 0,
        }
    }
}

impl AutoMotion {
    pub fn active(&self) -> bool {
        self.orbit || self.dolly
    }

    /// Dolly offset (fraction of the distance) at `frame`.
    fn dolly_at(&self, frame: u32) -> f32 {
        let phase = frame as f32 / self.dolly_period.max(2) as f32;
        self.dolly_amount * (std::f32::consts::TAU * phase).sin()
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct CameraState {
    /// The camera every frame renders with.
    pub camera: Camera,
    /// The scene's own camera ("reset" goes back to it).
    pub scene_camera: Camera,
    pub center: Vec3,
    /// Size of the scene (bounding-box diagonal).
    pub scale: f32,
    /// Fly speed in scene units per second.
    pub speed: f32,
    pub viewpoints: Vec<Viewpoint>,
    pub motion: AutoMotion,
    /// The scene's bounds, for F (frame the scene).
    pub bounds: Aabb,
    /// The scene camera was chosen automatically (the file has none); the panel says so.
    pub automatic: bool,
}

impl CameraState {
    pub fn new(scene_camera: Camera, bounds: Aabb) -> CameraState {
        let scale = if bounds.is_empty() {
            1.0
        } else {
            bounds.extent().length().max(1e-6)
        };
        CameraState {
            camera: scene_camera,
            scene_camera,
            center: if bounds.is_empty() {
                Vec3::ZERO
            } else {
                bounds.center()
            },
            scale,
            // Crossing the scene takes about four seconds.
            speed: scale * 0.25,
            viewpoints: Vec::new(),
            motion: AutoMotion::default(),
            bounds,
            automatic: false,
        }
    }

    /// F: keeps the view direction and moves to where the whole scene is in view at
    /// `aspect`, looking at its centre.
    pub fn frame_scene(&mut self, aspect: f32) {
        self.camera = frame_from_direction(&self.camera, self.bounds, aspect);
    }

    /// Applies one frame of input; true when the camera moved or turned.
    pub fn fly(&mut self, input: &FlyInput, dt: f32) -> bool {
        if input.wheel != 0.0 {
            self.speed = (self.speed * WHEEL_STEP.powf(input.wheel))
                .clamp(self.scale * 1e-4, self.scale * 100.0);
        }
        let before = self.camera;
        if input.look != Vec2::ZERO {
            let yaw = Quat::from_rotation_y(-input.look.x * LOOK_RADIANS_PER_PIXEL);
            let pitch = Quat::from_rotation_x(-input.look.y * LOOK_RADIANS_PER_PIXEL);
            // Yaw about world up, pitch about the camera's own right axis: no roll creeps in.
            let turned = (yaw * self.camera.rotation * pitch).normalize();
            let yawed = (yaw * self.camera.rotation).normalize();
            let upright =
                |q: Quat| (q * Vec3::NEG_Z).y.abs() < MAX_ABS_FORWARD_Y && (q * Vec3::Y).y > 0.0;
            self.camera.rotation = if upright(turned) { turned } else { yawed };
        }
        let c = self.camera;
        let direction = c.forward() * input.forward + c.right() * input.right + Vec3::Y * input.up;
        if direction != Vec3::ZERO {
            let speed = self.speed * if input.fast { FAST_FACTOR } else { 1.0 };
            self.camera.position += direction.normalize() * speed * dt;
        }
        self.camera != before
    }

    /// Advances the automatic orbit/dolly by one frame; true when it moved the camera.
    pub fn advance_auto(&mut self) -> bool {
        let m = self.motion;
        if !m.active() {
            return false;
        }
        if m.orbit {
            self.camera = orbit(self.camera, self.center, m.orbit_degrees);
        }
        if m.dolly {
            // Move by the change of the offset, so the dolly oscillates about where it began.
            let toward_center =
                (self.center - self.camera.position).normalize_or(self.camera.forward());
            let delta = m.dolly_at(m.frame + 1) - m.dolly_at(m.frame);
            self.camera.position += toward_center * delta * self.scale;
        }
        self.motion.frame = m.frame.wrapping_add(1);
        true
    }

    pub fn reset(&mut self) {
        self.camera = self.scene_camera;
    }

    pub fn save_viewpoint(&mut self) {
        let name = format!("View {}", self.viewpoints.len() + 1);
        self.viewpoints.push(Viewpoint {
            name,
            camera: self.camera,
        });
    }

    /// Yaw (0 looking down -Z, 90 looking down +X) and pitch (positive up), in degrees.
    pub fn yaw_pitch_degrees(&self) -> (f32, f32) {
        let f = self.camera.forward();
        (
            f.x.atan2(-f.z).to_degrees(),
            f.y.clamp(-1.0, 1.0).asin().to_degrees(),
        )
    }

    /// The camera as text (what the Copy button puts on the clipboard).
    pub fn describe(&self) -> String {
        let c = self.camera;
        let p = c.position;
        let q = c.rotation;
        format!(
            "position = [{:.4}, {:.4}, {:.4}]\nrotation = [{:.5}, {:.5}, {:.5}, {:.5}]\nyfov_degrees = {:.2}\n",
            p.x,
            p.y,
            p.z,
            q.x,
            q.y,
            q.z,
            q.w,
            c.yfov.to_degrees()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state() -> CameraState {
        let bounds = Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        };
        CameraState::new(
            Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, 0.8),
            bounds,
        )
    }

    #[test]
    fn moving_forward_follows_the_view_direction_at_the_set_speed() {
        let mut s = state();
        let input = FlyInput {
            forward: 1.0,
            ..Default::default()
        };
        assert!(s.fly(&input, 1.0));
        assert!((s.camera.position - Vec3::new(0.0, 0.0, 5.0 - s.speed)).length() < 1e-4);
        let before = s.camera.position;
        s.fly(
            &FlyInput {
                forward: 1.0,
                fast: true,
                ..Default::default()
            },
            1.0,
        );
        assert!(((before - s.camera.position).length() - s.speed * FAST_FACTOR).abs() < 1e-4);
    }

    #[test]
    fn idle_input_leaves_the_camera_exactly_alone() {
        let mut s = state();
        let before = s.camera;
        assert!(!s.fly(&FlyInput::default(), 0.1));
        assert_eq!(s.camera, before);
        assert!(!s.fly(
            &FlyInput {
                fast: true,
                ..Default::default()
            },
            0.1
        ));
    }

    #[test]
    fn looking_never_rolls_or_flips_over_the_pole() {
        let mut s = state();
        s.fly(
            &FlyInput {
                look: Vec2::new(120.0, -80.0),
                ..Default::default()
            },
            0.0,
        );
        assert!(s.camera.right().y.abs() < 1e-4, "no roll");
        for _ in 0..100 {
            s.fly(
                &FlyInput {
                    look: Vec2::new(0.0, -50.0),
                    ..Default::default()
                },
                0.0,
            );
        }
        assert!(s.camera.forward().y < MAX_ABS_FORWARD_Y + 1e-3);
        assert!(s.camera.up().y > 0.0);
    }

    #[test]
    fn wheel_scales_speed_within_bounds() {
        let mut s = state();
        let v = s.speed;
        s.fly(
            &FlyInput {
                wheel: 2.0,
                ..Default::default()
            },
            0.0,
        );
        assert!((s.speed - v * 1.44).abs() < 1e-5);
        s.fly(
            &FlyInput {
                wheel: -1000.0,
                ..Default::default()
            },
            0.0,
        );
        assert!(s.speed >= s.scale * 1e-4);
    }

    #[test]
    fn orbit_keeps_the_distance_and_dolly_returns_after_a_period() {
        let mut s = state();
        s.motion.orbit = true;
        s.motion.orbit_degrees = 90.0;
        s.advance_auto();
        assert!((s.camera.position.length() - 5.0).abs() < 1e-4);
        let mut d = state();
        d.motion.dolly = true;
        d.motion.dolly_period = 8;
        let start = d.camera.position;
        d.advance_auto();
        assert!((d.camera.position - start).length() > 0.1);
        for _ in 1..8 {
            d.advance_auto();
        }
        assert!((d.camera.position - start).length() < 1e-3);
    }

    #[test]
    fn reset_viewpoints_and_description() {
        let mut s = state();
        s.fly(
            &FlyInput {
                right: 1.0,
                ..Default::default()
            },
            1.0,
        );
        s.save_viewpoint();
        s.reset();
        assert_eq!(s.camera, s.scene_camera);
        assert_eq!(s.viewpoints.len(), 1);
        assert_ne!(s.viewpoints[0].camera, s.scene_camera);
        let text = s.describe();
        assert!(
            text.contains("position = [0.0000, 0.0000, 5.0000]"),
            "{text}"
        );
        let (yaw, pitch) = s.yaw_pitch_degrees();
        assert!(yaw.abs() < 1e-3 && pitch.abs() < 1e-3);
    }
}
