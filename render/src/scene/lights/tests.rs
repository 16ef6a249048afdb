//! Light table tests: alias sampling against select_pdf (χ² and exact), exclusions, the
//! BVH-order mapping and punctual entries.

use std::f64::consts::PI;

use glam::{Vec2, Vec3};

use super::*;
use crate::reservoir::test_support::{Rng, assert_chi_square};
use crate::scene::{TextureRef, Triangle, Vertex, Wrap};

fn table_from_powers(powers: &[f64]) -> LightTable {
    let entries: Vec<(u32, f64)> = powers
        .iter()
        .enumerate()
        .map(|(i, &p)| (i as u32, p))
        .collect();
    let (lights, total_power) = alias_table(&entries);
    LightTable {
        lights,
        triangle_light: Vec::new(),
        punctual: Vec::new(),
        total_power,
        power_range: None,
        environment_light: NO_LIGHT,
        entries,
    }
}

/// The probability the alias table really gives each entry: its own slot's kept share plus
/// the shares other slots hand to it, each slot picked with probability 1/n.
fn implied_probabilities(lights: &[GpuLight]) -> Vec<f64> {
    let n = lights.len() as f64;
    let mut p = vec![0.0; lights.len()];
    for (i, l) in lights.iter().enumerate() {
        p[i] += l.alias_threshold as f64 / n;
        p[l.alias_index as usize] += (1.0 - l.alias_threshold as f64) / n;
    }
    p
}

#[test]
fn alias_sampling_follows_select_pdf() {
    let mut rng = Rng::new(21);
    let uniform = |rng: &mut Rng, n: usize| (0..n).map(|_| rng.f64() * 10.0).collect::<Vec<_>>();
    let log_uniform = |rng: &mut Rng, n: usize| {
        (0..n)
            .map(|_| 10f64.powf(-20.0 + 28.0 * rng.f64()))
            .collect()
    };
    let cases: Vec<Vec<f64>> = vec![
        vec![3.0],
        vec![1.0, 1e-9],
        uniform(&mut rng, 7),
        uniform(&mut rng, 300),
        log_uniform(&mut rng, 50),
        log_uniform(&mut rng, 1000),
    ];
    for powers in cases {
        let table = table_from_powers(&powers);
        let total: f64 = powers.iter().sum();
        let probs: Vec<f64> = powers.iter().map(|p| p / total).collect();
        for (l, (&p, implied)) in table
            .lights
            .iter()
            .zip(probs.iter().zip(implied_probabilities(&table.lights)))
        {
            assert!((0.0..=1.0).contains(&l.alias_threshold));
            assert!(
                (l.select_pdf as f64 - p).abs() <= 1e-6 * p,
                "select_pdf {} vs {p}",
                l.select_pdf
            );
            // f32 thresholds: absolute error of a few ulps of 1 per slot.
            assert!(
                (implied - p).abs() <= 1e-6 * (p + 1.0 / powers.len() as f64),
                "alias gives {implied} for {p}"
            );
        }
        let mut counts = vec![0u64; powers.len()];
        for _ in 0..200_000 {
            let (i, pdf) = table.sample(rng.f32(), rng.f32());
            assert_eq!(pdf, table.lights[i as usize].select_pdf);
            counts[i as usize] += 1;
        }
        assert_chi_square(&counts, &probs);
    }
    assert_eq!(table_from_powers(&[]).sample(0.5, 0.5), (NO_LIGHT, 0.0));
}

fn vertex(position: Vec3) -> Vertex {
    Vertex {
        position,
        normal: Vec3::ZERO,
        uv: Vec2::ZERO,
    }
}

/// A scene with one triangle per `(positions, material)`.
fn scene(triangles: &[([Vec3; 3], u32)], materials: Vec<Material>) -> Scene {
    let mut s = Scene {
        name: "test".into(),
        materials,
        ..Scene::default()
    };
    for &(p, material) in triangles {
        let base = s.vertices.len() as u32;
        s.vertices.extend(p.map(vertex));
        s.triangles.push(Triangle {
            indices: [base, base + 1, base + 2],
            material,
        });
    }
    s
}

/// A right triangle of area `a` at height `z`.
fn tri(a: f32, z: f32) -> [Vec3; 3] {
    let s = (2.0 * a).sqrt();
    [
        Vec3::new(0.0, 0.0, z),
        Vec3::new(s, 0.0, z),
        Vec3::new(0.0, s, z),
    ]
}

