//! Specialisation (docs/src/specialisation.md): effect detection gives known answers, the
//! specialised pipeline renders what the general one does, and a diffuse scene's compiled shaders
//! contain no code for effects it does not have.

use crate::common;

use std::collections::BTreeSet;

use restir_render::effects::{Effect, EffectSet, SceneFeatures};
use restir_render::shader_source::compose;
use restir_render::{Mode, Settings, load_scene};

fn detected(scene: &str) -> BTreeSet<Effect> {
    let s = load_scene(scene).unwrap();
    EffectSet::detect(&SceneFeatures::of(&s), &Settings::default(), false).enabled
}

#[test]
fn effect_detection_gives_known_answers() {
    use Effect::*;
    let set = |effects: &[Effect]| effects.iter().copied().collect::<BTreeSet<_>>();
    // Lambertian walls and one area light: no GGX, no textures, no punctual lights.
    // (BSDF candidates are on by default whenever there is a light; light tiles from
    // LIGHT_TILES_BREAK_EVEN lights on, counted in emissive triangles.)
    let lit = [AreaLights, Shadows, BsdfCandidates];
    let tiles = |triangles: usize| {
        if triangles >= restir_render::effects::LIGHT_TILES_BREAK_EVEN {
            vec![LightTiles]
        } else {
            vec![]
        }
    };
    assert_eq!(
        detected("builtin:cornell"),
        set(&[&lit[..], &tiles(2)].concat())
    );
    assert_eq!(
        detected("builtin:many-lights-diffuse"),
        set(&[&lit[..], &tiles(8192)].concat())
    );
    assert_eq!(
        detected("builtin:many-lights"),
        set(&[&lit[..], &[Specular], &tiles(8192)].concat())
    );
    assert_eq!(
        detected("builtin:hard:mirror"),
        set(&[&lit[..], &[Specular, Metallic], &tiles(1024)].concat())
    );
    assert_eq!(detected("builtin:hard:no-emitters"), set(&[]));
    // A plane under a light is the boundary of a convex region: provably no shadows.
    assert_eq!(
        detected("builtin:plane-light"),
        set(&[&[AreaLights, BsdfCandidates][..], &tiles(2)].concat())
    );
    // The Blender exports: textured, one metallic/rough material (docs/src/scenes.md,
    // "Files in the repository"), the default specularFactor of 1 (a GGX lobe), one
    // emissive quad.
    let assets = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets");
    for file in [
        "blender-2.79-cornell/cornellBox-2.79-Cycles-gltf.gltf",
        "blender-2.80-cornell/cornellBox-2.80-Eevee-gltf.gltf",
    ] {
        let effects = detected(&format!("{assets}/{file}"));
        for e in [
            AreaLights,
            BaseColorTextures,
            Specular,
            Shadows,
            BsdfCandidates,
        ] {
            assert!(
                effects.contains(&e),
                "{file}: {e:?} missing from {effects:?}"
            );
        }
        // A handful of emitters: light tiles would cost more than they save.
        assert!(
            !effects.contains(&PunctualLights)
                && !effects.contains(&AlphaMask)
                && !effects.contains(&Motion)
                && !effects.contains(&LightTiles)
        );
    }
    // Settings add their own: no BSDF candidates, no BSDF-candidate code; a moving camera
    // needs motion vectors.
    let cornell = load_scene("builtin:cornell").unwrap();
    let features = SceneFeatures::of(&cornell);
    let s = Settings {
        bsdf_candidates: 0,
        light_sampler: restir_render::settings::LightSampler::Power,
        ..Settings::default()
    };
    assert!(!EffectSet::detect(&features, &s, false).contains(BsdfCandidates));
    assert!(!EffectSet::detect(&features, &s, false).contains(LightTiles));
    assert!(EffectSet::detect(&features, &s, true).contains(Motion));
    // Every effect carries a reason that says why it is on or off.
    let e = EffectSet::detect(&features, &Settings::default(), false);
    let specular = &e.reasons.iter().find(|(x, _)| *x == Specular).unwrap().1;
    assert!(specular.contains("specularFactor 0"), "{specular}");
}

