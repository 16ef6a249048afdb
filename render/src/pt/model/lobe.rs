//! One BSDF lobe per material: Lambert for a rough surface, a normalised Phong lobe about
//! the mirror direction for a glossy one (exponent `e = 2/r² − 2`, the Beckmann-equivalent
//! roughness `r`). Each lobe samples by an invertible map of two uniform numbers, so random
//! replay can reuse them and the tests can invert a direction back to its numbers. One lobe
//! per material keeps the replay Jacobian a ratio of the lobe's own densities; with a
//! mixture the Jacobian is the chosen lobe's ratio, not the mixture's.

use glam::Vec3;
use std::f32::consts::PI;

/// Roughness at and above which a material is Lambertian.
const LAMBERT_ROUGHNESS: f32 = 0.999;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    pub albedo: f32,
    /// In (0, 1]: 1 is Lambert, small is a near mirror.
    pub roughness: f32,
}

/// A direction sampled by a lobe, with its density (solid angle) and the BSDF value.
#[derive(Clone, Copy, Debug)]
pub struct Sampled {
    pub direction: Vec3,
    pub pdf: f32,
}

impl Lobe {
    fn exponent(&self) -> Option<f32> {
        (self.roughness < LAMBERT_ROUGHNESS).then(|| {
            let r = self.roughness.max(1e-3);
            2.0 / (r * r) - 2.0
        })
    }

    /// The lobe's axis at a surface of normal `n` seen from `w_in` (unit, pointing away).
    fn axis(&self, n: Vec3, w_in: Vec3) -> Vec3 {
        match self.exponent() {
            Some(_) => (2.0 * n.dot(w_in) * n - w_in).normalize(),
            None => n,
        }
    }

    /// The direction the numbers `u` map to (the lobe's inverse CDF). It may lie below the
    /// surface (a glossy lobe near grazing): then `eval` is 0 there.
    pub fn sample(&self, n: Vec3, w_in: Vec3, u: [f32; 2]) -> Sampled {
        let axis = self.axis(n, w_in);
        let (t, b) = axis.any_orthonormal_pair();
        let cos = match self.exponent() {
            Some(e) => u[0].max(0.0).powf(1.0 / (e + 1.0)),
            None => (1.0 - u[0]).max(0.0).sqrt(),
        };
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        let phi = 2.0 * PI * u[1];
        let direction = (t * (sin * phi.cos()) + b * (sin * phi.sin()) + axis * cos).normalize();
        Sampled {
            direction,
            pdf: self.pdf(n, w_in, direction),
        }
    }

    /// The numbers `sample` maps to `direction` (its inverse).
    pub fn numbers_of(&self, n: Vec3, w_in: Vec3, direction: Vec3) -> [f32; 2] {
        let axis = self.axis(n, w_in);
        let (t, b) = axis.any_orthonormal_pair();
        let cos = axis.dot(direction).clamp(0.0, 1.0);
        let u0 = match self.exponent() {
            Some(e) => cos.powf(e + 1.0),
            None => 1.0 - cos * cos,
        };
        let phi = b.dot(direction).atan2(t.dot(direction));
        let u1 = (phi / (2.0 * PI)).rem_euclid(1.0);
        [u0, u1]
    }

    /// Solid-angle density of `sample` at `direction`.
    pub fn pdf(&self, n: Vec3, w_in: Vec3, direction: Vec3) -> f32 {
        let cos = self.axis(n, w_in).dot(direction).max(0.0);
        match self.exponent() {
            Some(e) => (e + 1.0) / (2.0 * PI) * cos.powf(e),
            None => cos / PI,
        }
    }

    /// The BSDF from `w_in` to `direction`; 0 below the surface.
    pub fn eval(&self, n: Vec3, w_in: Vec3, direction: Vec3) -> f32 {
        if n.dot(direction) <= 0.0 || n.dot(w_in) <= 0.0 {
            return 0.0;
        }
        match self.exponent() {
            Some(e) => {
                let cos = self.axis(n, w_in).dot(direction).max(0.0);
                self.albedo * (e + 2.0) / (2.0 * PI) * cos.powf(e)
            }
            None => self.albedo / PI,
        }
    }

    pub fn is_rough(&self, threshold: f32) -> bool {
        self.roughness >= threshold
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reservoir::test_support::Rng;

    const LOBES: [Lobe; 3] = [
        Lobe {
            albedo: 0.7,
            roughness: 1.0,
        },
        Lobe {
            albedo: 0.7,
            roughness: 0.35,
        },
        Lobe {
            albedo: 0.9,
            roughness: 0.03,
        },
    ];

    #[test]
    fn numbers_of_inverts_sample() {
        let mut rng = Rng::new(3);
        let n = Vec3::new(0.1, 0.2, 1.0).normalize();
        let w_in = Vec3::new(-0.5, 0.3, 0.7).normalize();
        for lobe in LOBES {
            for _ in 0..1000 {
                let u = [rng.range(0.01, 0.99), rng.range(0.01, 0.99)];
                let d = lobe.sample(n, w_in, u).direction;
                let back = lobe.numbers_of(n, w_in, d);
                // f32 round trip through powf and atan2: 1e-3 of the unit square.
                assert!((back[0] - u[0]).abs() < 1e-3, "{lobe:?} {u:?} {back:?}");
                let du1 = (back[1] - u[1]).abs();
                assert!(du1.min(1.0 - du1) < 1e-3, "{lobe:?} {u:?} {back:?}");
            }
        }
    }

    /// The density integrates to 1 over the sphere (midpoint rule in (cos, φ) about the
    /// axis would hide an error in the normalisation, so integrate over the sphere's
    /// own coordinates instead).
    #[test]
    fn pdf_integrates_to_one() {
        let n = Vec3::Z;
        let w_in = Vec3::new(0.3, 0.0, 1.0).normalize();
        for lobe in &LOBES[..2] {
            let (steps_t, steps_p) = (2000, 400);
            let mut sum = 0.0f64;
            for i in 0..steps_t {
                let ct = -1.0 + 2.0 * (i as f64 + 0.5) / steps_t as f64;
                let st = (1.0 - ct * ct).sqrt();
                for j in 0..steps_p {
                    let p = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / steps_p as f64;
                    let d = Vec3::new((st * p.cos()) as f32, (st * p.sin()) as f32, ct as f32);
                    sum += lobe.pdf(n, w_in, d) as f64;
                }
            }
            let integral = sum * 4.0 * std::f64::consts::PI / (steps_t * steps_p) as f64;
            // Midpoint quadrature of a lobe of exponent ~14: 1e-3.
            assert!((integral - 1.0).abs() < 2e-3, "{lobe:?}: {integral}");
        }
    }
}