#[test]
fn triangle_powers_exclusions_and_bvh_mapping() {
    let red_black = Texture {
        name: "half red".into(),
        width: 2,
        height: 1,
        texels: vec![[255, 0, 0, 255], [0, 0, 0, 0]],
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::Repeat,
    };
    let black = Texture {
        texels: vec![[0, 0, 0, 255]],
        ..red_black.clone()
    };
    let mut textured = Material::emitter("textured", Vec3::splat(4.0), false);
    textured.emissive_texture = Some(TextureRef::new(0));
    let mut dark = Material::emitter("black texture", Vec3::ONE, false);
    dark.emissive_texture = Some(TextureRef::new(1));
    let materials = vec![
        Material::diffuse("wall", Vec3::ONE), // 0: not emissive
        Material::emitter("one-sided", Vec3::new(1.0, 2.0, 3.0), false), // 1
        Material::emitter("two-sided", Vec3::ONE, true), // 2
        textured,                             // 3
        dark,                                 // 4
        Material::emitter("negative", Vec3::new(-1.0, 0.0, 0.0), false), // 5
    ];
    let collinear = [Vec3::ZERO, Vec3::X, Vec3::X * 3.0];
    let huge = [Vec3::ZERO, Vec3::X * f32::MAX, Vec3::Y * f32::MAX];
    let source = [
        (tri(1.0, 0.0), 0),
        (tri(2.0, 1.0), 1),
        (collinear, 1),
        (tri(0.5, 2.0), 2),
        ([Vec3::ONE; 3], 2),
        (tri(3.0, 3.0), 3),
        (tri(1.0, 4.0), 4),
        (tri(1.0, 5.0), 5),
        (huge, 1),
    ];
    let mut s = scene(&source, materials);
    s.textures = vec![red_black, black];
    let triangle_order = [8, 3, 0, 5, 7, 2, 1, 4, 6];
    let table = LightTable::build(&s, &triangle_order);

    let lum = |rgb: [f32; 3]| luminance(rgb) as f64;
    // Texture mean (0.5, 0, 0) in linear: emission 4 → Le = (2, 0, 0).
    let expected = [
        (3, 0.5 * PI * 2.0),
        (5, 3.0 * PI * lum([2.0, 0.0, 0.0])),
        (1, 2.0 * PI * lum([1.0, 2.0, 3.0])),
    ];
    assert_eq!(table.lights.len(), expected.len());
    let total: f64 = expected.iter().map(|e| e.1).sum();
    assert!((table.total_power - total).abs() < 1e-5 * total);
    let mut emitters = 0;
    for (bvh_index, &light) in table.triangle_light.iter().enumerate() {
        let source = triangle_order[bvh_index];
        let Some(&(_, power)) = expected.iter().find(|e| e.0 == source) else {
            assert_eq!(light, NO_LIGHT, "triangle {source} should not be a light");
            continue;
        };
        emitters += 1;
        let entry = &table.lights[light as usize];
        assert_eq!(
            entry.kind_prim,
            LIGHT_KIND_TRIANGLE << LIGHT_KIND_SHIFT | bvh_index as u32
        );
        assert!(
            (entry.select_pdf as f64 - power / total).abs() < 1e-5,
            "triangle {source}"
        );
    }
    assert_eq!(emitters, expected.len());
    let (lo, hi) = table.power_range.unwrap();
    assert!((lo as f64 - PI).abs() < 1e-5 && (hi as f64 - expected[2].1).abs() < 1e-4);
}

#[test]
fn punctual_entries() {
    let light = |kind, intensity: Vec3| PunctualLight {
        kind,
        position: Vec3::new(1.0, 2.0, 3.0),
        direction: Vec3::new(0.0, -2.0, 0.0),
        intensity,
        range: None,
    };
    let spot = PunctualKind::Spot {
        inner_cone: 0.25,
        outer_cone: 0.5,
    };
    let mut s = scene(
        &[
            (tri(1.0, 0.0), 0),
            ([Vec3::ZERO, Vec3::ZERO, Vec3::new(2.0, 2.0, 1.0)], 0),
        ],
        vec![Material::default()],
    );
    s.punctual_lights = vec![
        light(PunctualKind::Point, Vec3::ONE),
        light(PunctualKind::Directional, Vec3::splat(2.0)),
        light(PunctualKind::Point, Vec3::ZERO), // no power: not in the table
        PunctualLight {
            range: Some(7.0),
            ..light(spot, Vec3::new(0.0, 1.0, 0.0))
        },
    ];
    let table = LightTable::build(&s, &[1, 0]);
    // Bounds (0,0,0)–(2,2,1): diagonal 3, R = 1.5.
    let powers = [
        (0, 4.0 * PI),
        (1, 2.0 * PI * 1.5 * 1.5),
        (3, 2.0 * PI * (1.0 - 0.5f64.cos()) * 0.7152),
    ];
    let total: f64 = powers.iter().map(|p| p.1).sum();
    assert!((table.total_power - total).abs() < 1e-5 * total);
    assert_eq!(table.triangle_light, [NO_LIGHT, NO_LIGHT]);
    assert_eq!(table.lights.len(), 3);
    for (entry, (index, power)) in table.lights.iter().zip(powers) {
        assert_eq!(
            entry.kind_prim,
            LIGHT_KIND_PUNCTUAL << LIGHT_KIND_SHIFT | index
        );
        assert!((entry.select_pdf as f64 - power / total).abs() < 1e-6);
    }
    assert_eq!(table.punctual.len(), 4);
    let p = &table.punctual[3];
    assert_eq!(
        (p.kind, p.range, p.position, p.direction),
        (PUNCTUAL_SPOT, 7.0, [1.0, 2.0, 3.0], [0.0, -1.0, 0.0])
    );
    assert_eq!((p.cos_outer, p.cos_inner), (0.5f32.cos(), 0.25f32.cos()));
    assert_eq!(
        (table.punctual[0].kind, table.punctual[0].range),
        (PUNCTUAL_POINT, 0.0)
    );
    assert_eq!(table.punctual[1].kind, PUNCTUAL_DIRECTIONAL);
}

