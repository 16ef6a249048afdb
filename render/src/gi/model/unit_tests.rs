//! GI reuse's bookkeeping on hand-made reservoirs: which rejection is reported, which
//! confidence counts, and that nothing fed to it comes out NaN or infinite.

use glam::Vec3;
use proptest::prelude::*;

use super::toy_scene::*;
use super::*;
use crate::reservoir::test_support::{wild_f32, wild_vec3};

fn sample_at(z: f32) -> GiSample {
    GiSample {
        position: Vec3::new(0.0, 0.0, z),
        normal: Vec3::NEG_Z,
        radiance: Vec3::ONE,
        source_pdf: 1.0,
        age: 3,
    }
}

fn finalised(sample: GiSample, r: &GiReceiver) -> GiReservoir {
    let mut res = GiReservoir::empty();
    let p = r.target(&sample);
    res.update(sample, p, p, 0.5);
    res.finalize_initial();
    res
}

#[test]
fn rejected_samples_count_their_confidence_but_never_contribute() {
    let here = receiver([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.8);
    let near = receiver([0.0, 0.0, 0.9], [0.0, 0.0, 1.0], 0.8);
    let canonical = finalised(sample_at(1.0), &here);
    // Seen from 0.1 away, reused from 1 away: J = 0.01, outside the window of 10.
    let far_sample = finalised(sample_at(1.0), &near);
    // Below the sample's surface as seen from here: the reconnection is undefined.
    let below = receiver([0.0, 0.0, -2.0], [0.0, 0.0, 1.0], 0.8);
    let behind = finalised(sample_at(-1.0), &below);
    let neighbours = [
        GiNeighbour {
            receiver: near,
            reservoir: &far_sample,
            confidence: 3.0,
        },
        GiNeighbour {
            receiver: below,
            reservoir: &behind,
            confidence: 2.0,
        },
        GiNeighbour {
            receiver: here,
            reservoir: &canonical,
            confidence: 4.0,
        },
    ];
    for pairwise in [false, true] {
        let mut occluded = |_: Vec3, _: Vec3| false;
        let mut u = || 0.99;
        let reuse = GiReuse {
            pairwise,
            ..REUSE_PAIRWISE
        };
        let out = gi_resample(
            &here,
            &canonical,
            1.0,
            &neighbours,
            reuse,
            &mut occluded,
            &mut u,
            reconnection_jacobian,
        );
        assert_eq!(
            out.rejections,
            vec![
                GI_REJECT_JACOBIAN,
                GI_REJECT_RECONNECTION,
                GI_REJECT_OCCLUDED
            ]
        );
        // All three seen, none usable: M = 1 + 3 + 2 + 4, and only the canonical survives.
        // 1/M: its W is diluted by the confidence the rejections count (1/10). Pairwise: no
        // neighbour sees y_c either (everything is occluded, MIS visibility on), so the
        // canonical's MIS weight is 1 and W is the canonical's own.
        assert_eq!(out.reservoir.m, 10.0);
        assert_eq!(out.reservoir.sample, canonical.sample);
        let expected = if pairwise {
            canonical.weight
        } else {
            canonical.weight / 10.0
        };
        assert!((out.reservoir.weight / expected - 1.0).abs() < 1e-6);
    }
}

proptest! {
    #[test]
    fn reuse_stays_finite_whatever_it_is_fed(
        samples in prop::collection::vec((wild_vec3(), wild_vec3(), wild_vec3(), wild_f32(), wild_f32(), wild_f32()), 1..5),
        here_position in wild_vec3(), j_max in wild_f32(), pairwise in any::<bool>(),
    ) {
        let here = GiReceiver { position: here_position, normal: Vec3::Z, brdf: Vec3::splat(0.25) };
        let reservoirs: Vec<(GiReceiver, GiReservoir)> = samples
            .iter()
            .map(|&(position, normal, radiance, w, p, m)| {
                let s = GiSample { position, normal, radiance, source_pdf: 1.0, age: 0 };
                let mut r = GiReservoir::empty();
                r.update(s, w, p, 0.5);
                r.finalize(1.0);
                r.m = m;
                (GiReceiver { position: position * 0.5, normal: Vec3::Z, brdf: Vec3::splat(0.2) }, r)
            })
            .collect();
        let neighbours: Vec<GiNeighbour> = reservoirs
            .iter()
            .map(|(receiver, reservoir)| GiNeighbour { receiver: *receiver, reservoir, confidence: reservoir.m })
            .collect();
        let reuse = GiReuse { pairwise, jacobian_max: j_max, visibility: false, mis_visibility: pairwise };
        let mut u = || 0.3;
        let out = gi_resample(&here, &reservoirs[0].1, reservoirs[0].1.m, &neighbours, reuse, &mut unoccluded, &mut u, reconnection_jacobian);
        let r = out.reservoir;
        for v in [r.w_sum, r.weight, r.m, r.p_hat] {
            prop_assert!(v.is_finite() && v >= 0.0, "{:?}", r);
        }
        prop_assert_eq!(r.sample.is_some(), r.weight > 0.0);
    }
}
