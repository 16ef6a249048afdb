//! The denoiser in plain Rust, pass for pass as the WGSL under `shaders/denoise/` computes
//! it (docs/src/denoiser.md): the tests run it on the GPU's own inputs and compare, and
//! plant the errors the GPU tests must catch. Images are row-major, `width × height`.

use glam::{Vec2, Vec3, Vec4};

use crate::denoise::constants::{
    DENOISE_ALBEDO_FLOOR, DENOISE_GRADIENT_STRIDE, DENOISE_GRADIENT_TAPS, DENOISE_MIN_HISTORY,
    DENOISE_NORMAL_COS, DENOISE_POSITION_TOLERANCE, DENOISE_VARIANCE_RADIUS,
};
use crate::denoise::params::GpuDenoiseParams;
use crate::gpu_types::{GpuDenoiseHistory, GpuSurface};

/// What the denoiser reads of a pixel's G-buffer surface.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pixel {
    /// False where the pixel sees no surface (the sky, or nothing): passed through unfiltered.
    pub valid: bool,
    pub position: Vec3,
    pub depth: f32,
    pub normal: Vec3,
    pub geo_normal: Vec3,
    pub base_color: Vec3,
    pub emission: Vec3,
    pub throughput: Vec3,
    /// Where the point was last frame, in pixels (centres at +0.5); negative: not seen.
    pub motion: Vec2,
}

impl Pixel {
    pub fn from_surface(s: &GpuSurface) -> Pixel {
        let base = s.base_color_metallic.to_le_bytes();
        Pixel {
            valid: s.depth > 0.0,
            position: s.position.into(),
            depth: s.depth,
            normal: oct_decode(s.normal),
            geo_normal: oct_decode(s.geo_normal),
            base_color: Vec3::new(base[0] as f32, base[1] as f32, base[2] as f32) / 255.0,
            emission: s.emission.into(),
            throughput: s.throughput.into(),
            motion: s.motion.into(),
        }
    }

    /// What the lighting is divided by before filtering and multiplied by after: the
    /// surface's colour and the weight of the glass in front of it, so the filter sees
    /// illumination alone and texture detail survives it.
    pub fn demodulation(&self) -> Vec3 {
        (self.base_color * self.throughput).max(Vec3::splat(DENOISE_ALBEDO_FLOOR))
    }
}

/// `oct_decode` of math.wgsl (`unpack2x16snorm`, then the octahedron folded back).
pub fn oct_decode(e: u32) -> Vec3 {
    let snorm = |v: u32| ((v & 0xffff) as u16 as i16 as f32 / 32767.0).clamp(-1.0, 1.0);
    let p = Vec2::new(snorm(e), snorm(e >> 16));
    let mut n = Vec3::new(p.x, p.y, 1.0 - p.x.abs() - p.y.abs());
    let t = (-n.z).max(0.0);
    n.x += if n.x >= 0.0 { -t } else { t };
    n.y += if n.y >= 0.0 { -t } else { t };
    n.normalize()
}

/// The denoiser's knobs (the `denoise_*` rows of the settings table; `settings::model_params`
/// fills them).
#[derive(Clone, Copy, Debug)]
pub struct Params {
    /// The knobs the shaders read too (`params.denoise`), exactly as the GPU gets them.
    pub uniform: GpuDenoiseParams,
    pub iterations: u32,
    /// The angle between neighbouring pixels' camera rays (the world footprint of a pixel
    /// is its depth times this).
    pub pixel_angle: f32,
}

impl Params {
    /// The angle between the image centre's ray and the next pixel's, as the WGSL measures
    /// it (`denoise_pixel_angle`), for a vertical field of view and an image height.
    pub fn pixel_angle(yfov: f32, height: u32) -> f32 {
        (2.0 * (yfov / 2.0).tan() / height as f32).atan()
    }
}

/// Errors the tests plant to prove that they would see them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Planted {
    /// À-trous weights without depth, normal and luminance terms (a plain blur).
    pub no_edge_stopping: bool,
    /// The luminance gate scaled by the centre pixel's variance alone.
    pub centre_variance_gate: bool,
}

pub struct Frame<'a> {
    pub width: u32,
    pub height: u32,
    pub pixels: &'a [Pixel],
    /// Last frame's surfaces (for validating the reprojected history).
    pub previous: &'a [Pixel],
    pub radiance: &'a [Vec3],
}

