//! A perspective pinhole camera in the glTF convention: it looks down its local -Z with +Y up.

use glam::{Mat4, Quat, Vec3};

use super::Aabb;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    pub rotation: Quat,
    /// Vertical field of view in radians (glTF `yfov`); the aspect follows the output size.
    pub yfov: f32,
}

impl Camera {
    pub fn forward(&self) -> Vec3 {
        self.rotation * Vec3::NEG_Z
    }

    pub fn up(&self) -> Vec3 {
        self.rotation * Vec3::Y
    }

    pub fn right(&self) -> Vec3 {
        self.rotation * Vec3::X
    }

    /// A camera at `position` looking at `target` with world +Y as up.
    pub fn look_at(position: Vec3, target: Vec3, yfov: f32) -> Camera {
        let forward = (target - position).normalize_or(Vec3::NEG_Z);
        // Pick a helper up vector that is not parallel to the view direction.
        let up = if forward.y.abs() > 0.999 {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let view = glam::camera::rh::view::look_to_mat4(position, forward, up);
        let rotation = Quat::from_mat4(&view.inverse()).normalize();
        Camera {
            position,
            rotation,
            yfov,
        }
    }

    /// A camera in front of the bounds (+Z side, slightly above) that sees all of them.
    pub fn framing(bounds: Aabb) -> Camera {
        let yfov = 45f32.to_radians();
        if bounds.is_empty() {
            return Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, yfov);
        }
        let center = bounds.center();
        let radius = (bounds.extent().length() * 0.5).max(1e-6);
        let distance = radius / (yfov * 0.5).sin() * 1.05;
        let dir = Vec3::new(0.0, 0.25, 1.0).normalize();
        Camera::look_at(center + dir * distance, center, yfov)
    }

    /// World → view (right-handed, camera at origin looking down -Z).
    pub fn view_matrix(&self) -> Mat4 {
        Mat4::from_rotation_translation(self.rotation, self.position).inverse()
    }

    /// Reverse-Z infinite projection: depth 1 at `near`, 0 at infinity. This keeps depth
    /// precision for scenes from 1e-3 to 1e4 units without a far plane to tune.
    pub fn projection_matrix(&self, aspect: f32, near: f32) -> Mat4 {
        // wgpu's clip space is DirectX-like: z in [0, 1], y up.
        glam::camera::rh::proj::directx::perspective_infinite_reverse(
            self.yfov,
            aspect.max(1e-6),
            near,
        )
    }
}
