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

/// Renders `frames` frames while orbiting about the point one scene-scale unit ahead of the
/// camera (so temporal reuse shifts samples between visible points), and returns how many
/// non-finite values the passes' guards counted and replaced; `name` labels a failure.
pub fn orbit_counting_non_finite(r: &mut Renderer, frames: u32, name: &str) -> u64 {
    let start = r.camera();
    let centre = start.position + start.forward() * r.scene_scale();
    let mut counted = 0;
    for frame in 0..frames {
        let turn = glam::Quat::from_rotation_y(0.05 * frame as f32);
        let position = centre + turn * (start.position - centre);
        r.set_camera(restir_render::Camera::look_at(position, centre, start.yfov));
        r.render_frame().unwrap_or_else(|e| panic!("{name}: {e}"));
        counted += r
            .collect_reports(true)
            .iter()
            .map(|f| f.counters.non_finite_total())
            .sum::<u64>();
    }
    counted
}

/// Renders one frame and returns what stats counter `index` counted in it.
pub fn count_in_next_frame(r: &mut Renderer, index: u32) -> u64 {
    r.collect_reports(true);
    r.render_frame().unwrap();
    r.collect_reports(true)
        .iter()
        .map(|f| f.counters.get(index))
        .sum()
}