pub fn luminance(c: Vec3) -> f32 {
    crate::image::luminance(c.into())
}

impl Frame<'_> {
    fn index(&self, x: i32, y: i32) -> Option<usize> {
        (x >= 0 && y >= 0 && x < self.width as i32 && y < self.height as i32)
            .then(|| (y as u32 * self.width + x as u32) as usize)
    }

    fn coords(&self, i: usize) -> (i32, i32) {
        (
            (i as u32 % self.width) as i32,
            (i as u32 / self.width) as i32,
        )
    }

    /// The lighting at pixel `i` divided by its demodulation (0 where it sees no surface).
    pub fn illumination(&self, i: usize) -> Vec3 {
        let p = &self.pixels[i];
        if !p.valid {
            return Vec3::ZERO;
        }
        ((self.radiance[i] - p.emission).max(Vec3::ZERO)) / p.demodulation()
    }
}

/// Whether last frame's surface `prev` is this pixel's point seen again.
pub fn same_surface(p: &Pixel, prev: &Pixel) -> bool {
    prev.valid
        && p.normal.dot(prev.normal) >= DENOISE_NORMAL_COS
        && (prev.position - p.position).length() <= DENOISE_POSITION_TOLERANCE * p.depth
}

/// The temporal gradient λ per pixel from DI's gradient samples (each pixel's history
/// sample shaded last frame and now, `GpuPixelDebug::gradient`): both summed over a
/// neighbourhood on the same surfaces, λ = |Σ now − Σ before| / max(Σ now, Σ before).
pub fn gradient(f: &Frame, samples: &[[f32; 2]], p: &Params) -> Vec<f32> {
    (0..f.pixels.len())
        .map(|i| {
            let px = &f.pixels[i];
            if !px.valid {
                return 0.0;
            }
            let (x, y) = f.coords(i);
            let r = DENOISE_GRADIENT_TAPS as i32;
            let stride = DENOISE_GRADIENT_STRIDE as i32;
            let (mut before, mut now) = (0.0f32, 0.0f32);
            for dy in -r..=r {
                for dx in -r..=r {
                    let (ox, oy) = (dx * stride, dy * stride);
                    let Some(j) = f.index(x + ox, y + oy) else {
                        continue;
                    };
                    if !f.pixels[j].valid {
                        continue;
                    }
                    let distance = ((ox * ox + oy * oy) as f32).sqrt();
                    let w = geometry_weight(px, &f.pixels[j], distance, p, Planted::default());
                    before += w * samples[j][0];
                    now += w * samples[j][1];
                }
            }
            let larger = before.max(now);
            if larger > 0.0 {
                ((now - before).abs() / larger).clamp(0.0, 1.0)
            } else {
                0.0
            }
        })
        .collect()
}

