//! Sampling directions of the environment in proportion to luminance × solid angle: a
//! marginal alias table over rows and, per row, a conditional alias table over its
//! columns; a direction is then uniform in solid angle inside the chosen texel (uniform in
//! φ and in cos θ). The weight of a texel is luminance × its solid angle
//! Ω_row = (2π/W)(cos θ_top − cos θ_bottom), the exact form of "luminance × sin θ", so the
//! density in solid angle is luminance / ∫ luminance dω.
//!
//! Two levels instead of one table over all texels: the shaders pick a slot as
//! ⌊u·n⌋ with a 24-bit u, which favours some slots by up to n/2²⁴; with n ≤ 4096 per level
//! that is below 0.03 %, where one 8-million-entry table would be off by 50 %.
//!
//! `sample` and `pdf` mirror `env_sample_uv` and `env_pdf` in environment.wgsl.

use std::f64::consts::PI;

use super::texel_of;
use crate::alias::{AliasSlot, alias_pick, alias_slots};
use crate::gpu_types::GpuEnvTexel;
use crate::image::luminance;

/// What a texel's weight is. Only `SolidAngle` is correct; `PerTexel` is the classic bug
/// (sin θ forgotten, poles oversampled) kept so a test can prove the checks catch it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Weighting {
    SolidAngle,
    #[cfg_attr(not(test), allow(dead_code))]
    PerTexel,
}

#[derive(Clone, Debug)]
pub struct EnvDistribution {
    pub width: u32,
    pub height: u32,
    /// W·H conditional entries (alias within the row, pdf of the texel's directions in
    /// solid angle), then H marginal entries (alias over rows; `pdf` = P(row)). This is
    /// the GPU buffer as uploaded.
    pub table: Vec<GpuEnvTexel>,
    /// ∫ luminance dω over the sphere at strength 1 (0 for a black image).
    pub integral: f64,
}

/// A sampled direction as image coordinates, and its pdf in solid angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvSample {
    pub uv: [f32; 2],
    pub pdf: f32,
}

/// Solid angle of one texel of `row` in a W×H equirectangular image.
pub fn texel_solid_angle(row: u32, width: u32, height: u32) -> f64 {
    let theta = |r: u32| PI * r as f64 / height as f64;
    2.0 * PI / width as f64 * (theta(row).cos() - theta(row + 1).cos())
}

impl EnvDistribution {
    pub fn build(width: u32, height: u32, texels: &[[f32; 3]]) -> EnvDistribution {
        Self::build_with(width, height, texels, Weighting::SolidAngle)
    }

    pub(crate) fn build_with(
        width: u32,
        height: u32,
        texels: &[[f32; 3]],
        weighting: Weighting,
    ) -> EnvDistribution {
        let (w, h) = (width as usize, height as usize);
        let mut table = Vec::with_capacity(w * h + h);
        let mut row_weights = Vec::with_capacity(h);
        let mut integral = 0.0;
        let mut weights = vec![0.0f64; w];
        // Density before normalisation, in f64: luminance / Ω overflows f32 near the poles.
        let mut density = Vec::with_capacity(w * h);
        for row in 0..h {
            let omega = texel_solid_angle(row as u32, width, height);
            let factor = match weighting {
                Weighting::SolidAngle => omega,
                Weighting::PerTexel => 1.0,
            };
            for (x, weight) in weights.iter_mut().enumerate() {
                let lum = luminance(texels[row * w + x]).max(0.0) as f64;
                integral += lum * omega;
                *weight = lum * factor;
            }
            let (slots, row_total) = alias_slots(&weights);
            row_weights.push(row_total);
            density.extend(weights.iter().map(|&wt| wt / omega));
            // The pdf is filled in once the grand total is known.
            table.extend(slots.iter().map(|s| GpuEnvTexel {
                alias_threshold: s.threshold,
                alias_index: s.alias,
                pdf: 0.0,
            }));
        }
        let (rows, total) = alias_slots(&row_weights);
        let scale = if total > 0.0 { 1.0 / total } else { 0.0 };
        for (entry, d) in table.iter_mut().zip(density) {
            entry.pdf = (d * scale) as f32;
        }
        table.extend(rows.iter().zip(&row_weights).map(|(s, &wt)| GpuEnvTexel {
            alias_threshold: s.threshold,
            alias_index: s.alias,
            pdf: (wt * scale) as f32,
        }));
        EnvDistribution {
            width,
            height,
            table,
            integral,
        }
    }

    fn slots(&self, start: usize, n: usize) -> Vec<AliasSlot> {
        self.table[start..start + n]
            .iter()
            .map(|e| AliasSlot {
                threshold: e.alias_threshold,
                alias: e.alias_index,
            })
            .collect()
    }

    /// A direction from six uniform numbers in [0, 1), as the shader draws it: row, column,
    /// then φ and cos θ inside the texel. Only for tests and tools (it copies a row).
    pub fn sample(&self, u: [f32; 6]) -> EnvSample {
        let (w, h) = (self.width as usize, self.height as usize);
        let row = alias_pick(&self.slots(w * h, h), u[0], u[1]);
        let col = alias_pick(&self.slots(row * w, w), u[2], u[3]);
        let theta = |r: usize| std::f32::consts::PI * r as f32 / h as f32;
        let (cos0, cos1) = (theta(row).cos(), theta(row + 1).cos());
        let cos_theta = cos0 - u[5] * (cos0 - cos1);
        let uv = [
            (col as f32 + u[4]) / w as f32,
            cos_theta.clamp(-1.0, 1.0).acos() / std::f32::consts::PI,
        ];
        EnvSample {
            uv,
            pdf: self.pdf(uv),
        }
    }

    /// The density of `sample` at `uv`, per steradian (0 where the image is black).
    pub fn pdf(&self, uv: [f32; 2]) -> f32 {
        let (x, y) = texel_of(uv, self.width, self.height);
        self.table[(y * self.width + x) as usize].pdf
    }
}
