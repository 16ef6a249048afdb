//! ReSTIR GI (issue 12) against exact answers and the 2-bounce reference.

mod common;

use std::collections::BTreeSet;

use restir_render::effects::{EffectSet, SceneFeatures};
use restir_render::metrics::luma_ratio;
use restir_render::{LinearImage, Mode, Renderer, load_scene};

fn luma(p: &[f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Mean luma over 8×8-pixel blocks, for block-wise comparisons that average noise away.
fn blocks(img: &LinearImage) -> Vec<f64> {
    let (bw, bh) = (img.width / 8, img.height / 8);
    let mut out = vec![0.0; (bw * bh) as usize];
    for y in 0..bh * 8 {
        for x in 0..bw * 8 {
            out[((y / 8) * bw + x / 8) as usize] += luma(&img.pixels[(y * img.width + x) as usize]) / 64.0;
        }
    }
    out
}

fn cornell_gi(assignments: &[&str], planted: Option<&str>, frames: u32) -> LinearImage {
    let scene = load_scene("builtin:cornell").unwrap();
    let mut all = vec!["jitter=false", "gi=true"];
    all.extend_from_slice(assignments);
    let settings = common::settings(&all);
    let mut effects = EffectSet::detect(&SceneFeatures::of(&scene), &settings, false);
    effects.planted = planted.map(str::to_string).into_iter().collect::<BTreeSet<_>>();
    let mut r = Renderer::new(common::gpu(), &scene, 64, 48, settings).unwrap();
    r.force_effects(Some(effects));
    r.set_mode(Mode::Restir);
    common::accumulate(&mut r, frames)
}

fn cornell_reference(bounces: u32, spp: u32) -> LinearImage {
    let settings = common::settings(&["jitter=false", &format!("max_bounces={bounces}")]);
    let mut r = common::renderer("builtin:cornell", 64, 48, Mode::Reference, settings);
    common::reference(&mut r, 1, spp)
}

fn mean_luma(img: &LinearImage) -> f64 {
    img.pixels.iter().map(luma).sum::<f64>() / img.pixels.len() as f64
}

#[test]
fn explore() {
    let ref2 = cornell_reference(2, 2048);
    let ref1 = cornell_reference(1, 2048);
    let indirect_ref = mean_luma(&ref2) - mean_luma(&ref1);
    let frames = 256;
    let di = cornell_gi(&["gi=false"], None, frames);
    let di_wide = cornell_gi(&["gi=false"], None, frames);
    assert_eq!(mean_luma(&di), mean_luma(&di_wide));
    for (name, a, p) in [
        ("pairwise", vec![], None),
        ("1/M", vec!["gi_bias_correction=one-over-m"], None),
        ("wide spatial pairwise", vec!["gi_temporal=false", "gi_spatial_radius=600", "gi_jacobian_max=1000", "gi_spatial_neighbours=5"], None),
        ("wide spatial pairwise noJ", vec!["gi_temporal=false", "gi_spatial_radius=600", "gi_jacobian_max=1000", "gi_spatial_neighbours=5"], Some("PLANTED_GI_NO_JACOBIAN")),
        ("wide spatial 1/M", vec!["gi_temporal=false", "gi_spatial_radius=600", "gi_jacobian_max=1000", "gi_spatial_neighbours=5", "gi_bias_correction=one-over-m"], None),
        ("wide spatial 1/M noJ", vec!["gi_temporal=false", "gi_spatial_radius=600", "gi_jacobian_max=1000", "gi_spatial_neighbours=5", "gi_bias_correction=one-over-m"], Some("PLANTED_GI_NO_JACOBIAN")),
    ] {
        let img = cornell_gi(&a, p, frames);
        let ind = mean_luma(&img) - mean_luma(&di);
        let bi: Vec<f64> = blocks(&img).iter().zip(blocks(&di)).map(|(a, b)| a - b).collect();
        let br: Vec<f64> = blocks(&ref2).iter().zip(blocks(&ref1)).map(|(a, b)| a - b).collect();
        let rel: Vec<f64> = bi.iter().zip(&br).filter(|(_, b)| **b > 1e-4).map(|(a, b)| a / b).collect();
        let mean_rel = rel.iter().sum::<f64>() / rel.len() as f64;
        let sd = (rel.iter().map(|r| (r - mean_rel).powi(2)).sum::<f64>() / (rel.len() - 1) as f64).sqrt();
        eprintln!("{name}: indirect ratio {:.4}; block ratios mean {:.4} sd {:.4} (n {})", ind / indirect_ref, mean_rel, sd, rel.len());
    }
}