/// Temporal accumulation: this frame's illumination blended into last frame's,
/// reprojected through the motion vector with a bilinear filter over the taps that see the
/// same surface; luminance moments alike. `history` is `None` when there is none (first
/// frame, cut, resize); `lambda`, the temporal gradient, raises this frame's weight.
pub fn temporal(
    f: &Frame,
    history: Option<&[GpuDenoiseHistory]>,
    lambda: Option<&[f32]>,
    p: &Params,
) -> Vec<GpuDenoiseHistory> {
    (0..f.pixels.len())
        .map(|i| {
            let px = &f.pixels[i];
            if !px.valid {
                return GpuDenoiseHistory::default();
            }
            let illum = f.illumination(i);
            let l = luminance(illum);
            let mut acc = (Vec3::ZERO, 0.0f32, Vec2::ZERO, 0.0f32);
            if let Some(h) = history
                && px.motion.x >= 0.0
                && px.motion.y >= 0.0
            {
                let c = px.motion - 0.5;
                let (x0, y0) = (c.x.floor(), c.y.floor());
                let (fx, fy) = (c.x - x0, c.y - y0);
                for (dx, dy, w) in [
                    (0, 0, (1.0 - fx) * (1.0 - fy)),
                    (1, 0, fx * (1.0 - fy)),
                    (0, 1, (1.0 - fx) * fy),
                    (1, 1, fx * fy),
                ] {
                    let Some(j) = f.index(x0 as i32 + dx, y0 as i32 + dy) else {
                        continue;
                    };
                    if w <= 0.0 || !same_surface(px, &f.previous[j]) || h[j].length <= 0.0 {
                        continue;
                    }
                    acc.0 += w * Vec3::from(h[j].illumination);
                    acc.1 += w * h[j].length;
                    acc.2 += w * Vec2::from(h[j].moments);
                    acc.3 += w;
                }
            }
            let has_history = acc.3 > 1e-3;
            let (length, alpha, moments_alpha) = if has_history {
                let length = (acc.1 / acc.3 + 1.0).min(p.uniform.history_cap.max(1.0));
                // α + (1 − α) λ: a changed neighbourhood weighs this frame more.
                let lambda = lambda.map_or(0.0, |l| l[i]);
                let blend = |alpha: f32| {
                    let alpha = alpha.max(1.0 / length);
                    alpha + (1.0 - alpha) * lambda
                };
                (
                    length,
                    blend(p.uniform.alpha),
                    blend(p.uniform.moments_alpha),
                )
            } else {
                (1.0, 1.0, 1.0)
            };
            let (prev_illum, prev_moments) = if has_history {
                (acc.0 / acc.3, acc.2 / acc.3)
            } else {
                (illum, Vec2::new(l, l * l))
            };
            let illum = prev_illum.lerp(illum, alpha);
            let moments = prev_moments.lerp(Vec2::new(l, l * l), moments_alpha);
            if !illum.is_finite() || !(moments.x + moments.y).is_finite() {
                // Absurd radiance (l² beyond f32): the pixel starts afresh, black.
                return GpuDenoiseHistory {
                    length: 1.0,
                    ..Default::default()
                };
            }
            GpuDenoiseHistory {
                illumination: illum.into(),
                length,
                moments: moments.into(),
                _pad: [0.0; 2],
            }
        })
        .collect()
}

/// Edge-stopping weights between pixel `a` (the centre) and `b`, `distance` pixels apart.
fn geometry_weight(a: &Pixel, b: &Pixel, distance: f32, p: &Params, planted: Planted) -> f32 {
    if planted.no_edge_stopping {
        return 1.0;
    }
    let normal = a.normal.dot(b.normal).max(0.0).powf(p.uniform.phi_normal);
    // Distance from b to a's tangent plane, against how far a pixel reaches at a's depth:
    // zero on the same plane however steep, large across a silhouette.
    let plane = a.geo_normal.dot(b.position - a.position).abs();
    let reach = p.uniform.phi_depth * a.depth * p.pixel_angle * distance + 1e-6 * a.depth;
    normal * (-plane / reach).exp()
}

/// The variance estimate: the temporal moments' variance where the history is long enough,
/// else (a new or disoccluded pixel) the moments and illumination of a 7 × 7 neighbourhood
/// on the same surfaces, its variance raised by 4 / length as SVGF does for short histories.
/// Output: (illumination, variance).
pub fn variance(f: &Frame, h: &[GpuDenoiseHistory], p: &Params) -> Vec<Vec4> {
    (0..f.pixels.len())
        .map(|i| {
            let px = &f.pixels[i];
            if !px.valid {
                return Vec4::ZERO;
            }
            let m = Vec2::from(h[i].moments);
            if h[i].length >= DENOISE_MIN_HISTORY as f32 {
                return Vec3::from(h[i].illumination).extend((m.y - m.x * m.x).max(0.0));
            }
            let (x, y) = f.coords(i);
            let r = DENOISE_VARIANCE_RADIUS as i32;
            let (mut illum, mut moments, mut sum) = (Vec3::ZERO, Vec2::ZERO, 0.0f32);
            for dy in -r..=r {
                for dx in -r..=r {
                    let Some(j) = f.index(x + dx, y + dy) else {
                        continue;
                    };
                    if !f.pixels[j].valid {
                        continue;
                    }
                    let distance = ((dx * dx + dy * dy) as f32).sqrt();
                    let w = geometry_weight(px, &f.pixels[j], distance, p, Planted::default());
                    illum += w * Vec3::from(h[j].illumination);
                    moments += w * Vec2::from(h[j].moments);
                    sum += w;
                }
            }
            // The centre's own weight is 1, so `sum` ≥ 1.
            let (illum, moments) = (illum / sum, moments / sum);
            let var = (moments.y - moments.x * moments.x).max(0.0) * 4.0 / h[i].length.max(1.0);
            illum.extend(var)
        })
        .collect()
}

