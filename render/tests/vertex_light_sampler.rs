//! The light BVH at every light-sampling site past DI's candidates (docs/src/light-samplers.md,
//! "At every vertex"): the reference with the tree agrees with the reference with the
//! power table, and GI's and PT's path vertices with the tree agree with the same
//! estimators with the table there. Planted: a vertex that divides by the power table's
//! PDF after the tree drew (PLANTED_VERTEX_TABLE_PDF) is caught in each.
//!
//! Two references that agree are the independent check the issue asks for: the table's
//! shares no code path with the tree's walk or PDF, so a tree PDF wrong in the same way
//! at DI's candidates and at the vertices would still show against it.
//!
//! Sizes are tiny (lavapipe on two cores); every tolerance says where it comes from.

use crate::common;

use common::blocks::{block_means, worst_block};
use common::indirect::mean_luma;
use common::scene_parts::every_kind_of_light;
use restir_render::effects::Effect;
use restir_render::{Mode, Renderer, Scene, load_scene};

const PLANTED: &str = "PLANTED_VERTEX_TABLE_PDF";
/// The reference (jitter off, `bounces` vertices, `spp` samples per pixel in 4 frames),
/// its lights sampled with the tree or the table at every vertex, with `planted` compiled in.
fn reference_blocks(
    scene: &Scene,
    size: (u32, u32),
    bounces: u32,
    spp: u32,
    tree: bool,
    planted: &[&str],
) -> Vec<f64> {
    let settings = common::settings(&[
        "jitter=false",
        &format!("max_bounces={bounces}"),
        &format!("reference_light_bvh={tree}"),
        &format!("reference_spp={}", spp / 4),
    ]);
    let mut r = Renderer::new(common::gpu(), scene, size.0, size.1, settings)
        .unwrap_or_else(|e| panic!("{e:#}"));
    r.plant_for_tests(planted);
    r.set_mode(Mode::Reference);
    let img = common::accumulate(&mut r, 4);
    let effects = r.last_effects().expect("a rendered frame");
    assert_eq!(
        effects.contains(Effect::VertexLightBvh),
        tree,
        "the reference's vertex sampler"
    );
    assert_eq!(
        effects.contains(Effect::LightBvh),
        tree,
        "the reference builds the tree only when asked"
    );
    assert_eq!(img.non_finite_count(), 0);
    block_means(&img)
}

/// On the city (4096 lights along streets: the tree and the table draw very different
/// lights) and in a room with every kind of light (area lights one- and two-sided, a point
/// light, a spot, the sun and the sky; the tree holds the first four kinds), two bounces:
/// the tree's reference at 256 spp agrees with the table's at 1024 block by block, and the
/// planted PDF does not.
///
/// Tolerances per scene, from what was measured (blocks of 256 pixels): the city's
/// tree-vs-table worst block 2.9 %, where the table's own reference at 256 spp differs from
/// its 1024 by 5.5 % (the tree's reference is the closer one), planted 2000 %: below 8 %
/// passes, above 100 % is caught. The room: 0.6 % (the table's 256 spp: 0.8 %), planted
/// 6.5 %: below 2 % passes, above 4 % is caught.
#[test]
fn the_reference_with_the_tree_agrees_with_the_reference_with_the_table() {
    let city = load_scene("builtin:city:4096").unwrap();
    let room = every_kind_of_light();
    for (name, scene, unbiased_below, planted_above) in [
        ("city:4096", &city, 0.08, 1.0),
        ("every kind of light", &room, 0.02, 0.04),
    ] {
        let table = reference_blocks(scene, SIZE, 2, 1024, false, &[]);
        let tree = reference_blocks(scene, SIZE, 2, 256, true, &[]);
        let planted = reference_blocks(scene, SIZE, 2, 256, true, &[PLANTED]);
        let table_256 = reference_blocks(scene, SIZE, 2, 256, false, &[]);
        let (unbiased, wrong) = (worst_block(&tree, &table), worst_block(&planted, &table));
        eprintln!(
            "{name}: tree vs table worst block {:.2} % (the table's 256 spp: {:.2} %), planted {:.2} %",
            100.0 * unbiased,
            100.0 * worst_block(&table_256, &table),
            100.0 * wrong
        );
        assert!(
            unbiased < unbiased_below,
            "{name}: the tree's reference is {:.1} % off the table's",
            100.0 * unbiased
        );
        assert!(
            wrong > planted_above,
            "{name}: {PLANTED} went unseen ({:.1} %)",
            100.0 * wrong
        );
    }
}