#[test]
fn a_diffuse_scene_compiles_no_ggx_punctual_or_texture_code() {
    let cornell = load_scene("builtin:cornell").unwrap();
    let defines =
        EffectSet::detect(&SceneFeatures::of(&cornell), &Settings::default(), false).defines();
    let general = EffectSet::all().defines();
    for pass in [
        "di/initial.wgsl",
        "di/temporal.wgsl",
        "di/spatial.wgsl",
        "di/shade.wgsl",
        "reference.wgsl",
        "gbuffer_resolve.wgsl",
        "gbuffer_raster.wgsl",
    ] {
        let specialised = compose(pass, &defines).unwrap();
        for absent in [
            "fn ggx_d",
            "fn sample_ggx_vndf",
            "punctual_attenuation",
            "fn sample_texture",
            "unpack4x8unorm(texels",
        ] {
            assert!(
                !specialised.contains(absent),
                "{pass} for cornell still contains `{absent}`"
            );
        }
        // The general pipeline does contain them where the pass uses them.
        let all = compose(pass, &general).unwrap();
        assert!(
            all.len() > specialised.len(),
            "{pass}: specialising removed nothing"
        );
    }
    assert!(
        compose("di/initial.wgsl", &general)
            .unwrap()
            .contains("fn ggx_d")
    );
}

#[test]
fn specialised_and_general_pipelines_render_the_same_diffuse_image() {
    // Same seed, same scene. On a diffuse scene the general pipeline's extra code (GGX,
    // textures, punctual lights, metallic) is reached with specular = metallic = 0 and no
    // textures, where it computes exactly base_colour / π: the images agree to float
    // rounding (the GGX path forms (1 − F)·diffuse + F·spec with F = 0 exactly, so not even
    // rounding differs in practice). The assertion allows 1e-5 relative. Light tiles are
    // forced on, as when this was measured: the general set has them, and with `auto` a
    // one-light scene draws its candidates without them (same distribution, other numbers).
    for mode in [Mode::Restir, Mode::Reference] {
        let render = |effects: Option<EffectSet>| {
            let mut r = common::renderer(
                "builtin:cornell",
                48,
                36,
                mode,
                common::settings(&["jitter=false", "reference_spp=4", "light_sampler=tiles"]),
            );
            r.force_effects(effects);
            common::accumulate(&mut r, 4)
        };
        let auto = render(None);
        let all = render(Some(EffectSet::all()));
        let max_diff = auto
            .pixels
            .iter()
            .zip(&all.pixels)
            .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / b[c].abs().max(1e-3)))
            .fold(0.0f32, f32::max);
        eprintln!("{mode:?}: largest relative difference auto vs all: {max_diff:e}");
        assert!(
            max_diff < 1e-5,
            "{mode:?}: specialised and general differ by {max_diff}"
        );
    }
}

#[test]
fn passes_and_buffers_follow_the_settings() {
    let mut r = common::renderer(
        "builtin:cornell",
        32,
        24,
        Mode::Restir,
        common::settings(&["temporal=false", "spatial=false"]),
    );
    r.render_frame().unwrap();
    assert!(!r.last_passes().contains(&"temporal") && !r.last_passes().contains(&"spatial"));
    // Without temporal reuse no history is kept: its buffers are not even allocated.
    assert!(!r.history_allocated());
    r.set_settings(Settings::default());
    r.render_frame().unwrap();
    assert!(r.last_passes().contains(&"temporal") && r.last_passes().contains(&"spatial"));
    assert!(r.history_allocated());
    let effects = r.last_effects().unwrap().to_string();
    assert!(
        !effects.contains("specular") && !effects.contains("textures"),
        "{effects}"
    );
}

/// The light samplers are alternatives: the general pipeline keeps the tiles (ReGIR's fill
/// would overwrite them, the BVH's PDF would misweigh their BSDF candidates), and a forced
/// list naming two is refused in one line.
#[test]
fn the_light_samplers_are_alternatives() {
    let all = EffectSet::all();
    assert!(all.contains(Effect::LightTiles));
    assert!(!all.contains(Effect::Regir) && !all.contains(Effect::LightBvh));
    let err = EffectSet::parse_list("area-lights,light-tiles,light-bvh").unwrap_err();
    assert!(err.contains("alternative") && !err.contains('\n'), "{err}");
    assert!(EffectSet::parse_list("area-lights,regir").is_ok());
}
