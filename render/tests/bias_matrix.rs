//! The bias matrix's fast slice (docs/src/measured/unbiased-reuse.md, "The bias matrix"): six cells
//! at a small size, each a signed bias with its 95 % interval over seeds and the matrix's verdict,
//! computed with the same code the `bias-matrix` command uses (`metrics::seeds`,
//! `metrics::pixel_moments`). Unbiased estimators must land on "consistent with 0" (or at least an
//! interval that contains 0, where it is too wide to decide); each planted error — a dropped 1/M, a
//! missing Jacobian, a wrong PDF — must land on "biased". Every cell also checks its own power: an
//! interval so wide that the planted errors would fit in it proves nothing.
//!
//! Sizes are tiny (lavapipe on two cores); every tolerance says where it comes from.

use crate::common;

use std::collections::BTreeSet;

use restir_render::effects::{EffectSet, SceneFeatures};
use restir_render::metrics::pixel_moments::PixelMoments;
use restir_render::metrics::seeds::{Interval, Verdict};
use restir_render::{LinearImage, Mode, Renderer, Scene, load_scene};

/// One cell: `scene` at `size`, ReSTIR (or `mode`) with `assignments` and `planted`
/// compiled in, `seeds` seeds of `frames` frames each against a 2048-spp reference of the
/// same max_bounces. Returns the signed bias's interval and its verdict.
#[derive(Clone, Copy)]
struct Cell<'a> {
    scene: &'a str,
    size: (u32, u32),
    mode: Mode,
    assignments: &'a [&'a str],
    seeds: u32,
    frames: u32,
}

impl Cell<'_> {
    /// The signed bias of the cell's mean luminance against `reference`, over the seeds.
    fn run(&self, reference: &LinearImage, planted: Option<&str>) -> Interval {
        let truth = reference.mean_luminance();
        let ratios: Vec<f64> = self.means(planted).iter().map(|m| m / truth).collect();
        self.report(Interval::of(&ratios).shifted(1.0), planted)
    }

    /// Per seed, the mean luminance of the accumulated image (a clean history each).
    fn means(&self, planted: Option<&str>) -> Vec<f64> {
        let scene = load_scene(self.scene).unwrap();
        let mut r = self.renderer(&scene, planted);
        (0..self.seeds)
            .map(|seed| {
                r.set_seed(seed);
                r.request_cut();
                let mut moments = PixelMoments::new(self.size.0, self.size.1);
                for _ in 0..self.frames {
                    r.render_frame().unwrap_or_else(|e| panic!("{e}"));
                    moments.push(&r.read_radiance());
                }
                assert_eq!(moments.non_finite, 0, "{}: non-finite pixels", self.scene);
                moments.mean().iter().sum::<f64>() / moments.mean().len() as f64
            })
            .collect()
    }

    fn report(&self, signed: Interval, planted: Option<&str>) -> Interval {
        eprintln!(
            "{} {:?} {:?} {planted:?}: signed bias {:+.2} % ± {:.2} % → {:?}",
            self.scene,
            self.mode,
            self.assignments,
            100.0 * signed.mean,
            100.0 * signed.half_width,
            Verdict::of(&signed)
        );
        signed
    }

    fn renderer(&self, scene: &Scene, planted: Option<&str>) -> Renderer {
        let mut all = vec!["jitter=false"];
        all.extend_from_slice(self.assignments);
        let settings = common::settings(&all);
        let mut effects = EffectSet::detect(&SceneFeatures::of(scene), &settings, false);
        effects.planted = planted
            .map(str::to_string)
            .into_iter()
            .collect::<BTreeSet<_>>();
        let mut r = Renderer::new(common::gpu(), scene, self.size.0, self.size.1, settings)
            .unwrap_or_else(|e| panic!("{e:#}"));
        r.force_effects(Some(effects));
        r.set_mode(self.mode);
        r
    }

    /// The reference at the cell's max_bounces (2048 spp: its mean luminance carries
    /// ~0.1 % of noise at these sizes, a fifth of the matrix's ±0.5 %).
    fn reference(&self) -> LinearImage {
        let mut r = self.renderer(&load_scene(self.scene).unwrap(), None);
        common::reference(&mut r, 1, 2048)
    }
}

/// An unbiased cell: its interval contains 0, or lies within ±0.5 % (a small certain bias
/// below the matrix's resolution), and is narrow enough to have caught the planted errors
/// (each ≥ 5 %, measured below): `power` is the largest half-width allowed.
fn assert_unbiased(signed: &Interval, power: f64, what: &str) {
    let verdict = Verdict::of(signed);
    assert!(
        signed.contains(0.0) || verdict == Verdict::Unbiased,
        "{what}: {:+.2} % ± {:.2} % ({verdict:?})",
        100.0 * signed.mean,
        100.0 * signed.half_width
    );
    assert!(
        signed.half_width < power,
        "{what}: ± {:.2} % is too wide to catch anything",
        100.0 * signed.half_width
    );
}

fn assert_caught(signed: &Interval, what: &str) {
    assert_eq!(
        Verdict::of(signed),
        Verdict::Biased,
        "{what} went unseen: {:+.2} % ± {:.2} %",
        100.0 * signed.mean,
        100.0 * signed.half_width
    );
}

const SMALL: (u32, u32) = (48, 36);

const DEFAULT_RESTIR: Cell = Cell {
    scene: "builtin:cornell",
    size: SMALL,
    mode: Mode::Restir,
    assignments: &[],
    seeds: 4,
    frames: 48,
};

