//! ReSTIR PT (docs/src/restir-pt.md) against exact answers and the multi-bounce reference, per
//! shift.
//!
//! As for GI (restir_gi.rs), the indirect part is measured alone: PT's passes draw their
//! own random streams and never touch DI's buffers, so (pt on − pt off) is the indirect
//! estimate, compared with (max_bounces reference − 1-bounce reference).

use crate::common;

use common::indirect::mean_luma;
use glam::Vec3;
use restir_render::shader_constants::{INDIRECT_PASS_TEMPORAL, STAT_INDIRECT_NONFINITE};
use restir_render::{Camera, Mode, Renderer, Scene, load_scene};

const W: u32 = 64;
const H: u32 = 48;
const BOUNCES: &str = "max_bounces=3";
/// Neighbours 4–13 px away (the default 30 px at 1080p is 2 px here).
const WIDE: &str = "pt_spatial_radius=300";
const TEMPORAL_ONLY: &str = "pt_spatial=false";
const SHIFTS: [&str; 3] = [
    "pt_shift=reconnection",
    "pt_shift=random-replay",
    "pt_shift=hybrid",
];

fn render(scene: &Scene, assignments: &[&str], planted: Option<&str>, frames: u32) -> Renderer {
    let all = [&[BOUNCES][..], assignments].concat();
    common::indirect::render_planted(scene, (W, H), &all, planted, frames)
}

/// Seeds of the random streams each estimate is averaged over: one seed's 128 frames at
/// 64×48 scatter by ±1 % (on the glossy room a near-mirror's rare bright paths: measured
/// 0.987–1.019 over five seeds, temporal reuse on or off alike; 0.990–1.005 on the Cornell
/// box), three seeds put the mean's spread near 0.4 %.
static SEEDS: [u32; 3] = [1, 2, 3];

/// (pt on − pt off) / (3-bounce − 1-bounce reference) in mean luma on one scene, each side
/// with the same seed (PT draws its own streams, so DI's noise cancels exactly), averaged
/// over `seeds`.
struct Indirect {
    scene: Scene,
    reference: f64,
    seeds: &'static [u32],
    direct: Vec<f64>,
    frames: u32,
}

impl Indirect {
    fn new(name: &str, frames: u32, seeds: &'static [u32]) -> Indirect {
        let scene = load_scene(name).unwrap();
        let reference = |bounces: u32| {
            let settings = common::settings(&["jitter=false", &format!("max_bounces={bounces}")]);
            let mut r = common::renderer(name, W, H, Mode::Reference, settings);
            mean_luma(&common::reference(&mut r, 1, 2048))
        };
        let indirect = reference(3) - reference(1);
        let mut s = Indirect {
            scene,
            reference: indirect,
            seeds,
            direct: Vec::new(),
            frames,
        };
        s.direct = seeds
            .iter()
            .map(|&seed| s.mean(&["pt=false"], None, seed))
            .collect();
        s
    }

    /// The mean luma of `frames` frames with `seed`, checked for non-finite values.
    fn mean(&self, assignments: &[&str], planted: Option<&str>, seed: u32) -> f64 {
        let mut r = render(&self.scene, assignments, planted, 0);
        r.set_seed(seed);
        let image = common::accumulate(&mut r, self.frames);
        let guarded: u64 = r
            .collect_reports(true)
            .iter()
            .map(|f| f.counters.non_finite_total())
            .sum();
        assert_eq!(guarded, 0, "non-finite values caught in a PT frame");
        assert_eq!(image.non_finite_count(), 0);
        mean_luma(&image)
    }

    fn ratio(&self, assignments: &[&str], planted: Option<&str>) -> f64 {
        let mut all = vec!["pt=true"];
        all.extend_from_slice(assignments);
        let ratios: Vec<f64> = self
            .seeds
            .iter()
            .zip(&self.direct)
            .map(|(&seed, direct)| (self.mean(&all, planted, seed) - direct) / self.reference)
            .collect();
        let ratio = ratios.iter().sum::<f64>() / ratios.len() as f64;
        eprintln!(
            "indirect ratio {ratio:.4} (seeds {ratios:.4?}) with {assignments:?} {planted:?}"
        );
        ratio
    }
}

