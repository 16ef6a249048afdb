//! Images compared block by block, so that a bias cannot hide in the image mean by
//! darkening one part and brightening another (light_samplers.rs, vertex_light_sampler.rs).

use restir_render::LinearImage;

/// Blocks of BLOCK × BLOCK pixels.
pub const BLOCK: u32 = 16;

/// Mean luminance of each BLOCK × BLOCK block, row by row.
pub fn block_means(img: &LinearImage) -> Vec<f64> {
    let mut means = Vec::new();
    for by in 0..img.height / BLOCK {
        for bx in 0..img.width / BLOCK {
            let mut sum = 0.0;
            for y in by * BLOCK..(by + 1) * BLOCK {
                for x in bx * BLOCK..(bx + 1) * BLOCK {
                    sum += img.luminance_at(x, y) as f64;
                }
            }
            means.push(sum / (BLOCK * BLOCK) as f64);
        }
    }
    means
}

/// The largest relative difference of a block against `base`'s.
pub fn worst_block(estimate: &[f64], base: &[f64]) -> f64 {
    estimate
        .iter()
        .zip(base)
        .map(|(e, b)| (e - b).abs() / b.max(1e-6))
        .fold(0.0, f64::max)
}
