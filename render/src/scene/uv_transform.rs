//! `KHR_texture_transform` as a 2×3 affine matrix on uv coordinates.

use glam::Vec2;

/// uv' = M · (u, v, 1), stored as M's three columns (the WGSL `mat3x2<f32>` layout).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    pub columns: [[f32; 2]; 3],
}

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    pub const IDENTITY: UvTransform = UvTransform {
        columns: [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]],
    };

    /// The extension's T · R · S. Its rotation turns the uvs counter-clockwise in the
    /// texture's frame (v down), that is u' = cos·u + sin·v, v' = −sin·u + cos·v: the
    /// spec's example (offset (0, 1), rotation π/2, scale ½ shows the lower-left quadrant)
    /// holds only with this sign, and three.js and the sample model TextureTransformTest
    /// agree. `None` when a value is not finite.
    pub fn from_khr(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> Option<UvTransform> {
        let (s, c) = rotation.sin_cos();
        let m = UvTransform {
            columns: [
                [c * scale[0], -s * scale[0]],
                [s * scale[1], c * scale[1]],
                offset,
            ],
        };
        m.columns
            .iter()
            .flatten()
            .all(|x| x.is_finite())
            .then_some(m)
    }

    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let [a, b, t] = self.columns.map(Vec2::from_array);
        a * uv.x + b * uv.y + t
    }

    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_specs_example_shows_the_lower_left_quadrant() {
        // KHR_texture_transform README: offset (0, 1), rotation π/2, scale ½ "utilizes only
        // the lower left quadrant of the source image, rotated clockwise 90°".
        let m = UvTransform::from_khr([0.0, 1.0], std::f32::consts::FRAC_PI_2, [0.5, 0.5]).unwrap();
        let lower_left = |p: Vec2| {
            (-1e-6..=0.5 + 1e-6).contains(&p.x) && (0.5 - 1e-6..=1.0 + 1e-6).contains(&p.y)
        };
        for corner in [Vec2::ZERO, Vec2::X, Vec2::Y, Vec2::ONE] {
            assert!(
                lower_left(m.apply(corner)),
                "{corner} → {}",
                m.apply(corner)
            );
        }
        // Planted twin: the opposite rotation sign leaves the image.
        let wrong =
            UvTransform::from_khr([0.0, 1.0], -std::f32::consts::FRAC_PI_2, [0.5, 0.5]).unwrap();
        assert!(
            !lower_left(wrong.apply(Vec2::X)),
            "{}",
            wrong.apply(Vec2::X)
        );
        // Offset then scale order: T · R · S scales first.
        let ts = UvTransform::from_khr([0.25, 0.0], 0.0, [2.0, 1.0]).unwrap();
        assert_eq!(ts.apply(Vec2::new(0.5, 0.5)), Vec2::new(1.25, 0.5));
    }

    #[test]
    fn non_finite_values_give_none() {
        assert!(UvTransform::from_khr([f32::NAN, 0.0], 0.0, [1.0, 1.0]).is_none());
        assert!(UvTransform::from_khr([0.0, 0.0], f32::INFINITY, [1.0, 1.0]).is_none());
        assert!(UvTransform::from_khr([0.0, 0.0], 0.0, [f32::MAX, 1.0]).is_some());
        assert!(
            UvTransform::from_khr([0.0, 0.0], 0.0, [1.0, 1.0])
                .unwrap()
                .is_identity()
        );
    }
}
