//! The boiling and survivor-change views (docs/src/debug-views.md, "Boiling and survivor
//! change"): the temporal window's σ/mean of each
//! pixel's luminance and its survivor-change fraction. The detector has two halves: a
//! frozen scene rendered by the reference with jitter off and the same random numbers
//! every frame does not boil at all (0 everywhere), and ReSTIR at M cap 100 with
//! permutation sampling boils more than at M cap 5 (docs/src/measured/dynamic-scenes.md, "A high M
//! cap on a static stretch": a mosaic of long-lived samples passed between neighbours). The planted
//! twin computes "boiling" from the current frame alone (its 3 × 3 neighbourhood) and must fail the
//! detector; a second guard shows the zero is not the window's doing (new random numbers per frame
//! do boil).
//!
//! 48 × 32 pixels, a few dozen frames each (lavapipe on two cores).

use crate::common;

use std::collections::BTreeSet;

use restir_render::effects::{EffectSet, SceneFeatures};
use restir_render::renderer::TemporalWindow;
use restir_render::shader_constants::TEMPORAL_WINDOW_FRAMES;
use restir_render::{DebugView, Mode, Renderer, Settings, ViewSettings, load_scene};

const SIZE: (u32, u32) = (48, 32);
/// The Lambertian room with 256 lights, never advanced in time: a frozen scene.
const SCENE: &str = "builtin:dynamic:blinking-lights";
const PLANTED: &str = "PLANTED_WINDOW_CURRENT_FRAME_ONLY";

/// What one run of the window measured.
struct Window {
    window: TemporalWindow,
    /// Pixels that see a surface.
    surface: Vec<bool>,
    /// The view's output (sRGB RGBA8).
    display: Vec<u8>,
}

impl Window {
    fn mean_boiling(&self) -> f64 {
        TemporalWindow::mean(&self.window.rel_std, Some(&self.surface))
    }

    fn max_boiling(&self) -> f32 {
        self.window
            .rel_std
            .iter()
            .zip(&self.surface)
            .filter(|(_, s)| **s)
            .map(|(v, _)| *v)
            .fold(0.0, f32::max)
    }

    fn boiling_share(&self) -> f64 {
        self.window.boiling_share(Some(&self.surface))
    }

    fn mean_survivor_change(&self) -> f64 {
        TemporalWindow::mean(&self.window.change_fraction, Some(&self.surface))
    }
}

/// Renders `frames` frames of `SCENE` in `mode` with the boiling view on.
fn run(mode: Mode, settings: Settings, frozen_noise: bool, planted: bool, frames: u32) -> Window {
    let scene = load_scene(SCENE).unwrap_or_else(|e| panic!("{e}"));
    let mut r = Renderer::new(common::gpu(), &scene, SIZE.0, SIZE.1, settings.clone())
        .unwrap_or_else(|e| panic!("{e:#}"));
    r.set_mode(mode);
    r.set_seed(0);
    r.freeze_noise(frozen_noise);
    if planted {
        let mut effects = EffectSet::detect(&SceneFeatures::of(&scene), &settings, false);
        effects.planted = BTreeSet::from([PLANTED.to_string()]);
        r.force_effects(Some(effects));
    }
    r.set_view(ViewSettings {
        view: DebugView::Boiling,
        ..ViewSettings::default()
    });
    for _ in 0..frames {
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
    }
    let window = r
        .read_temporal_window()
        .expect("the boiling view keeps the window");
    assert_eq!(window.frames, TEMPORAL_WINDOW_FRAMES.min(frames));
    let surface = r.read_surfaces().iter().map(|s| s.depth > 0.0).collect();
    Window {
        window,
        surface,
        display: r.read_display_rgba8(),
    }
}

fn frozen_reference(planted: bool, frozen_noise: bool) -> Window {
    let settings = common::settings(&["jitter=false", "reference_spp=4"]);
    run(Mode::Reference, settings, frozen_noise, planted, 20)
}

fn restir(m_cap: u32, planted: bool) -> Window {
    let settings = common::settings(&[
        "jitter=false",
        "permutation=true",
        &format!("m_cap={m_cap}"),
    ]);
    run(Mode::Restir, settings, false, planted, 60)
}

/// The detector: zero on the frozen reference, and a larger share of boiling pixels at
/// M cap 100 than at 5. The share, not the mean: at M cap 100 most pixels hold one
/// long-lived sample (calmer than at 5: median σ/mean 0.07 against 0.11 here) while the
/// ones whose survivor comes and goes boil hard (3.5 % above the threshold against 1.0 %
/// with seed 0, 2.8-4× over seeds 0-3 with the default radius; 1.5× is the margin asked
/// for).
fn detector_holds(planted: bool) -> bool {
    let frozen = frozen_reference(planted, true);
    let (high, low) = (restir(100, planted), restir(5, planted));
    eprintln!(
        "planted={planted}: frozen reference max {:.3e}; restir boiling share M cap 100 {:.4}, \
         M cap 5 {:.4} (mean σ/mean {:.4}, {:.4})",
        frozen.max_boiling(),
        high.boiling_share(),
        low.boiling_share(),
        high.mean_boiling(),
        low.mean_boiling()
    );
    frozen.max_boiling() == 0.0 && high.boiling_share() > 1.5 * low.boiling_share()
}

#[test]
fn a_frozen_image_does_not_boil_and_a_high_m_cap_boils_more() {
    assert!(
        detector_holds(false),
        "the boiling detector failed (see the figures above)"
    );
}

/// A view that reads the current frame only sees noise where nothing flickers.
#[test]
fn planted_current_frame_only_boiling_fails_the_detector() {
    assert!(
        !detector_holds(true),
        "a view that reads only the current frame passed the boiling test"
    );
}

/// The zero comes from the frozen noise, not from the window: a new draw every frame
/// boils, and the view paints the frozen image the palette's 0 everywhere it sees a surface.
#[test]
fn the_zero_is_the_images_and_the_view_paints_it() {
    let frozen = frozen_reference(false, true);
    let live = frozen_reference(false, false);
    eprintln!(
        "reference, new noise per frame: mean boiling {:.4}",
        live.mean_boiling()
    );
    assert!(live.mean_boiling() > 0.1, "4 spp per frame should flicker");
    // The palette's 0 (viridis' dark purple) on every surface pixel.
    fn colour(w: &Window, i: usize) -> &[u8] {
        &w.display[i * 4..i * 4 + 4]
    }
    let first = frozen.surface.iter().position(|s| *s).expect("a surface");
    let zero = colour(&frozen, first).to_vec();
    assert!(
        zero[2] > zero[1] && zero[0] > zero[1],
        "not viridis' 0: {zero:?}"
    );
    for (i, s) in frozen.surface.iter().enumerate() {
        if *s {
            assert_eq!(colour(&frozen, i), &zero[..], "pixel {i}");
        }
    }
    assert!((0..live.surface.len()).any(|i| live.surface[i] && colour(&live, i) != &zero[..]));
}

/// The survivor-change view: the reference has no survivors (0 everywhere); ReSTIR's
/// survivors do change, and a rejected-everything history changes them every frame.
#[test]
fn survivors_change_under_restir_and_not_in_the_reference() {
    let frozen = frozen_reference(false, true);
    assert_eq!(frozen.mean_survivor_change(), 0.0);
    let low = restir(5, false);
    let fraction = low.mean_survivor_change();
    eprintln!("restir M cap 5: mean survivor change {fraction:.3}");
    assert!(fraction > 0.05 && fraction <= 1.0, "{fraction}");
}