/// Inside the furnace box (every wall emits 1, albedo 0.5) paths of 2 and 3 bounces add
/// exactly a₁·a + a₁·a² to DI's 1 + a₁ (a₁ the G-buffer's 8-bit albedo), for every shift,
/// with and without spatial reuse. Tolerance 1.5 %: as GI's furnace (restir_gi.rs), the
/// mean of 64 frames of 16×16 pixels scatters by ~0.3 %.
#[test]
fn restir_pt_in_the_furnace_adds_exactly_its_bounces() {
    let scene = common::furnace::furnace_box(1.0, 0.5);
    let a1 = (0.5f64 * 255.0).round() / 255.0;
    let expected = 1.0 + a1 + a1 * 0.5 + a1 * 0.25;
    for assignments in [
        vec!["pt=true", "pt_spatial=false"],
        vec!["pt=true", SHIFTS[0]],
        vec!["pt=true", SHIFTS[1]],
        vec!["pt=true", SHIFTS[2]],
    ] {
        let all = [&["jitter=false", BOUNCES][..], &assignments].concat();
        let mut r = Renderer::new(common::gpu(), &scene, 16, 16, common::settings(&all)).unwrap();
        r.set_camera(Camera::look_at(
            Vec3::ZERO,
            Vec3::new(1.0, 0.3, 0.6),
            70f32.to_radians(),
        ));
        r.set_mode(Mode::Restir);
        let mean = mean_luma(&common::accumulate(&mut r, 64));
        eprintln!("furnace {assignments:?}: {mean:.4} (expected {expected:.4})");
        assert!(
            (mean / expected - 1.0).abs() < 0.015,
            "{assignments:?}: {mean:.4} vs {expected:.4}"
        );
    }
}

/// Each shift under pairwise MIS, temporal and spatial reuse together (the default),
/// converges to the 3-bounce reference's indirect light on the Cornell box and on the
/// glossy room (a rough-glossy floor and near-mirror panels, where the shifts differ;
/// neighbours up to 13 px away at 48 px high); on the glossy room temporal reuse alone too
/// (the history read through the 4×4 permutation, so the previous path comes from another
/// pixel and both shifts are real). Tolerance ±1.5 % on the mean of the seeds (see
/// `SEEDS`): the seeds' means scatter by ~0.4 % and the references' own noise (2048 spp)
/// by ~0.5 % (measured 0.9935–1.0008 over these twelve estimates).
///
/// Planted twins: a neighbour whose shift back fails left out of the canonical weight
/// while it still counts in M (the class of bug reported against RTXDI's PT in 2026)
/// darkens by 27 % with temporal and spatial reuse, by 12 % in temporal reuse alone; the
/// Jacobian the wrong way round brightens reconnection by 19 %; left out (|J| = 1) it darkens
/// hybrid by 3.9 % (reconnection 4.7 %; random replay only +1.1 %, inside the tolerance: its
/// Jacobian, a ratio of lobe densities, stays near 1 here, and pairwise weights built with
/// the same wrong |J| mask part of it, so that error is caught on the CPU, against finite
/// differences: render/src/pt/model/jacobian_tests.rs). The biased Jacobian clamp
/// (`pt_jacobian_clamp=1.5`) darkens reconnection by 3.3 %: the option is named biased
/// and this is its measure.
#[test]
fn every_pt_shift_converges_to_the_reference_and_planted_errors_do_not() {
    let within = |ratio: f64| (0.985..=1.015).contains(&ratio);
    let scenes =
        ["builtin:cornell", "builtin:glossy"].map(|name| (name, Indirect::new(name, 128, &SEEDS)));
    for (name, s) in &scenes {
        for shift in SHIFTS {
            let ratio = s.ratio(&[shift, WIDE], None);
            assert!(within(ratio), "{name} {shift}: {ratio:.4}");
        }
    }
    let s = &scenes[1].1;
    for shift in SHIFTS {
        let ratio = s.ratio(&[shift, TEMPORAL_ONLY], None);
        assert!(within(ratio), "glossy temporal only, {shift}: {ratio:.4}");
    }
    let dropped = s.ratio(&[SHIFTS[2], WIDE], Some("PLANTED_PT_FAILED_SHIFT_DROPPED"));
    assert!(
        !within(dropped),
        "a dropped failed shift must fail ({dropped:.4})"
    );
    let dropped = s.ratio(
        &[SHIFTS[2], TEMPORAL_ONLY],
        Some("PLANTED_PT_FAILED_SHIFT_DROPPED"),
    );
    assert!(
        !within(dropped),
        "a dropped failed temporal back-shift must fail ({dropped:.4})"
    );
    // The biased option, measured as biased: |J| clamped into [1/1.5, 1.5].
    let clamped = s.ratio(&[SHIFTS[0], WIDE, "pt_jacobian_clamp=1.5"], None);
    assert!(
        !within(clamped),
        "a clamped Jacobian is a wrong change of measure ({clamped:.4})"
    );
    let missing = s.ratio(&[SHIFTS[2], WIDE], Some("PLANTED_PT_NO_JACOBIAN"));
    assert!(
        !within(missing),
        "a missing Jacobian must fail ({missing:.4})"
    );
    let inverted = s.ratio(&[SHIFTS[0], WIDE], Some("PLANTED_PT_INVERTED_JACOBIAN"));
    assert!(
        !within(inverted),
        "an inverted Jacobian must fail ({inverted:.4})"
    );
}

