//! A perspective pinhole camera in the glTF convention: it looks down its local -Z with +Y up.

use glam::{Mat4, Quat, Vec3};

use super::Aabb;

/// Vertical field of view of a camera chosen for a file without one.
pub const FRAMING_YFOV_DEG: f32 = 45.0;

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

    /// The camera of a file without one, the way model viewers frame a model: from the
    /// horizontal side (+X or +Z) whose face of the bounds is larger, 20° above it; a flat
    /// model lying down (its top face over three times either side face) from 60° above.
    /// Distance: the whole box in view at any landscape aspect (fitted to the vertical
    /// 45° field of view, the narrower one), see [`frame_from_direction`].
    pub fn framing(bounds: Aabb) -> Camera {
        let yfov = FRAMING_YFOV_DEG.to_radians();
        if bounds.is_empty() {
            return Camera::look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, yfov);
        }
        let e = bounds.extent();
        let (x_face, z_face, top) = (e.y * e.z, e.x * e.y, e.x * e.z);
        // A tie goes to +Z, glTF's front (the open side of the Blender Cornell boxes).
        let side = if x_face > z_face { Vec3::X } else { Vec3::Z };
        let elevation: f32 = if top > 3.0 * x_face.max(z_face) {
            60f32
        } else {
            20f32
        };
        let (sin, cos) = elevation.to_radians().sin_cos();
        let towards_camera = side * cos + Vec3::Y * sin;
        let center = bounds.center();
        let aimed = Camera::look_at(center + towards_camera, center, yfov);
        frame_from_direction(&aimed, bounds, 1.0)
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

/// `camera` moved along its own view direction to where all of `bounds` is in view at
/// `aspect` (width / height), looking at their centre: the viewer's F key. Orientation and
/// field of view are kept; the eight corners fit the frustum with a 5 % margin.
pub fn frame_from_direction(camera: &Camera, bounds: Aabb, aspect: f32) -> Camera {
    if bounds.is_empty() {
        return *camera;
    }
    let (forward, right, up) = (camera.forward(), camera.right(), camera.up());
    let tan_v = (camera.yfov * 0.5).tan().max(1e-6);
    let tan_h = tan_v * aspect.max(1e-6);
    let center = bounds.center();
    // A corner at offset o from the centre, with the camera at centre − forward · D, has
    // depth D + o·forward; it is in view when |o·right| ≤ tan_h · depth and likewise up.
    let mut distance = 0f32;
    for corner in bounds.corners() {
        let o = corner - center;
        let along = o.dot(forward);
        distance = distance
            .max(o.dot(right).abs() / tan_h - along)
            .max(o.dot(up).abs() / tan_v - along);
    }
    // Never inside the box, whatever its shape.
    let radius = bounds.extent().length() * 0.5;
    let distance = (distance * 1.05).max(radius * 1.05).max(1e-6);
    Camera {
        position: center - forward * distance,
        ..*camera
    }
}

#[cfg(test)]
mod tests;
