//! The split tree against brute force and against a single tree, its layout, and the
//! promise it exists for: moving triangles never touch the static part's nodes.

use glam::Vec3;

use super::*;
use crate::reservoir::test_support::Rng;
use crate::scene::bvh::BVH_MAX_DEPTH;
use crate::scene::bvh::tests::{brute_force, check_structure, random_ray, random_soup};

/// A soup with every third triangle marked moving.
fn soup(seed: u64, n: usize) -> (Vec<[Vec3; 3]>, Vec<bool>) {
    let mut rng = Rng::new(seed);
    let tris = random_soup(&mut rng, n);
    let moving = (0..n).map(|t| t % 3 == 1).collect();
    (tris, moving)
}

/// `tris` shifted where `moving`: a frame of the animation.
fn moved(tris: &[[Vec3; 3]], moving: &[bool], by: Vec3) -> Vec<[Vec3; 3]> {
    tris.iter()
        .zip(moving)
        .map(|(t, &m)| if m { t.map(|p| p + by) } else { *t })
        .collect()
}

/// Rays whose closest hit (t) or shadow answer differs from brute force over `tris`.
fn mismatches(bvh: &Bvh, tris: &[[Vec3; 3]], seed: u64, rays: usize) -> usize {
    let mut rng = Rng::new(seed);
    let ordered = bvh.in_leaf_order(tris);
    (0..rays)
        .filter(|_| {
            let ray = random_ray(&mut rng);
            let expected = brute_force(tris, &ray);
            let hit = bvh.closest_hit(&ordered, &ray).map(|h| h.t);
            hit != expected || bvh.any_hit(&ordered, &ray) != expected.is_some()
        })
        .count()
}

#[test]
fn a_split_tree_hits_what_brute_force_hits_and_keeps_its_parts_apart() {
    let (tris, moving) = soup(5, 1200);
    let (bvh, part) = Bvh::build_split(&tris, &moving);
    let part = part.expect("both kinds of triangle: a split");
    check_structure(&bvh, &tris);
    assert!(bvh.depth() <= BVH_MAX_DEPTH + 1);
    assert_eq!(mismatches(&bvh, &tris, 9, 3000), 0);
    // Static triangles fill the slots before `first_slot`, moving ones the rest.
    for (slot, &source) in bvh.triangle_order.iter().enumerate() {
        assert_eq!(
            moving[source as usize],
            slot >= part.first_slot,
            "slot {slot}"
        );
    }
    assert_eq!(part.first_slot, moving.iter().filter(|&&m| !m).count());
    // The root's children are the parts' roots.
    assert_eq!((bvh.nodes[0].count, bvh.nodes[0].first), (0, 1));
    // Planted: a moving part whose leaves keep their own slots (the graft's offset left
    // out) points at static triangles, and the rays see it.
    let mut planted = Bvh {
        nodes: bvh.nodes.clone(),
        triangle_order: bvh.triangle_order.clone(),
    };
    for i in std::iter::once(2).chain(part.first_node..planted.nodes.len()) {
        if planted.nodes[i].count > 0 {
            planted.nodes[i].first -= part.first_slot as u32;
        }
    }
    assert!(
        mismatches(&planted, &tris, 9, 3000) > 0,
        "the detector fires"
    );
}

#[test]
fn nothing_to_keep_apart_gives_the_single_tree() {
    let (tris, _) = soup(6, 50);
    for moving in [vec![false; 50], vec![true; 50], Vec::new()] {
        let (bvh, part) = Bvh::build_split(&tris, &moving);
        assert_eq!(part, None);
        assert_eq!(bvh.nodes, Bvh::build(&tris).nodes);
    }
}

/// Refitting a frame's motion rewrites the moving part and the root only, and a rebuild of
/// the moving part leaves every static node and slot as it was, with the hits still right.
#[test]
fn motion_refits_and_rebuilds_the_moving_part_only() {
    let (tris, moving) = soup(7, 900);
    let (mut bvh, part) = Bvh::build_split(&tris, &moving);
    let part = part.unwrap();
    let static_nodes = |b: &Bvh| {
        let mut n = vec![b.nodes[1]];
        n.extend_from_slice(&b.nodes[3..part.first_node]);
        n
    };
    let before = static_nodes(&bvh);
    let static_slots = bvh.triangle_order[..part.first_slot].to_vec();
    let now = moved(&tris, &moving, Vec3::new(0.4, -0.2, 0.3));

    let links = bvh.refit_links();
    let moved_slots: Vec<usize> = (part.first_slot..tris.len()).collect();
    let rewritten = bvh.refit_moved(&links, &moved_slots, |s| now[s as usize]);
    assert!(
        rewritten
            .iter()
            .all(|&i| i == 0 || i == 2 || i >= part.first_node),
        "a static node was rewritten"
    );
    assert_eq!(static_nodes(&bvh), before);
    assert_eq!(mismatches(&bvh, &now, 10, 2000), 0);

    let refitted = bvh.moving_sah_cost(part);
    bvh.rebuild_moving(part, &now);
    check_structure(&bvh, &now);
    assert_eq!(static_nodes(&bvh), before);
    assert_eq!(&bvh.triangle_order[..part.first_slot], &static_slots[..]);
    assert_eq!(mismatches(&bvh, &now, 11, 2000), 0);
    // The same triangles rebuilt where they are: the moving part is a fresh tree again.
    let (fresh, fresh_part) = Bvh::build_split(&now, &moving);
    assert_eq!(fresh_part, Some(part));
    assert_eq!(bvh.nodes, fresh.nodes);
    assert!(bvh.moving_sah_cost(part) <= refitted + 1e-9);
}

/// Scattering the moving triangles raises the moving part's cost, measured against the
/// static part's box (which does not grow with them), and the static part adds nothing.
#[test]
fn the_moving_cost_measures_the_moving_part() {
    let (tris, moving) = soup(8, 600);
    let (bvh, part) = Bvh::build_split(&tris, &moving);
    let part = part.unwrap();
    let own = bvh.moving_sah_cost(part);
    assert!(own > 0.0);
    let mut still = Bvh {
        nodes: bvh.nodes.clone(),
        triangle_order: Vec::new(),
    };
    // Planted: the static part's boxes doubled change nothing of the moving part's cost.
    for i in std::iter::once(1).chain(3..part.first_node) {
        still.nodes[i].max = still.nodes[i].max.map(|x| 2.0 * x + 1.0);
    }
    still.nodes[1] = bvh.nodes[1];
    assert_eq!(still.moving_sah_cost(part), own);
    let mut scattered = bvh;
    let mut rng = Rng::new(3);
    let now: Vec<[Vec3; 3]> = tris
        .iter()
        .zip(&moving)
        .map(|(t, &m)| {
            if m {
                let jump = Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0);
                t.map(|p| p + jump)
            } else {
                *t
            }
        })
        .collect();
    scattered.refit(&scattered.in_leaf_order(&now));
    assert!(scattered.moving_sah_cost(part) > 1.5 * own);
}