#[test]
fn empty_table_is_valid() {
    let table = LightTable::build(
        &scene(&[(tri(1.0, 0.0), 0)], vec![Material::default()]),
        &[0],
    );
    assert!(table.lights.is_empty() && table.punctual.is_empty());
    assert_eq!((table.total_power, table.power_range), (0.0, None));
    assert_eq!(table.triangle_light, [NO_LIGHT]);
    assert_eq!(table.sample(0.3, 0.7), (NO_LIGHT, 0.0));
}

#[test]
fn environment_share_sets_its_probability_and_keeps_the_others_proportions() {
    let entries: Vec<(u32, f64)> = [3.0, 1.0, 96.0]
        .iter()
        .enumerate()
        .map(|(i, &p)| (i as u32, p))
        .collect();
    // Entry 2 is the environment: 96 % by power, 30 % by choice.
    let by_power = with_environment_share(&entries, 2, 0.0);
    assert!((by_power[2].select_pdf - 0.96).abs() < 1e-6);
    let shared = with_environment_share(&entries, 2, 0.3);
    let p = implied_probabilities(&shared);
    for (got, want) in p.iter().zip([0.7 * 0.75, 0.7 * 0.25, 0.3]) {
        assert!((got - want).abs() < 1e-6, "{got} vs {want}");
    }
    for (l, want) in shared.iter().zip(&p) {
        assert!((l.select_pdf as f64 - want).abs() < 1e-6);
    }
    // No environment entry, or nothing to share with: the power table.
    assert_eq!(with_environment_share(&entries, NO_LIGHT, 0.3), by_power);
    let alone = [(0u32, 5.0)];
    assert_eq!(with_environment_share(&alone, 0, 0.3)[0].select_pdf, 1.0);
}

#[test]
fn kept_slots_keep_their_index_at_zero_power_and_are_never_picked() {
    let on = Material::emitter("on", Vec3::ONE, false);
    let mut off = Material::emitter("off", Vec3::ONE, false);
    off.emission = Vec3::ZERO;
    let s = scene(
        &[(tri(1.0, 0.0), 0), (tri(1.0, 1.0), 1), (tri(2.0, 2.0), 0)],
        vec![on, off],
    );
    let order = [0, 1, 2];
    // Without slots the dark triangle is left out and the third light becomes entry 1.
    let plain = LightTable::build(&s, &order);
    assert_eq!(plain.triangle_light, vec![0, NO_LIGHT, 1]);
    let kept = LightTable::build_with_slots(&s, &order, &[false, true], false);
    assert_eq!(kept.triangle_light, vec![0, 1, 2]);
    assert_eq!(kept.lights[1].select_pdf, 0.0);
    let p = implied_probabilities(&kept.lights);
    assert_eq!(p[1], 0.0);
    assert!(
        (p[0] - 1.0 / 3.0).abs() < 1e-6 && (p[2] - 2.0 / 3.0).abs() < 1e-6,
        "{p:?}"
    );
    assert!(kept.sampleable());
    // Every light off: a table of kept slots that cannot be sampled, with no NaN in it.
    let dark = scene(
        &[(tri(1.0, 0.0), 0)],
        vec![Material::diffuse("d", Vec3::ONE)],
    );
    let t = LightTable::build_with_slots(&dark, &[0], &[true], false);
    assert_eq!(t.lights.len(), 1);
    assert!(!t.sampleable());
    assert_eq!(t.lights[0].select_pdf, 0.0);
    assert_eq!(t.power_range, None);
}

#[test]
fn zero_power_entries_in_an_alias_table_get_no_probability() {
    // Many zero slots around a few lit ones: rounding must not leave a zero slot picked.
    let powers: Vec<f64> = (0..1000)
        .map(|i| if i % 7 == 0 { 1.0 + i as f64 } else { 0.0 })
        .collect();
    let table = table_from_powers(&powers);
    let p = implied_probabilities(&table.lights);
    for (i, &power) in powers.iter().enumerate() {
        if power == 0.0 {
            assert_eq!(p[i], 0.0, "entry {i}");
        }
    }
}
