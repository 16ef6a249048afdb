//! The environment (docs/src/environment.md): an equirectangular HDR image of the radiance arriving
//! from every direction, or the procedural `builtin:sky`. It is shown where camera rays miss the
//! scene and is one more light of the light table, sampled in proportion to luminance × solid angle
//! (`distribution.rs`).
//!
//! Convention (docs/src/environment.md, "Convention"): +Y up; the top row is the zenith; the image
//! centre (u = 0.5) looks along +X and u grows toward +Z, as Blender's world texture does once the
//! glTF exporter turns Blender's Z-up into glTF's Y-up. `rotation_deg` turns the environment about
//! +Y (right-handed: +X toward −Z for +90°).
//!
//! `direction_to_uv` and `uv_to_direction` mirror `shaders/common/environment.wgsl` line
//! by line.

mod distribution;
pub(crate) mod load;
mod sky;
#[cfg(test)]
mod tests;

use std::f32::consts::PI;
use std::fmt;

use glam::Vec3;

pub use distribution::{EnvDistribution, EnvSample};
pub use load::{EnvironmentError, load_environment};
pub use sky::{BUILTIN_SKY, clear_sky_texels};

/// The largest image kept at full resolution (a 4K HDRI): its row-and-column table takes
/// 12 bytes per texel, which must fit one storage binding of WebGPU's default 128 MiB
/// limit. Larger images are box-filtered down by 2 until they fit (logged).
pub const MAX_TEXELS: usize = 4096 * 2048;

/// Linear RGB radiance per texel, row-major, row 0 = zenith, plus what the renderer
/// applies on top (strength, rotation) and the sampling distribution built once per image.
#[derive(Clone)]
pub struct Environment {
    /// The file name as given, or `builtin:sky`.
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 3]>,
    /// Multiplies every texel (`--env-strength`); does not change the distribution.
    pub strength: f32,
    /// Rotation about +Y in degrees (`--env-rotation`).
    pub rotation_deg: f32,
    pub distribution: EnvDistribution,
    /// Wall time of building `distribution`, in milliseconds (the Scene panel, bench).
    pub build_ms: f64,
}

impl fmt::Debug for Environment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "Environment({}, {}x{}, strength {}, rotation {}°)",
            self.name, self.width, self.height, self.strength, self.rotation_deg
        )
    }
}

impl Environment {
    /// An environment from linear texels (validated by the caller), with its distribution.
    pub fn from_texels(name: &str, width: u32, height: u32, texels: Vec<[f32; 3]>) -> Self {
        let start = std::time::Instant::now();
        let distribution = EnvDistribution::build(width, height, &texels);
        Environment {
            name: name.to_string(),
            width,
            height,
            texels,
            strength: 1.0,
            rotation_deg: 0.0,
            distribution,
            build_ms: start.elapsed().as_secs_f64() * 1e3,
        }
    }

    /// Sets `--env-strength` and `--env-rotation`, refusing what would poison the image.
    pub fn with_strength_and_rotation(
        mut self,
        strength: f32,
        rotation_deg: f32,
    ) -> Result<Self, String> {
        if !(strength.is_finite() && strength >= 0.0) {
            return Err(format!(
                "--env-strength {strength}: expected a finite number ≥ 0"
            ));
        }
        if !rotation_deg.is_finite() {
            return Err(format!("--env-rotation {rotation_deg}: expected degrees"));
        }
        self.strength = strength;
        self.rotation_deg = rotation_deg;
        Ok(self)
    }

    /// (cos, sin) of the rotation, as the shader receives it.
    pub fn rotation_cos_sin(&self) -> [f32; 2] {
        let a = self.rotation_deg.to_radians();
        [a.cos(), a.sin()]
    }

    /// Radiance arriving from `uv` (nearest texel, strength applied).
    pub fn radiance_at(&self, uv: [f32; 2]) -> [f32; 3] {
        let (x, y) = texel_of(uv, self.width, self.height);
        let t = self.texels[(y * self.width + x) as usize];
        t.map(|c| c * self.strength)
    }

    /// ∫ luminance dω over the sphere, strength applied (the light table's power measure).
    pub fn luminance_integral(&self) -> f64 {
        self.distribution.integral * self.strength as f64
    }

    /// Text that changes whenever the rendered environment would (reference cache keys).
    pub fn fingerprint(&self) -> String {
        let mut h = crate::fnv::Fnv64::default();
        h.write(bytemuck::cast_slice(&self.texels));
        format!(
            "{}:{}x{}:{:016x}:strength={:08x}:rotation={:08x}",
            self.name,
            self.width,
            self.height,
            h.finish(),
            self.strength.to_bits(),
            self.rotation_deg.to_bits()
        )
    }
}

/// The texel (column, row) that `uv` falls in, clamped to the image (`env_texel`).
pub fn texel_of(uv: [f32; 2], width: u32, height: u32) -> (u32, u32) {
    let x = ((uv[0] * width as f32).max(0.0) as u32).min(width - 1);
    let y = ((uv[1] * height as f32).max(0.0) as u32).min(height - 1);
    (x, y)
}

/// World direction → image coordinates (`env_direction_to_uv`).
pub fn direction_to_uv(d: Vec3, cos_sin: [f32; 2]) -> [f32; 2] {
    let [c, s] = cos_sin;
    let local = Vec3::new(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
    let u = 0.5 + local.z.atan2(local.x) / (2.0 * PI);
    let v = local.y.clamp(-1.0, 1.0).acos() / PI;
    [u, v]
}

/// Image coordinates → world direction (`env_uv_to_direction`).
pub fn uv_to_direction(uv: [f32; 2], cos_sin: [f32; 2]) -> Vec3 {
    let [c, s] = cos_sin;
    let phi = 2.0 * PI * (uv[0] - 0.5);
    let theta = PI * uv[1];
    let local = Vec3::new(
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    );
    Vec3::new(
        c * local.x + s * local.z,
        local.y,
        -s * local.x + c * local.z,
    )
}
