//! With jitter on (the viewer's default), the live per-frame error measures the estimator,
//! not the pixel footprint (docs/src/viewer.md, "Accuracy with jitter on"): each frame is
//! scored against the reference of its own jitter phase, and ReSTIR's error comes out
//! clearly below RIS's, as it does with jitter off. The planted twin scores the same frames
//! against the antialiased reference, as the viewer once did, and must find the two nearly
//! equal. GPU test: fails with a clear message when there is no adapter.

use crate::common;

use restir_render::metrics::luma_rmse;
use restir_render::phase_references::{PhaseReferences, reference_for_frame};
use restir_render::reference_cache::{ReferenceRequest, render_reference};
use restir_render::renderer::jitter_phase;
use restir_render::{Camera, LinearImage, Mode, Renderer, Scene, Settings, load_scene};

const SCENE: &str = "builtin:concourse";
const SIZE: (u32, u32) = (64, 48);
const SPP: u32 = 256;
/// Frames before the first scored one: temporal reuse has its history by then.
const FIRST: u64 = 16;
/// Frames scored, each at its own phase (a reference each).
const SCORED: u64 = 8;

/// The reference image and its own estimated luma RMSE.
fn reference(r: &mut Renderer, request: &ReferenceRequest) -> (LinearImage, f64) {
    let (image, meta) =
        render_reference(r, request, &mut |_| true).unwrap_or_else(|e| panic!("{e:#}"));
    (image, meta.noise_luma_rmse.expect("two halves"))
}

/// Mean per-frame luma RMSE of `mode` (viewer defaults: jitter on) with `seed` over the
/// scored frames, against each frame's phase reference and against the antialiased one.
fn live_errors(
    scene: &Scene,
    camera: Camera,
    (mode, seed): (Mode, u32),
    plain: &LinearImage,
    phases: &PhaseReferences,
) -> (f64, f64) {
    let mut r = Renderer::new(common::gpu(), scene, SIZE.0, SIZE.1, Settings::default())
        .unwrap_or_else(|e| panic!("{e:#}"));
    r.set_mode(mode);
    r.set_camera(camera);
    r.set_seed(seed);
    let (mut matched, mut antialiased) = (0.0, 0.0);
    for _ in 0..FIRST + SCORED {
        let frame = r.frame_index();
        r.render_frame().unwrap_or_else(|e| panic!("{e}"));
        if frame < FIRST {
            continue;
        }
        let image = r.read_radiance();
        let own = reference_for_frame(true, frame, plain, phases).expect("rendered below");
        matched += luma_rmse(&image, own).unwrap();
        antialiased += luma_rmse(&image, plain).unwrap();
    }
    (matched / SCORED as f64, antialiased / SCORED as f64)
}

#[test]
fn jittered_restir_scores_below_ris_against_each_frames_phase_reference() {
    let scene = load_scene(SCENE).unwrap_or_else(|e| panic!("{e}"));
    let camera = scene.default_camera();
    let mut r = Renderer::new(common::gpu(), &scene, SIZE.0, SIZE.1, Settings::default())
        .unwrap_or_else(|e| panic!("{e:#}"));
    let request = |jitter| ReferenceRequest::new(SCENE, &scene, camera, SIZE, SPP, jitter);
    let (plain, _) = reference(&mut r, &request(true));
    let mut phases = PhaseReferences::default();
    let mut noise: f64 = 0.0;
    for frame in FIRST..FIRST + SCORED {
        let phase = jitter_phase(frame);
        let (image, n) = reference(&mut r, &request(false).at_jitter_phase(phase));
        phases.insert(phase, image);
        noise = noise.max(n);
    }
    // What the footprint alone reads at each scored phase (phase reference against the
    // antialiased one): its swing from phase to phase is why one scalar F cannot be
    // subtracted from a frame's error (docs/src/viewer.md, "Accuracy with jitter on").
    let footprint: Vec<String> = (FIRST..FIRST + SCORED)
        .map(|f| {
            let own = reference_for_frame(true, f, &plain, &phases).expect("rendered above");
            format!("{:.3}", luma_rmse(own, &plain).unwrap())
        })
        .collect();
    eprintln!(
        "footprint RMSE per phase: {}; phase references' own noise ≤ {noise:.4}",
        footprint.join(" ")
    );
    // Two seeds: a figure from one seed is a guess.
    for seed in [1, 2] {
        let (restir, restir_plain) =
            live_errors(&scene, camera, (Mode::Restir, seed), &plain, &phases);
        let (ris, ris_plain) = live_errors(&scene, camera, (Mode::Ris, seed), &plain, &phases);
        eprintln!(
            "seed {seed}: per-frame luma RMSE, jitter on: against each frame's phase reference \
             restir {restir:.4} ris {ris:.4}; against the antialiased reference restir \
             {restir_plain:.4} ris {ris_plain:.4}"
        );
        // TOLERANCES (measured: the message above; docs/src/viewer.md, "Accuracy with jitter
        // on"). With jitter off ReSTIR's per-frame error is a third of RIS's on this scene
        // (225×180); phase-matched with jitter on at 64×48 it read 0.55 and 0.61 of RIS's
        // (seeds 1, 2), the 256-spp references' own noise (≤ 0.02, printed) adding to both.
        // 0.7 leaves room for seeds and still separates it from the planted twin's 0.998.
        assert!(
            restir < 0.7 * ris,
            "seed {seed}, jitter on, phase-matched: restir {restir} is not clearly below ris {ris}"
        );
        // Planted: against the antialiased reference (the measurement this replaces) the
        // footprint swamps both estimators: they read within 5 % of each other.
        assert!(
            restir_plain > 0.95 * ris_plain,
            "seed {seed}: the antialiased score should hide the estimator: restir \
             {restir_plain} ris {ris_plain}"
        );
        // And the footprint is what it hid: the antialiased score is far above the matched.
        assert!(restir_plain > 3.0 * restir, "{restir_plain} vs {restir}");
    }
}
