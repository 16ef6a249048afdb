//! One pairwise-MIS reuse step over paths (GRIS, Lin et al. 2022, with the confidence
//! weights of `reservoir.rs`): the canonical pixel's reservoir and its neighbours', each
//! neighbour's path shifted here, and the canonical path shifted to each neighbour for its
//! MIS term. Every neighbour passed in takes part (the caller's G-buffer checks decided);
//! a shift that fails in either direction is a zero-target domain: its confidence stays in
//! `c_total` and its term stays in the canonical weight, with target 0.

use super::path::{PathSample, Pixel, evaluate};
use super::shift::{Shift, shift_path};
use super::toy_scene::ToyScene;
use crate::reservoir::{Reservoir, pairwise_mis_canonical_term, pairwise_mis_noncanonical};

/// Errors the tests plant, each the class of bug a reuse step can have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Planted {
    None,
    /// `|J| = 1` in every shift.
    NoJacobian,
    /// A neighbour whose shift of the canonical path fails is left out of the canonical
    /// MIS weight but still counted in `c_total` (reported against RTXDI's ReSTIR PT in
    /// 2026: neighbours without a reconnection vertex still add to M).
    FailedShiftCountedInM,
    /// A neighbour the canonical path cannot be shifted to is dropped altogether: out of
    /// `c_total` and the weights. Whether it takes part then depends on a sample, not on
    /// the G-buffer (DI's `SampleRule::Reject` in path form).
    FailedShiftDropped,
}

/// A pixel and its reservoir of paths (finalised: `weight` is W, `p_hat` the target there).
pub struct Candidate<'a> {
    pub pixel: &'a Pixel,
    pub reservoir: Reservoir<PathSample>,
}

/// The target of `path` at `pixel`: its contribution (a scalar here; luminance on the GPU).
pub fn target(scene: &ToyScene, pixel: &Pixel, path: &PathSample) -> f32 {
    evaluate(scene, pixel, path).contribution
}

/// A shifted path, its target where it was moved to, and `|J|`.
type Moved = (PathSample, f32, f32);

/// `path` (found at `from`) moved to `to`: the shifted path, its target at `to` and `|J|`;
/// `None` where the shift fails.
fn shifted(
    scene: &ToyScene,
    path: &PathSample,
    from: &Pixel,
    to: &Pixel,
    shift: Shift,
    planted: Planted,
) -> Option<Moved> {
    let s = shift_path(scene, path, from, to, shift).ok()?;
    let j = if planted == Planted::NoJacobian {
        1.0
    } else {
        s.jacobian
    };
    Some((s.path, target(scene, to, &s.path), j))
}

/// Resamples `canonical` with `neighbours` by defensive pairwise MIS; returns the
/// finalised reservoir with `m = c_total`. Confidences are the reservoirs' `m`.
pub fn pairwise_path_reuse(
    scene: &ToyScene,
    canonical: &Candidate,
    neighbours: &[Candidate],
    shift: Shift,
    planted: Planted,
    u: &mut dyn FnMut() -> f32,
) -> Reservoir<PathSample> {
    let here = canonical.pixel;
    let canonical_shifts: Vec<_> = neighbours
        .iter()
        .map(|n| {
            let y = canonical.reservoir.sample?;
            shifted(scene, &y, here, n.pixel, shift, planted)
        })
        .collect();
    // Each neighbour with the canonical path moved to it (for its MIS term).
    let neighbours: Vec<(&Candidate, Option<Moved>)> = neighbours
        .iter()
        .zip(canonical_shifts)
        .filter(|(_, s)| planted != Planted::FailedShiftDropped || s.is_some())
        .collect();
    let c_c = canonical.reservoir.m;
    let c_total = neighbours
        .iter()
        .fold(c_c, |acc, (n, _)| acc + n.reservoir.m);
    let mut r = Reservoir::empty();
    if let Some(y) = canonical.reservoir.sample {
        let p_c = canonical.reservoir.p_hat;
        let mut m_c = c_c / c_total;
        for (n, to_n) in &neighbours {
            match to_n {
                Some((_, t, j)) => {
                    m_c += pairwise_mis_canonical_term(c_total, c_c, n.reservoir.m, p_c, t * j)
                }
                None if planted == Planted::FailedShiftCountedInM => {}
                // A zero-target domain: the canonical path takes the neighbour's share.
                None => m_c += pairwise_mis_canonical_term(c_total, c_c, n.reservoir.m, p_c, 0.0),
            }
        }
        r.update(y, p_c * canonical.reservoir.weight * m_c, p_c, u());
    }
    for (n, _) in &neighbours {
        let Some(y) = n.reservoir.sample else {
            continue;
        };
        let Some((moved, t, j)) = shifted(scene, &y, n.pixel, here, shift, planted) else {
            continue;
        };
        let m = pairwise_mis_noncanonical(c_total, c_c, n.reservoir.m, n.reservoir.p_hat, t * j);
        r.update(moved, t * n.reservoir.weight * j * m, t, u());
    }
    r.finalize(1.0);
    r.m = c_total;
    r
}