const KERNEL: [f32; 5] = [1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0];

/// The centre's variance blurred 3 × 3 (Gaussian, over pixels with a surface): a steadier
/// scale for the luminance gate than one pixel's estimate.
fn prefiltered_variance(f: &Frame, input: &[Vec4], i: usize) -> f32 {
    let (x, y) = f.coords(i);
    let k = [0.25f32, 0.5, 0.25];
    let (mut var, mut sum) = (0.0f32, 0.0f32);
    for dy in -1..=1i32 {
        for dx in -1..=1i32 {
            let Some(j) = f.index(x + dx, y + dy) else {
                continue;
            };
            if f.pixels[j].valid {
                let w = k[(dx + 1) as usize] * k[(dy + 1) as usize];
                var += w * input[j].w;
                sum += w;
            }
        }
    }
    var / sum
}

/// One à-trous iteration with taps `step` pixels apart: the 5 × 5 B3-spline kernel,
/// weighted by depth, normal and luminance edge-stopping. Variance is carried as the
/// variance of the weighted mean (Σ w² σ² / (Σ w)²).
pub fn atrous(f: &Frame, input: &[Vec4], step: i32, p: &Params, planted: Planted) -> Vec<Vec4> {
    (0..f.pixels.len())
        .map(|i| {
            let px = &f.pixels[i];
            if !px.valid {
                return input[i];
            }
            let (x, y) = f.coords(i);
            let l = luminance(input[i].truncate());
            let var_centre = prefiltered_variance(f, input, i);
            let (mut illum, mut var, mut sum) = (Vec3::ZERO, 0.0f32, 0.0f32);
            for ky in 0..5i32 {
                for kx in 0..5i32 {
                    let (dx, dy) = ((kx - 2) * step, (ky - 2) * step);
                    let Some(j) = f.index(x + dx, y + dy) else {
                        continue;
                    };
                    if !f.pixels[j].valid {
                        continue;
                    }
                    let q = input[j];
                    let distance = ((dx * dx + dy * dy) as f32).sqrt();
                    let mut w = KERNEL[kx as usize] * KERNEL[ky as usize];
                    w *= geometry_weight(px, &f.pixels[j], distance, p, planted);
                    if !planted.no_edge_stopping {
                        // The difference of two independent estimates has the sum of their
                        // variances: gating by the centre's alone keeps a bright pixel's
                        // neighbours out of its own mean but lets it average the dark ones
                        // in, so bright energy is lost.
                        let spread = if planted.centre_variance_gate {
                            var_centre
                        } else {
                            var_centre + q.w.max(0.0)
                        };
                        let lq = luminance(q.truncate());
                        w *= (-(l - lq).abs() / (p.uniform.phi_luminance * spread.sqrt() + 1e-10))
                            .exp();
                    }
                    illum += w * q.truncate();
                    var += w * w * q.w;
                    sum += w;
                }
            }
            // The centre's weight is 9/64 > 0 whatever the edges say.
            (illum / sum).extend(var / (sum * sum))
        })
        .collect()
}

/// Remodulation: the filtered illumination times the pixel's demodulation, plus its
/// emission; pixels without a surface keep their radiance.
pub fn modulate(f: &Frame, filtered: &[Vec4]) -> Vec<Vec3> {
    (0..f.pixels.len())
        .map(|i| {
            let px = &f.pixels[i];
            if !px.valid {
                return f.radiance[i];
            }
            px.emission + px.demodulation() * filtered[i].truncate()
        })
        .collect()
}

/// One frame of the whole denoiser: (next frame's history, the denoised radiance).
/// `gradient_samples`: DI's gradient samples when temporal gradients are on.
pub fn denoise(
    f: &Frame,
    history: Option<&[GpuDenoiseHistory]>,
    gradient_samples: Option<&[[f32; 2]]>,
    p: &Params,
    planted: Planted,
) -> (Vec<GpuDenoiseHistory>, Vec<Vec3>) {
    let lambda = gradient_samples.map(|s| gradient(f, s, p));
    let h = temporal(f, history, lambda.as_deref(), p);
    let mut filtered = variance(f, &h, p);
    for i in 0..p.iterations {
        filtered = atrous(f, &filtered, 1 << i, p, planted);
    }
    (h.clone(), modulate(f, &filtered))
}
