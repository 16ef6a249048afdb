//! Each shift's Jacobian against the finite-difference determinant of the shift itself:
//! the path at pixel q is moved by small steps of each of its directions (tangent-plane
//! coordinates, whose area element is 1 at the base point), re-traced, shifted to pixel r,
//! and the shifted directions' coordinates differentiated by central differences. The
//! determinant of that 2n×2n matrix is |dω'/dω| of the whole path.

use glam::Vec3;

use super::fixtures::{find_path, pixel, scene_for_fd};
use super::path::{PathSample, Pixel, lobe_at, w_in};
use super::shift::{Shift, shift_path};
use super::toy_scene::{BACK_WALL, EMITTER, FLOOR, MIRROR, ToyScene};

/// A path with its directions replaced: re-traced from `pixel` along `directions`, with
/// the numbers that draw them; `None` if it no longer hits the same surfaces.
fn retrace(
    scene: &ToyScene,
    pixel: &Pixel,
    base: &PathSample,
    directions: &[Vec3],
) -> Option<PathSample> {
    let mut p = *base;
    p.vertices[0] = pixel.primary;
    for (b, d) in directions.iter().enumerate() {
        let at = p.vertices[b];
        let lobe = lobe_at(scene, &at)?;
        p.numbers[b] = lobe.numbers_of(at.normal, w_in(pixel, &p, b), *d);
        let hit = scene.intersect(at.position, *d, f32::MAX)?;
        if hit.quad != base.vertices[b + 1].quad {
            return None;
        }
        p.vertices[b + 1] = hit;
    }
    Some(p)
}

fn directions(p: &PathSample) -> Vec<Vec3> {
    (0..p.bounces)
        .map(|b| (p.vertices[b + 1].position - p.vertices[b].position).normalize())
        .collect()
}

fn tangent(d: Vec3) -> (Vec3, Vec3) {
    d.any_orthonormal_pair()
}

/// Gnomonic coordinates of `e` about `d`.
fn coords(d: Vec3, e: Vec3) -> [f64; 2] {
    let (t, b) = tangent(d);
    let z = e.dot(d) as f64;
    [e.dot(t) as f64 / z, e.dot(b) as f64 / z]
}

#[allow(clippy::needless_range_loop)] // Gaussian elimination reads best with indices.
fn determinant(mut m: Vec<Vec<f64>>) -> f64 {
    let n = m.len();
    let mut det = 1.0;
    for c in 0..n {
        let p = (c..n)
            .max_by(|&a, &b| m[a][c].abs().total_cmp(&m[b][c].abs()))
            .unwrap();
        if p != c {
            m.swap(p, c);
            det = -det;
        }
        det *= m[c][c];
        for r in c + 1..n {
            let f = m[r][c] / m[c][c];
            for k in c..n {
                m[r][k] -= f * m[c][k];
            }
        }
    }
    det
}

/// |det ∂(shifted directions)/∂(directions)| by central differences of step `h` radians.
#[allow(clippy::needless_range_loop)] // a matrix filled column by column
fn finite_difference_jacobian(
    scene: &ToyScene,
    q: &Pixel,
    r: &Pixel,
    path: &PathSample,
    shift: Shift,
) -> f64 {
    let base_dirs = directions(path);
    let base_shifted = directions(&shift_path(scene, path, q, r, shift).unwrap().path);
    let n = path.bounces;
    let h = 1e-3f32;
    let mut m = vec![vec![0.0; 2 * n]; 2 * n];
    for col in 0..2 * n {
        let (b, axis) = (col / 2, col % 2);
        let mut side = [[0.0f64; 6]; 2];
        for (s, sign) in [1.0f32, -1.0].into_iter().enumerate() {
            let mut dirs = base_dirs.clone();
            let (t, bt) = tangent(dirs[b]);
            let step = if axis == 0 { t } else { bt };
            dirs[b] = (dirs[b] + step * (sign * h)).normalize();
            let moved = retrace(scene, q, path, &dirs).expect("a small step keeps the surfaces");
            let out = shift_path(scene, &moved, q, r, shift).expect("a small step keeps the shift");
            for (i, e) in directions(&out.path).into_iter().enumerate() {
                let c = coords(base_shifted[i], e);
                side[s][2 * i] = c[0];
                side[s][2 * i + 1] = c[1];
            }
        }
        for row in 0..2 * n {
            m[row][col] = (side[0][row] - side[1][row]) / (2.0 * h as f64);
        }
    }
    determinant(m).abs()
}

