//! The light BVH's PDF against its own sampling, on a small "city": lights scattered over
//! 500 m with random orientations and powers. Each check has a planted twin.

use glam::Vec3;

use super::*;
use crate::test_hash::hash;

fn unit(i: u32, stream: u32) -> Vec3 {
    let z = 2.0 * hash(i, stream) - 1.0;
    let phi = std::f32::consts::TAU * hash(i, stream + 1);
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `count` small triangles over a 500 m × 500 m street grid, 0–20 m high, facing anywhere.
fn city(count: u32) -> Vec<EmissiveTriangle> {
    (0..count)
        .map(|i| {
            let c = Vec3::new(500.0 * hash(i, 1), 20.0 * hash(i, 2), 500.0 * hash(i, 3));
            let n = unit(i, 4);
            let t = n.any_orthonormal_vector();
            let b = n.cross(t);
            EmissiveTriangle {
                p: [c, c + 0.5 * t, c + 0.5 * b],
                power: 0.1 + 10.0 * hash(i, 6),
                // Every fifth light emits from both faces.
                two_sided: i % 5 == 0,
            }
        })
        .collect()
}

fn shading_points(count: u32) -> Vec<(Vec3, Vec3)> {
    (0..count)
        .map(|i| {
            let p = Vec3::new(
                500.0 * hash(i, 11),
                1.0 + 10.0 * hash(i, 12),
                500.0 * hash(i, 13),
            );
            (p, unit(i, 14))
        })
        .collect()
}

/// Over all lights, the PDF sums to 1 at every shading point (the walk never dead-ends).
#[test]
fn the_pdf_sums_to_one_over_all_lights() {
    let lights = city(300);
    let bvh = LightBvh::build(&lights);
    for (p, n) in shading_points(40) {
        let sum: f64 = (0..lights.len())
            .map(|l| bvh.pdf(l, p, n, true) as f64)
            .sum();
        // f32 products along ~9 branches: 1e-4 is far above their rounding.
        assert!((sum - 1.0).abs() < 1e-4, "Σ pdf = {sum} at {p}");
    }
}

/// How far the sampler's frequencies are from `pdf` at one point: the largest
/// |frequency − pdf| in standard errors over the lights, from `draws` stratified numbers.
fn worst_z(bvh: &LightBvh, p: Vec3, n: Vec3, pdf_orientation: bool, draws: u32) -> f64 {
    let mut counts = vec![0u32; bvh.trails.len()];
    for k in 0..draws {
        let u = (k as f32 + hash(k, 99)) / draws as f32;
        if let Some(s) = bvh.sample(p, n, u, true) {
            counts[s.light] += 1;
            assert!((s.pdf - bvh.pdf(s.light, p, n, true)).abs() <= 1e-5 * s.pdf.max(1e-6));
        }
    }
    counts
        .iter()
        .enumerate()
        .map(|(l, &c)| {
            let q = bvh.pdf(l, p, n, pdf_orientation) as f64;
            let f = c as f64 / draws as f64;
            let se = (q.max(1.0 / draws as f64) * (1.0 - q) / draws as f64).sqrt();
            (f - q).abs() / se
        })
        .fold(0.0, f64::max)
}

/// The traversal draws each light as often as its PDF says (and the PDF it reports is the
/// one `pdf` computes). Planted: a PDF that leaves out the orientation terms the traversal
/// uses — the same check fires.
#[test]
fn the_traversal_draws_what_the_pdf_says_and_a_pdf_without_orientation_is_caught() {
    let lights = city(64);
    let bvh = LightBvh::build(&lights);
    let draws = 200_000;
    let (mut kept, mut planted) = (0.0f64, 0.0f64);
    for (p, n) in shading_points(6) {
        kept = kept.max(worst_z(&bvh, p, n, true, draws));
        planted = planted.max(worst_z(&bvh, p, n, false, draws));
    }
    // 64 lights × 6 points: the largest of ~400 |z| of a correct PDF stays under 5 (a 5σ
    // excursion has probability 6e-7 each); stratified numbers make it smaller still.
    assert!(
        kept < 5.0,
        "the sampler and its PDF disagree by {kept} standard errors"
    );
    assert!(
        planted > 20.0,
        "a PDF without orientation went unseen ({planted} σ)"
    );
}

/// After 10 % of the lights move, the refit keeps every light inside the box of its leaf
/// and of every node above it, and its normal inside their cones; the PDF still sums to 1.
/// Planted: bounds left as built miss the moved lights.
#[test]
fn the_refit_keeps_every_moving_light_inside_its_nodes() {
    let mut lights = city(200);
    let mut bvh = LightBvh::build(&lights);
    for (i, l) in lights.iter_mut().enumerate().step_by(10) {
        let shift = Vec3::new(
            30.0 * hash(i as u32, 21) - 15.0,
            0.0,
            30.0 * hash(i as u32, 22) - 15.0,
        );
        let spin = glam::Quat::from_axis_angle(unit(i as u32, 23), 1.0);
        let c = l.centroid();
        l.p = l.p.map(|v| c + shift + spin * (v - c));
    }
    let escaped = |bvh: &LightBvh| {
        let mut bad = 0;
        for (light, l) in lights.iter().enumerate() {
            let (trail, depth) = bvh.trails[light];
            let mut node = 0;
            for k in 0..=depth {
                let b = bvh.nodes[node].bounds();
                let inside =
                    l.p.iter()
                        .all(|v| v.cmpge(b.min - 1e-3).all() && v.cmple(b.max + 1e-3).all());
                if !inside || !b.normals.contains(l.normal()) {
                    bad += 1;
                }
                if let Node::Interior { children, .. } = &bvh.nodes[node] {
                    node = children[((trail >> k) & 1) as usize];
                }
            }
        }
        bad
    };
    assert!(
        escaped(&bvh) > 0,
        "the planted stale tree should miss the moved lights"
    );
    // Refitting only the moved lights' paths gives the tree a full refit gives; leaving one
    // moved light out of the list leaves it outside its nodes.
    let moved: Vec<usize> = (0..lights.len()).step_by(10).collect();
    let mut partial = bvh.clone();
    let mut forgetful = bvh.clone();
    let rewritten = partial.refit_changed(&lights, &moved);
    assert!(
        rewritten.len() < bvh.nodes.len(),
        "{} nodes",
        rewritten.len()
    );
    forgetful.refit_changed(&lights, &moved[1..]);
    assert!(
        escaped(&forgetful) > 0,
        "a light left out of the refit went unseen"
    );
    bvh.refit(&lights);
    assert_eq!(escaped(&bvh), 0);
    assert_eq!(escaped(&partial), 0);
    for (a, b) in partial.nodes.iter().zip(&bvh.nodes) {
        assert_eq!(a.bounds(), b.bounds());
    }
    for (p, n) in shading_points(10) {
        let sum: f64 = (0..lights.len())
            .map(|l| bvh.pdf(l, p, n, true) as f64)
            .sum();
        assert!((sum - 1.0).abs() < 1e-4, "Σ pdf = {sum}");
    }
}

/// The refit's node list with marks kept between calls (as the GPU refit keeps them
/// frame to frame) equals a fresh one every call, and leaves every mark cleared. Planted: a
/// mark left set from an earlier call stops the climb there, and the list is short.
#[test]
fn node_lists_with_kept_marks_equal_fresh_ones() {
    let bvh = LightBvh::build(&city(300));
    let (mut marks, mut nodes) = (Vec::new(), Vec::new());
    for step in [7, 3, 11, 1] {
        let changed: Vec<usize> = (step..300).step_by(step * 2).collect();
        bvh.nodes_above_into(&changed, &mut marks, &mut nodes);
        assert_eq!(nodes, bvh.nodes_above(&changed), "every {step}th light");
        assert!(marks.iter().all(|m| !m), "a mark survived the call");
    }
    let changed = [5, 6];
    let fresh = bvh.nodes_above(&changed);
    marks[0] = true; // planted: the root left marked
    bvh.nodes_above_into(&changed, &mut marks, &mut nodes);
    assert!(
        nodes.len() < fresh.len(),
        "a stale mark went unseen ({} nodes)",
        nodes.len()
    );
}

/// No lights, one light, lights with no power, coplanar lights, all lights in one point
/// (zero-area triangles): sampling stays finite and the PDF sums to 1 (0 without lights).
#[test]
fn degenerate_light_sets_stay_finite() {
    let flat = |i: u32| EmissiveTriangle {
        p: [
            Vec3::new(i as f32, 5.0, 0.0),
            Vec3::new(i as f32 + 0.5, 5.0, 0.0),
            Vec3::new(i as f32, 5.0, 0.5),
        ],
        power: 1.0,
        two_sided: false,
    };
    let point = EmissiveTriangle {
        p: [Vec3::splat(3.0); 3],
        power: 2.0,
        two_sided: false,
    };
    let sets: Vec<Vec<EmissiveTriangle>> = vec![
        Vec::new(),
        vec![flat(0)],
        vec![
            EmissiveTriangle {
                power: 0.0,
                ..flat(0)
            },
            flat(1),
        ],
        (0..50).map(flat).collect(),
        vec![point; 20],
    ];
    for lights in sets {
        let bvh = LightBvh::build(&lights);
        for (p, n) in shading_points(8)
            .into_iter()
            .chain([(Vec3::splat(3.0), Vec3::Y)])
        {
            let sum: f64 = (0..lights.len())
                .map(|l| bvh.pdf(l, p, n, true) as f64)
                .sum();
            let expected = if lights.is_empty() { 0.0 } else { 1.0 };
            assert!((sum - expected).abs() < 1e-4, "Σ pdf = {sum}");
            match bvh.sample(p, n, 0.37, true) {
                Some(s) => assert!(s.pdf.is_finite() && s.pdf > 0.0, "{s:?}"),
                None => assert!(lights.is_empty()),
            }
        }
    }
}