/// Mean luma of `frames` ReSTIR frames of the city with `assignments` and `planted`, per
/// seed.
fn restir_means(scene: &Scene, assignments: &[&str], planted: &[&str], frames: u32) -> Vec<f64> {
    let mut all = vec!["jitter=false", "light_sampler=bvh"];
    all.extend_from_slice(assignments);
    let mut r = Renderer::new(common::gpu(), scene, SIZE.0, SIZE.1, common::settings(&all))
        .unwrap_or_else(|e| panic!("{e:#}"));
    r.plant_for_tests(planted);
    r.set_mode(Mode::Restir);
    let means = SEEDS
        .iter()
        .map(|&seed| {
            r.set_seed(seed);
            let img = common::accumulate(&mut r, frames);
            assert_eq!(img.non_finite_count(), 0, "{assignments:?}");
            mean_luma(&img)
        })
        .collect();
    let at_vertices = r
        .last_effects()
        .expect("a rendered frame")
        .contains(Effect::VertexLightBvh);
    let asked = !assignments.contains(&"bvh_at_vertices=false");
    assert_eq!(
        at_vertices, asked,
        "{assignments:?}: the vertex sampler compiled"
    );
    means
}

const SIZE: (u32, u32) = (48, 32);
const SEEDS: [u32; 2] = [1, 2];

/// GI's secondary vertex and PT's vertices (two bounces; the hybrid shift, and random
/// replay alone, which keeps the light point and takes the ratio of its densities at the
/// two vertices) on the city: their indirect light (the image with GI or PT less the same
/// seeds without it: DI draws its own random streams, so it cancels exactly) over the
/// reference's (the tree's references of two bounces less one, which the test above holds
/// to the table's), with the tree at the vertices and with the table there.
///
/// Measured (two seeds × 32 frames at 48×32): GI 1.002 with the tree (seeds 1.003, 1.001),
/// 1.022 with the table (1.048, 0.997); PT hybrid 1.002 and 1.006; PT replay 1.001 and
/// 1.031. Planted PDF: GI 52×, PT 17×. Tolerance ±5 %: the table's seeds scatter by up to
/// ±3 %. Replay keeping z without the ratio of its densities read 0.996 here and 1.001 on
/// the lit Cornell box: pairwise MIS built with the same wrong Jacobian masks it (as for
/// the replay Jacobian itself, restir_pt.rs), so no planted twin of it could fire.
#[test]
fn gi_and_pt_vertices_with_the_tree_or_the_table_converge_to_the_reference() {
    let scene = load_scene("builtin:city:4096").unwrap();
    let reference = |bounces: u32| {
        let blocks = reference_blocks(&scene, SIZE, bounces, 512, true, &[]);
        blocks.iter().sum::<f64>() / blocks.len() as f64
    };
    let expected = reference(2) - reference(1);
    for (name, on, off, shift) in [
        ("gi", "gi=true", "gi=false", "pt_shift=hybrid"),
        ("pt", "pt=true", "pt=false", "pt_shift=hybrid"),
        ("pt replay", "pt=true", "pt=false", "pt_shift=random-replay"),
    ] {
        let extra = ["max_bounces=2", shift];
        let direct = restir_means(&scene, &[&[off][..], &extra].concat(), &[], FRAMES);
        let ratio = |vertices: &str, planted: &[&str]| {
            let on = restir_means(
                &scene,
                &[&[on, vertices][..], &extra].concat(),
                planted,
                FRAMES,
            );
            let per_seed: Vec<f64> = on
                .iter()
                .zip(&direct)
                .map(|(a, d)| (a - d) / expected)
                .collect();
            let mean = per_seed.iter().sum::<f64>() / per_seed.len() as f64;
            eprintln!(
                "{name} {vertices} {planted:?}: indirect / reference {mean:.4} (seeds {per_seed:.4?})"
            );
            mean
        };
        let tree = ratio("bvh_at_vertices=true", &[]);
        let table = ratio("bvh_at_vertices=false", &[]);
        let planted = ratio("bvh_at_vertices=true", &[PLANTED]);
        for (what, r) in [("tree", tree), ("table", table)] {
            assert!(
                (r - 1.0).abs() < TOLERANCE,
                "{name} with the {what} at the vertices: {r:.4}"
            );
        }
        assert!(
            (planted - 1.0).abs() > 3.0 * TOLERANCE,
            "{name}: {PLANTED} went unseen ({planted:.4})"
        );
    }
}

const FRAMES: u32 = 32;
const TOLERANCE: f64 = 0.05;
