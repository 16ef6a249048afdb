//! The indirect-light tests' harness (restir_gi.rs, restir_pt.rs, restir_pt_inspect.rs):
//! a real-time renderer with jitter off and planted test-only defines, and the image's
//! mean luminance.

use std::collections::BTreeSet;

use restir_render::effects::{EffectSet, SceneFeatures};
use restir_render::{LinearImage, Mode, Renderer, Scene};

pub fn mean_luma(img: &LinearImage) -> f64 {
    let n = img.pixels.len() as f64;
    (0..img.height)
        .flat_map(|y| (0..img.width).map(move |x| (x, y)))
        .map(|(x, y)| img.luminance_at(x, y) as f64)
        .sum::<f64>()
        / n
}

/// `frames` ReSTIR frames of `scene` at `size` with jitter off, `assignments` on top of
/// the defaults, and `planted` (a test-only define, see effects.rs) compiled in.
pub fn render_planted(
    scene: &Scene,
    size: (u32, u32),
    assignments: &[&str],
    planted: Option<&str>,
    frames: u32,
) -> Renderer {
    let mut all = vec!["jitter=false"];
    all.extend_from_slice(assignments);
    let settings = super::settings(&all);
    let mut effects = EffectSet::detect(&SceneFeatures::of(scene), &settings, false);
    effects.planted = planted
        .map(str::to_string)
        .into_iter()
        .collect::<BTreeSet<_>>();
    let mut r = Renderer::new(super::gpu(), scene, size.0, size.1, settings).unwrap();
    r.force_effects(Some(effects));
    r.set_mode(Mode::Restir);
    r.reset_accumulation();
    for _ in 0..frames {
        r.render_frame().unwrap();
    }
    r
}