#[test]
fn the_default_restir_is_unbiased_and_a_dropped_one_over_m_is_caught() {
    let cell = DEFAULT_RESTIR;
    let reference = cell.reference();
    // Measured −0.01 % ± 0.15 %. ±1 % of power: the twin is far further out.
    assert_unbiased(&cell.run(&reference, None), 0.01, "cornell restir");
    // The twin on spatial reuse alone: with temporal reuse the weights' excess would feed
    // back through the history every frame and grow without bound.
    let spatial = Cell {
        assignments: &["temporal=false"],
        ..DEFAULT_RESTIR
    };
    assert_caught(
        &spatial.run(&reference, Some("PLANTED_DROPPED_ONE_OVER_M")),
        "a dropped 1/M (the neighbour's confidence share)",
    );
}

#[test]
fn ris_and_gi_are_unbiased() {
    let ris = Cell {
        mode: Mode::Ris,
        ..DEFAULT_RESTIR
    };
    // Measured −0.01 % ± 0.02 % and −0.01 % ± 0.12 %.
    assert_unbiased(&ris.run(&ris.reference(), None), 0.01, "cornell ris");
    let gi = Cell {
        assignments: &["gi=true", "max_bounces=2"],
        ..DEFAULT_RESTIR
    };
    assert_unbiased(&gi.run(&gi.reference(), None), 0.01, "cornell restir+gi");
}

/// The signed bias of the *indirect* light alone: per seed, (mean with `indirect` on − the
/// same seed with it off) / (the cell's reference − the 1-bounce reference). PT draws its
/// own random streams, so the direct light of both runs is the same frame exactly and its
/// noise cancels (render/tests/restir_pt.rs measures the same way): a bias of a few % in
/// the indirect part is then resolved where the whole image's noise would hide it.
/// The run with it off and both references are made once and serve every `planted` twin.
struct IndirectBias<'a> {
    cell: Cell<'a>,
    indirect_reference: f64,
    off_means: Vec<f64>,
}

impl<'a> IndirectBias<'a> {
    fn new(cell: Cell<'a>, off: &Cell) -> Self {
        let direct = Cell {
            assignments: &["max_bounces=1"],
            ..*off
        };
        let direct_reference = direct.reference().mean_luminance();
        IndirectBias {
            cell,
            indirect_reference: cell.reference().mean_luminance() - direct_reference,
            off_means: off.means(None),
        }
    }

    fn of(&self, planted: Option<&str>) -> Interval {
        let on = self.cell.means(planted);
        let ratios: Vec<f64> = (on.iter().zip(&self.off_means))
            .map(|(a, b)| (a - b) / self.indirect_reference)
            .collect();
        self.cell
            .report(Interval::of(&ratios).shifted(1.0), planted)
    }
}

#[test]
fn pt_is_unbiased_and_a_missing_jacobian_is_caught() {
    // The reconnection shift on the glossy room, neighbours up to 13 px away at 36 px high:
    // where reconnecting paths change their density most. Left out (|J| = 1), the Jacobian
    // darkens the indirect light by ~5 % (restir_pt.rs: 4.7 % at 64×48).
    const PT: [&str; 4] = [
        "pt=true",
        "pt_shift=reconnection",
        "max_bounces=3",
        "pt_spatial_radius=300",
    ];
    let pt = Cell {
        scene: "builtin:glossy",
        assignments: &PT,
        seeds: 8,
        frames: 96,
        ..DEFAULT_RESTIR
    };
    let off = Cell {
        assignments: &[PT[0], PT[1], PT[2], PT[3], "pt=false"],
        ..pt
    };
    let indirect = IndirectBias::new(pt, &off);
    // ±2 % of power: half the planted error.
    assert_unbiased(&indirect.of(None), 0.02, "glossy restir+pt, indirect");
    assert_caught(
        &indirect.of(Some("PLANTED_PT_NO_JACOBIAN")),
        "a missing PT Jacobian",
    );
}

#[test]
fn the_light_bvh_is_unbiased_and_a_wrong_pdf_is_caught() {
    let bvh = Cell {
        scene: "builtin:many-lights:256",
        assignments: &["light_sampler=bvh"],
        ..DEFAULT_RESTIR
    };
    let reference = bvh.reference();
    // Measured −0.33 % ± 0.45 %; the twin +7.5 % ± 1.0 %.
    assert_unbiased(&bvh.run(&reference, None), 0.02, "many-lights restir@bvh");
    assert_caught(
        &bvh.run(&reference, Some("PLANTED_BVH_PDF_WITHOUT_ORIENTATION")),
        "the BVH's PDF without its orientation bound",
    );
}

#[test]
fn restir_di_on_the_glossy_room_is_unbiased_over_seeds() {
    // The room whose one-seed figure once read "3 % dark" (docs/src/measured/unbiased-reuse.md,
    // "Why the glossy room converges slowly"): over 8 seeds its mean is the reference's. Its
    // accumulated image spreads far wider than RIS's, so this interval is the widest of the slice
    // (measured +0.54 % ± 1.51 %); ±2.5 % of power still tells a −3 % bias, the size the one-seed
    // figure suggested, from none.
    let glossy = Cell {
        scene: "builtin:glossy",
        seeds: 8,
        frames: 64,
        ..DEFAULT_RESTIR
    };
    assert_unbiased(
        &glossy.run(&glossy.reference(), None),
        0.025,
        "glossy restir",
    );
}
