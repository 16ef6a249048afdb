//! `seeds.png` (still camera, two seeds or more): where each configuration's bias and its
//! spread over seeds live (docs/src/results.md, "Error bars"). One row per configuration:
//! - **bias**: (mean over seeds − reference) / reference, in the `bias` view's palette
//!   (blue darker, red brighter, saturating at ±25 %), where it exceeds 3 standard errors of
//!   the mean over seeds (and the reference's noise) and 1 % of the reference; elsewhere the
//!   reference in dim grey. With K seeds the standard error rests on K − 1 degrees of
//!   freedom, so at K = 4 about 6 % of an unbiased image's pixels are painted by chance, as
//!   isolated specks; a bias shows as a region.
//! - **spread**: the standard deviation of one seed's accumulated luminance over the seeds,
//!   one inferno scale shared by every row (its top, in luminance, is in the label): where
//!   the accumulated image is still far from converged.

use std::path::Path;

use restir_render::LinearImage;
use restir_render::metrics::pixel_moments::PixelMoments;
use restir_render::metrics::{error_heatmap_scaled, heatmap_scale};
use restir_render::shader_constants::{BIAS_NEGLIGIBLE, BIAS_SIGNIFICANCE};

use super::strip::{self, Panel};
use crate::bench::plan::configs::Config;
use crate::bench::run::reference_sets::ReferenceSets;
use crate::bench::score::result::ConfigResult;

/// One configuration's seeds.
pub struct SeedSet<'a> {
    pub name: &'a str,
    pub moments: Vec<&'a PixelMoments>,
}

/// Per pixel: mean over seeds and the variance of one seed's value (NaN where a seed had
/// no finite value).
fn mean_and_variance(seeds: &[&PixelMoments]) -> (Vec<f64>, Vec<f64>) {
    let means: Vec<Vec<f64>> = seeds.iter().map(|m| m.mean()).collect();
    let k = means.len() as f64;
    let n = means.first().map_or(0, Vec::len);
    (0..n)
        .map(|p| {
            let mean = means.iter().map(|m| m[p]).sum::<f64>() / k;
            let var = means.iter().map(|m| (m[p] - mean).powi(2)).sum::<f64>() / (k - 1.0);
            (mean, var)
        })
        .unzip()
}

/// The bias map of one configuration (display-ready sRGB in [0, 1]).
fn bias_map(
    seeds: &[&PixelMoments],
    reference: &LinearImage,
    reference_luma: &[f64],
    reference_noise: f64,
) -> LinearImage {
    let (mean, var) = mean_and_variance(seeds);
    let k = seeds.len() as f64;
    let pixels = (0..mean.len())
        .map(|p| {
            let truth = reference_luma[p];
            let d = mean[p] - truth;
            let noise = (var[p] / k + reference_noise * reference_noise).sqrt();
            let significant = d.abs() > BIAS_SIGNIFICANCE as f64 * noise
                && d.abs() >= BIAS_NEGLIGIBLE as f64 * truth;
            if !d.is_finite() {
                [0.0, 1.0, 1.0, 1.0]
            } else if significant {
                bias_palette(4.0 * d / truth.max(1e-6))
            } else {
                let [r, _, _] = strip::display_srgb8([truth as f32; 3], 1.0);
                let dim = 0.2 + 0.35 * r as f32 / 255.0;
                [dim, dim, dim, 1.0]
            }
        })
        .collect();
    LinearImage {
        width: reference.width,
        height: reference.height,
        pixels,
    }
}

/// bias_view.wgsl's palette: blue (darker) – white – red (brighter), t in [−1, 1].
fn bias_palette(t: f64) -> [f32; 4] {
    let x = t.clamp(-1.0, 1.0) as f32;
    let far = if x < 0.0 {
        [0.1, 0.3, 1.0]
    } else {
        [1.0, 0.1, 0.05]
    };
    let towards = |c: f32| 1.0 + (c - 1.0) * x.abs();
    [towards(far[0]), towards(far[1]), towards(far[2]), 1.0]
}

/// The per-pixel standard deviation over seeds as a luminance image.
fn spread_image(seeds: &[&PixelMoments], reference: &LinearImage) -> LinearImage {
    let (_, var) = mean_and_variance(seeds);
    LinearImage {
        width: reference.width,
        height: reference.height,
        pixels: var
            .iter()
            .map(|v| {
                let s = v.sqrt() as f32;
                [s, s, s, 1.0]
            })
            .collect(),
    }
}

/// Writes `seeds.png` to `path`: per configuration its bias map and its spread map.
pub fn write(
    path: &Path,
    sets: &[SeedSet],
    reference: &LinearImage,
    reference_noise: f64,
) -> anyhow::Result<()> {
    let reference_luma = restir_render::metrics::seeds::luminance_of(reference);
    let black = LinearImage::new(reference.width, reference.height);
    let spreads: Vec<LinearImage> = sets
        .iter()
        .map(|s| spread_image(&s.moments, reference))
        .collect();
    // One scale for every row: the largest 99th percentile.
    let scale = spreads
        .iter()
        .map(|s| heatmap_scale(s, &black).unwrap_or(0.0))
        .fold(0.0, f64::max);
    let maps: Vec<(LinearImage, LinearImage)> = sets
        .iter()
        .zip(&spreads)
        .map(|(s, spread)| {
            Ok((
                bias_map(&s.moments, reference, &reference_luma, reference_noise),
                error_heatmap_scaled(spread, &black, scale)?,
            ))
        })
        .collect::<anyhow::Result<_>>()?;
    let rows: Vec<[Panel; 2]> = sets
        .iter()
        .zip(&maps)
        .map(|(s, (bias, spread))| {
            [
                Panel {
                    label: format!("{} · bias ({} seeds)", s.name, s.moments.len()),
                    image: bias,
                },
                Panel {
                    label: format!("spread over seeds · top {scale:.3}"),
                    image: spread,
                },
            ]
        })
        .collect();
    let rows: Vec<&[Panel]> = rows.iter().map(|r| &r[..]).collect();
    strip::write_display_grid(path, &rows)
}

/// `seeds.png` in `out`: each configuration's bias and spread over the seeds, against
/// the primary reference; configurations of another max_bounces are left out.
pub fn write_for_seeds(
    out: &Path,
    per_seed: &[Vec<ConfigResult>],
    configs: &[Config],
    sets: &ReferenceSets,
) -> anyhow::Result<()> {
    let primary = sets.primary();
    let primary_bounces = sets.bounces().next().map_or(1, |(b, _)| b);
    let seed_sets: Vec<SeedSet> = per_seed
        .iter()
        .zip(configs)
        .filter(|(_, c)| c.settings.reference_bounces() == primary_bounces)
        .map(|(runs, c)| SeedSet {
            name: &c.name,
            moments: runs.iter().filter_map(|r| r.moments.as_ref()).collect(),
        })
        .collect();
    write(
        &out.join("seeds.png"),
        &seed_sets,
        &primary.images[0],
        primary.noise_luma_rmse.unwrap_or(0.0),
    )
}