fn check(quads: &[usize], shift: Shift) -> (f64, f64) {
    let scene = scene_for_fd();
    let (q, r) = (pixel([0.2, -0.6]), pixel([0.42, -0.45]));
    let path = find_path(&scene, &q, quads, |p| {
        shift_path(&scene, p, &q, &r, shift).is_ok()
    });
    let analytic = shift_path(&scene, &path, &q, &r, shift).unwrap().jacobian as f64;
    let numeric = finite_difference_jacobian(&scene, &q, &r, &path, shift);
    // Central differences of f32 geometry at h = 1e-3: ~1e-4 per entry; 1 % on the
    // determinant of up to 6×6 leaves room.
    assert!(
        (analytic / numeric - 1.0).abs() < 1e-2,
        "{shift:?} along {quads:?}: analytic {analytic}, finite differences {numeric}"
    );
    (analytic, numeric)
}

const HYBRID: Shift = Shift::Hybrid {
    rough_threshold: 0.2,
    min_distance: 0.1,
};

#[test]
fn reconnection_jacobian_matches_finite_differences() {
    check(&[FLOOR, BACK_WALL, EMITTER], Shift::Reconnection);
    check(&[FLOOR, MIRROR, EMITTER], Shift::Reconnection);
}

/// The floor's roughness varies, so the replayed first bounce meets another lobe and the
/// Jacobian is not 1 (with equal lobes it is exactly 1: same numbers, same density): a
/// shift that left it out would fail here.
#[test]
fn random_replay_jacobian_matches_finite_differences() {
    for quads in [[FLOOR, BACK_WALL, EMITTER], [FLOOR, MIRROR, EMITTER]] {
        let (analytic, _) = check(&quads, Shift::RandomReplay);
        assert!(
            (analytic - 1.0).abs() > 0.05,
            "{quads:?}: |J| = {analytic}, too close to 1"
        );
    }
}

/// Through the glossy mirror the hybrid shift replays two bounces and reconnects the
/// third (back wall → emitter): the Jacobian is the replayed densities' ratio times the
/// reconnection's geometric ratio. Planted: either factor alone is off by more than the
/// tolerance, so the check would see a shift that forgot one.
#[test]
fn hybrid_jacobian_matches_finite_differences_and_needs_both_factors() {
    let scene = scene_for_fd();
    let (q, r) = (pixel([0.2, -0.6]), pixel([0.42, -0.45]));
    let quads = [FLOOR, MIRROR, BACK_WALL, EMITTER];
    let path = find_path(&scene, &q, &quads, |p| {
        super::shift::reconnection_bounce(&scene, p, HYBRID) == Some(2)
            && shift_path(&scene, p, &q, &r, HYBRID).is_ok()
    });
    let (analytic, numeric) = check(&quads, HYBRID);
    let next = path.vertices[3];
    let geometric = crate::gi::model::jacobian::reconnection_jacobian(
        next.position,
        next.normal,
        path.vertices[2].position,
        shift_path(&scene, &path, &q, &r, HYBRID)
            .unwrap()
            .path
            .vertices[2]
            .position,
    )
    .unwrap() as f64;
    let densities = analytic / geometric;
    for (name, partial) in [("densities only", densities), ("geometry only", geometric)] {
        assert!(
            (partial / numeric - 1.0).abs() > 0.05,
            "{name} ({partial}) is within 5 % of {numeric}: the check has no power here"
        );
    }
}
