//! Parameters measured in pixels are defined at 1080p and follow the image height, in the
//! renderer, for every entry point (viewer at any render scale, `render`, `bench`): a
//! 30 px disk spans similar surfaces at 1080p, but on a 180-pixel-high image it reaches
//! across a sixth of the frame, over edges and onto other objects, and reuse gets *worse*
//! than none (at 225×180, 2.8 of 5 neighbours rejected for depth; docs/src/spatial-reuse.md,
//! "The radius follows the resolution"). One rule,
//! here: value × height / 1080, never below a floor of a few pixels, under which
//! neighbours are (nearly) the same pixel and stop decorrelating anything.

use super::Settings;

/// The image height at which pixel-unit parameters mean what they say.
pub const REFERENCE_HEIGHT: u32 = 1080;

/// The smallest effective spatial radius (px), unless the parameter itself is smaller.
/// Measured (docs/src/measured/reuse.md, "Spatial radius at small sizes"): per-frame error falls as
/// the radius shrinks from 12 px to 2 px on `many-lights` at 96×96 (0.288 → 0.227) and is flat
/// within 10 % from 2 to 5 px on `concourse` at 225×180; at 1 px, where the disk is the 8 direct
/// neighbours, it rises again in both.
pub const MIN_SPATIAL_RADIUS_PX: f32 = 2.0;

/// What a length of `pixels_at_1080p` is in an image `height` pixels high, with `floor`
/// (lowered to the length itself, so a deliberately tiny value stays tiny at 1080p).
pub fn scale_to_height(pixels_at_1080p: f32, height: u32, floor: f32) -> f32 {
    let scaled = pixels_at_1080p * height as f32 / REFERENCE_HEIGHT as f32;
    scaled.max(floor.min(pixels_at_1080p))
}

/// The 1080p value that gives `pixels` at `height` (tests and presets that need an exact
/// pixel radius at a small size use it; the inverse of `scale_to_height` above the floor).
pub fn at_1080p(pixels: f32, height: u32) -> f32 {
    pixels * REFERENCE_HEIGHT as f32 / height.max(1) as f32
}

impl Settings {
    /// The spatial radius in pixels of an image `height` pixels high.
    pub fn effective_spatial_radius(&self, height: u32) -> f32 {
        scale_to_height(self.spatial_radius, height, MIN_SPATIAL_RADIUS_PX)
    }

    /// The GI spatial radius in pixels of an image `height` pixels high (same rule).
    pub fn effective_gi_spatial_radius(&self, height: u32) -> f32 {
        scale_to_height(self.gi_spatial_radius, height, MIN_SPATIAL_RADIUS_PX)
    }

    pub fn effective_pt_spatial_radius(&self, height: u32) -> f32 {
        scale_to_height(self.pt_spatial_radius, height, MIN_SPATIAL_RADIUS_PX)
    }

    /// For a pixel-unit parameter, the value used at `height`; `None` for the others.
    /// (The one list of such parameters: the UI and `params` ask here.)
    pub fn effective_pixels(&self, name: &str, height: u32) -> Option<f32> {
        match name {
            "spatial_radius" => Some(self.effective_spatial_radius(height)),
            "gi_spatial_radius" => Some(self.effective_gi_spatial_radius(height)),
            "pt_spatial_radius" => Some(self.effective_pt_spatial_radius(height)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_units_scale_with_height_above_a_floor() {
        let s = Settings::default();
        assert_eq!(s.effective_spatial_radius(1080), 30.0);
        assert_eq!(s.effective_spatial_radius(2160), 60.0);
        assert_eq!(s.effective_spatial_radius(540), 15.0);
        assert_eq!(s.effective_spatial_radius(180), 5.0);
        assert!((s.effective_spatial_radius(96) - 30.0 * 96.0 / 1080.0).abs() < 1e-5);
        assert_eq!(s.effective_spatial_radius(48), MIN_SPATIAL_RADIUS_PX);
        // A radius chosen below the floor stays as chosen at 1080p.
        let tiny = Settings {
            spatial_radius: 1.5,
            ..Settings::default()
        };
        assert_eq!(tiny.effective_spatial_radius(1080), 1.5);
        assert_eq!(tiny.effective_spatial_radius(100), 1.5);
        // The inverse gives exact small radii above the floor.
        let exact = Settings {
            spatial_radius: at_1080p(8.0, 80),
            ..Settings::default()
        };
        assert!((exact.effective_spatial_radius(80) - 8.0).abs() < 1e-4);
    }

    #[test]
    fn only_pixel_unit_parameters_have_an_effective_value() {
        let s = Settings::default();
        assert_eq!(s.effective_pixels("spatial_radius", 540), Some(15.0));
        assert_eq!(s.effective_pixels("gi_spatial_radius", 540), Some(15.0));
        assert_eq!(s.effective_pixels("m_cap", 540), None);
    }

    #[test]
    fn the_uniform_carries_the_effective_radius() {
        let s = Settings::default();
        assert_eq!(s.gpu_params(180).di.spatial_radius, 5.0);
        assert_eq!(s.gpu_params(1080).di.spatial_radius, 30.0);
        let gi = Settings {
            gi_spatial_radius: 40.0,
            ..Settings::default()
        };
        assert_eq!(gi.gpu_params(540).gi.spatial_radius, 20.0);
        assert_eq!(gi.gpu_params(48).gi.spatial_radius, MIN_SPATIAL_RADIUS_PX);
    }
}
