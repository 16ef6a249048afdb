//! Reproducible camera motion for headless experiments: `--orbit DEG` turns the camera
//! about the vertical axis through the scene centre by DEG per frame; `--cut-at FRAME`
//! jumps to a distant viewpoint at that frame (a camera cut); the bench's `pan` turns it
//! in place and its `walk` moves it forward.

use glam::{Quat, Vec3};
use restir_render::Camera;
use restir_render::scene::Aabb;

/// The camera rotated by `degrees` about the vertical axis through `center`.
pub fn orbit(camera: Camera, center: Vec3, degrees: f32) -> Camera {
    let q = Quat::from_rotation_y(degrees.to_radians());
    let pivot = Vec3::new(center.x, camera.position.y, center.z);
    Camera {
        position: pivot + q * (camera.position - pivot),
        rotation: (q * camera.rotation).normalize(),
        yfov: camera.yfov,
    }
}

/// The camera turned in place by `degrees` about the vertical axis (a pan: no parallax).
pub fn pan(camera: Camera, degrees: f32) -> Camera {
    let q = Quat::from_rotation_y(degrees.to_radians());
    Camera {
        rotation: (q * camera.rotation).normalize(),
        ..camera
    }
}

/// The camera moved `distance` along its view direction (negative: backwards).
pub fn walk(camera: Camera, distance: f32) -> Camera {
    Camera {
        position: camera.position + camera.forward() * distance,
        ..camera
    }
}

/// The viewpoint a cut jumps to: 120° around the scene and halfway to its centre, looking
/// at the centre. Far enough (in position and direction) that nothing reprojects.
pub fn cut_viewpoint(camera: Camera, bounds: Aabb) -> Camera {
    let center = bounds.center();
    let turned = orbit(camera, center, 120.0);
    let position = center + (turned.position - center) * 0.5;
    Camera::look_at(position, center, camera.yfov)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orbit_keeps_distance_and_height_and_a_full_turn_returns() {
        let c = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), 0.7);
        let o = orbit(c, Vec3::ZERO, 90.0);
        assert!((o.position - Vec3::new(4.0, 1.0, 0.0)).length() < 1e-5);
        assert!((o.forward() - Vec3::NEG_X).length() < 1e-5);
        let full = orbit(c, Vec3::ZERO, 360.0);
        assert!((full.position - c.position).length() < 1e-4);
    }

    #[test]
    fn a_pan_turns_in_place_and_a_walk_moves_along_the_view() {
        let c = Camera::look_at(Vec3::new(0.0, 1.0, 4.0), Vec3::new(0.0, 1.0, 0.0), 0.7);
        let p = pan(c, 90.0);
        assert_eq!(p.position, c.position);
        // Looking down -z, a positive turn about +y looks down -x (as the orbit's).
        assert!((p.forward() - Vec3::NEG_X).length() < 1e-5);
        let w = walk(c, 1.5);
        assert!((w.position - Vec3::new(0.0, 1.0, 2.5)).length() < 1e-5);
        assert!((w.forward() - c.forward()).length() < 1e-6);
    }
}