/// PT is compiled and dispatched only when `pt` is on, replaces GI while on; its temporal
/// pass runs from the second frame (the first has no history) and follows `pt_temporal`,
/// its spatial pass follows `pt_spatial`.
#[test]
fn pt_passes_run_only_when_pt_is_on() {
    let scene = load_scene("builtin:cornell").unwrap();
    let indirect_passes = |r: &Renderer| -> Vec<&'static str> {
        r.last_passes()
            .iter()
            .copied()
            .filter(|p| p.starts_with("pt") || p.starts_with("gi"))
            .collect()
    };
    let off = render(&scene, &[], None, 1);
    assert!(off.last_passes().iter().all(|p| !p.starts_with("pt")));
    let first = render(&scene, &["pt=true", "gi=true"], None, 1);
    assert_eq!(
        indirect_passes(&first),
        ["pt initial", "pt spatial", "pt shade"]
    );
    let second = render(&scene, &["pt=true", "gi=true"], None, 2);
    assert_eq!(
        indirect_passes(&second),
        ["pt initial", "pt temporal", "pt spatial", "pt shade"]
    );
    let no_temporal = render(&scene, &["pt=true", "pt_temporal=false"], None, 2);
    assert!(!no_temporal.last_passes().contains(&"pt temporal"));
    let alone = render(&scene, &["pt=true", "pt_spatial=false"], None, 1);
    assert!(!alone.last_passes().contains(&"pt spatial"));
    // ris reuses nothing: PT's path is traced and shaded, never reused (its reuse switches
    // were forgotten before the settings table marked them).
    let mut ris = render(&scene, &["pt=true"], None, 0);
    ris.set_mode(Mode::Ris);
    for _ in 0..2 {
        ris.render_frame().unwrap();
    }
    assert_eq!(indirect_passes(&ris), ["pt initial", "pt shade"]);
    // `--stats` names the indirect block after the technique that ran.
    let mut pt = render(&scene, &["pt=true"], None, 0);
    let summary = common::stats_of(&mut pt, 2);
    assert!(summary.pt.is_some_and(|b| b.frames == 2) && summary.gi.is_none());
    assert!(summary.non_finite_by_pass.contains_key("pt temporal"));
    assert!(!summary.non_finite_by_pass.contains_key("gi temporal"));
}

/// Hard cases with PT on (3 bounces, every shift in turn across the scenes): paths that
/// meet a tiny bright emitter, vanishing distances between touching boxes, degenerate
/// triangles, a tiny scene (the Jacobian's 1/d²), a mirror and moving geometry, with an
/// orbiting camera so temporal reuse shifts paths between visible points. Every PT pass
/// guards against non-finite values and counts what it replaced: nothing may be counted,
/// and the image stays finite. (GI's test walks all eleven hard scenes; each scene here
/// compiles its own PT pipelines, half a minute on lavapipe, so six that stress paths.)
#[test]
fn pt_stays_finite_on_hard_scenes() {
    let scenes = [
        "builtin:hard:tiny-bright",
        "builtin:hard:touching",
        "builtin:hard:degenerate",
        "builtin:hard:scale-small",
        "builtin:hard:mirror",
        "builtin:dynamic:moving-occluder",
    ];
    for (i, name) in scenes.into_iter().enumerate() {
        let scene = load_scene(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let shift = SHIFTS[i % SHIFTS.len()];
        let settings = common::settings(&["pt=true", BOUNCES, shift]);
        let mut r = Renderer::new(common::gpu(), &scene, 32, 24, settings).unwrap();
        r.set_mode(Mode::Restir);
        let counted = common::indirect::orbit_counting_non_finite(&mut r, 6, name);
        assert!(r.last_passes().contains(&"pt temporal"), "{name}");
        assert_eq!(counted, 0, "{name} ({shift}): non-finite values replaced");
        assert_eq!(
            r.read_radiance().non_finite_count(),
            0,
            "{name}: non-finite pixels"
        );
        assert!(
            r.read_pt_reservoirs()
                .iter()
                .all(|p| p.weight.is_finite() && p.m.is_finite() && p.w_sum.is_finite()),
            "{name}: a PT reservoir with a non-finite weight"
        );
    }
}

/// The guard the test above relies on fires: a poisoned PT history (NaN and infinite
/// values, weights and geometry) is counted by PT temporal reuse and never reaches the
/// image.
#[test]
fn a_poisoned_pt_history_is_counted_and_dropped() {
    let scene = load_scene("builtin:cornell").unwrap();
    let mut r = render(&scene, &["pt=true"], None, 2);
    r.poison_pt_history_for_tests();
    let counted = common::indirect::count_in_next_frame(
        &mut r,
        STAT_INDIRECT_NONFINITE + INDIRECT_PASS_TEMPORAL,
    );
    assert!(
        counted as u32 >= W * H / 2,
        "PT temporal counted {counted} poisoned reservoirs of {}",
        W * H
    );
    assert_eq!(r.read_radiance().non_finite_count(), 0);
}
