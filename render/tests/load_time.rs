//! What loading costs per triangle (docs/src/load-time.md), as ratios measured in one run (never a
//! wall-clock limit: lavapipe machines differ by factors, a ratio of two CPU phases of
//! the same run does not).

use std::time::Instant;

use glam::{Vec2, Vec3};
use restir_render::scene::bvh::Bvh;
use restir_render::scene::lights::LightTable;
use restir_render::scene::{Material, Scene, Texture, TextureRef, Triangle, Vertex, Wrap};

/// A generated model with many emissive textured triangles: a `side`×`side` grid of quads,
/// every other one emissive through a 1024² emissive texture (a lamp's shade), the rest
/// plain. Large textures and many emitters are what made light tables slow elsewhere.
fn emissive_grid(side: u32) -> Scene {
    let mut scene = Scene {
        name: "emissive grid".into(),
        ..Scene::default()
    };
    let texels = (0..1024u32 * 1024)
        .map(|i| [(i % 251) as u8, (i % 13 * 19) as u8, 200, 255])
        .collect();
    scene.textures.push(Texture {
        name: "emissive".into(),
        width: 1024,
        height: 1024,
        texels,
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::Repeat,
    });
    scene.materials.push(Material::default());
    scene.materials.push(Material {
        emission: Vec3::splat(4.0),
        emissive_texture: Some(TextureRef::new(0)),
        ..Material::default()
    });
    for y in 0..side {
        for x in 0..side {
            let base = scene.vertices.len() as u32;
            for (dx, dy) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                let (u, v) = ((x + dx) as f32, (y + dy) as f32);
                scene.vertices.push(Vertex {
                    position: Vec3::new(u, v, ((x * 7 + y * 3) % 5) as f32 * 0.1),
                    normal: Vec3::Z,
                    uv: Vec2::new(u / side as f32, v / side as f32),
                });
            }
            let material = (x + y) % 2;
            for t in [[0, 1, 2], [0, 2, 3]] {
                scene.triangles.push(Triangle {
                    indices: t.map(|i| base + i),
                    material,
                });
            }
        }
    }
    scene
}

fn median_ms(mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2]
}

/// The light table of 80 k triangles (40 k emissive, textured) costs less than building
/// the BVH over them. Measured here: about 0.1–0.3× (the texture is averaged once per
/// material, then each emitter is an area and a multiply). A light table that integrates
/// the texture per triangle at full resolution is 1000× slower and fails by far; the bound
/// of 1× leaves room for a footprint-matched per-triangle integral (a finer alternative)
/// and for noise between two phases measured on one busy machine (medians of 5).
#[test]
fn the_light_table_costs_less_per_triangle_than_the_bvh_build() {
    let scene = emissive_grid(200);
    let positions: Vec<[Vec3; 3]> = (0..scene.triangles.len())
        .map(|t| scene.triangle_positions(t))
        .collect();
    let bvh = Bvh::build(&positions);
    let bvh_ms = median_ms(|| {
        std::hint::black_box(Bvh::build(&positions));
    });
    let table_ms = median_ms(|| {
        std::hint::black_box(LightTable::build(&scene, &bvh.triangle_order));
    });
    let table = LightTable::build(&scene, &bvh.triangle_order);
    assert_eq!(
        table.lights.len(),
        40_000,
        "every emissive triangle is a light"
    );
    let ratio = table_ms / bvh_ms;
    eprintln!(
        "80 000 triangles: light table {table_ms:.1} ms, BVH build {bvh_ms:.1} ms, ratio {ratio:.2}"
    );
    assert!(
        ratio < 1.0,
        "the light table took {ratio:.2}× the BVH build ({table_ms:.1} vs {bvh_ms:.1} ms)"
    );
}

/// The loader's phases, in order, with what they worked on; the normal maps (this renderer
/// shades with vertex normals) are not decoded, every texture a material reads is.
#[test]
fn a_real_models_load_phases_are_timed_and_unread_images_are_not_decoded() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/khronos/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf"
    );
    let heard = std::sync::Mutex::new(Vec::new());
    let watch = |e: restir_render::load_phases::LoadEvent| {
        if let restir_render::load_phases::LoadEvent::Finished(p) = e {
            heard.lock().unwrap().push(p.name);
        }
    };
    let scene = restir_render::load_scene_watched(path, &watch).unwrap();
    let names: Vec<_> = scene.load_phases.phases.iter().map(|p| p.name).collect();
    assert_eq!(
        names,
        [
            "read and parse",
            "buffers",
            "images",
            "geometry",
            "validate"
        ]
    );
    assert_eq!(
        *heard.lock().unwrap(),
        names,
        "the watcher heard each phase"
    );
    let images = scene.load_phases.get("images").unwrap();
    assert!(
        images.detail.contains("2 not read by any material skipped"),
        "{}",
        images.detail
    );
    // Textures 1 and 5 are the file's two normal maps (material0_normal.png, material1_normal.png).
    for (i, t) in scene.textures.iter().enumerate() {
        let normal_map = i == 1 || i == 5;
        assert_eq!(
            (t.width, t.height) == (1, 1),
            normal_map,
            "texture {i}: {}×{}",
            t.width,
            t.height
        );
    }
}

use crate::common;

use restir_render::load_phases::LoadEvent;
use restir_render::{Mode, PipelineCompile, Renderer, Settings, load_scene};

/// The viewer's scene swap: `scene` prepared by `preparer` (uploaded, pipelines warmed on
/// a second device), shown, then a still and a moved frame. Returns what the warm-up
/// compiled and what the renderer's own device compiled for those two frames.
fn swap_and_compile(
    main: &mut Renderer,
    preparer: restir_render::ScenePreparer,
    scene: &restir_render::Scene,
) -> (Vec<PipelineCompile>, Vec<PipelineCompile>) {
    let heard = std::sync::Mutex::new(Vec::new());
    let watch = |e: LoadEvent| match e {
        LoadEvent::Started(n) => heard.lock().unwrap().push(format!("start {n}")),
        LoadEvent::Finished(p) => heard.lock().unwrap().push(format!("end {}", p.name)),
        LoadEvent::Progress { .. } => {}
    };
    let mut prepared = preparer.prepare(scene, &watch).unwrap();
    prepared.finish_warm_up();
    let heard = heard.into_inner().unwrap();
    for step in [
        "start upload",
        "end BVH build",
        "start warm-up",
        "end warm-up",
    ] {
        assert!(
            heard.iter().any(|h| h == step),
            "{step} not heard: {heard:?}"
        );
    }
    let warm_up = prepared.load_phases().get("warm-up").unwrap();
    assert!(
        warm_up.detail.contains("pipelines compiled and run once"),
        "{}",
        warm_up.detail
    );
    let warmed = prepared.warmed().to_vec();
    let before = main.pipeline_compiles().len();
    main.set_prepared_scene(prepared);
    main.render_frame().unwrap();
    let mut camera = main.camera();
    camera.position += camera.forward() * (0.01 * main.scene_scale());
    main.set_camera(camera);
    main.render_frame().unwrap();
    assert_eq!(main.read_radiance().non_finite_count(), 0);
    (warmed, main.pipeline_compiles()[before..].to_vec())
}

fn covered(warmed: &[PipelineCompile], c: &PipelineCompile) -> bool {
    warmed
        .iter()
        .any(|w| w.pass == c.pass && w.variant == c.variant)
}

/// The background preparation compiles (on its second device) every pipeline the new
/// scene's first frames then need on the renderer's device, in the renderer's mode,
/// settings and view: so the driver's shader cache has them when the window asks. Planted
/// twin: a preparer taken while the renderer was in another mode warms the wrong variants,
/// and the check sees pipelines it missed.
#[test]
fn the_warm_up_compiles_every_pipeline_the_first_frames_need() {
    // No frame before the swap: the renderer compiles pipelines once per variant, so
    // everything it compiles afterwards is for the new scene.
    let fresh = || {
        common::renderer(
            "builtin:plane-light",
            24,
            16,
            Mode::Restir,
            Settings::default(),
        )
    };
    let mut main = fresh();
    let scene = load_scene("builtin:cornell").unwrap();

    let preparer = main.preparer();
    let (warmed, compiled) = swap_and_compile(&mut main, preparer, &scene);
    // The renderer's device compiles for itself (the driver's cache makes that quick), so
    // there is something to cover; and the warm-up covered all of it.
    assert!(!compiled.is_empty());
    let missed: Vec<_> = compiled.iter().filter(|c| !covered(&warmed, c)).collect();
    assert!(missed.is_empty(), "not warmed: {missed:?}");

    // Planted: warmed for the reference, shown in restir.
    let mut main = fresh();
    main.set_mode(Mode::Reference);
    let stale = main.preparer();
    main.set_mode(Mode::Restir);
    let (warmed, compiled) = swap_and_compile(&mut main, stale, &scene);
    assert!(
        compiled.iter().any(|c| !covered(&warmed, c)),
        "a warm-up of the wrong mode went unnoticed"
    );
}

/// A scene swapped in compiles its own effect set, not the one the old scene's frames
/// cached (the set is cached while the settings stay the same): the viewer once showed
/// StainedGlassLamp, loaded after cornell, with cornell's effects — no textures, every
/// emitter a flat white.
#[test]
fn a_swapped_scene_renders_with_its_own_effects() {
    let textured = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/khronos/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf"
    );
    let own = |spec: &str| {
        let mut r = common::renderer(spec, 16, 12, Mode::Restir, Settings::default());
        r.render_frame().unwrap();
        r.last_effects().unwrap().clone()
    };
    let (before, after) = (own("builtin:cornell"), own(textured));
    assert_ne!(
        before, after,
        "the two scenes must differ in effects for this test"
    );
    let mut main = common::renderer("builtin:cornell", 16, 12, Mode::Restir, Settings::default());
    main.render_frame().unwrap();
    main.set_scene(&load_scene(textured).unwrap()).unwrap();
    main.render_frame().unwrap();
    assert_eq!(main.last_effects(), Some(&after));
}

/// A change that needs new pipelines (GI on) names its effect set before the frame, and
/// the sibling's warm-up of that set compiles every pipeline the renderer's next two frames
/// then compile (the second runs GI's temporal pass). Planted twin: a preparer taken
/// before the change (GI still off) warms the same effect set without GI's passes.
#[test]
fn a_changes_pipelines_warm_beside_the_renderer() {
    let scene = std::sync::Arc::new(load_scene("builtin:plane-light").unwrap());
    let fresh = || {
        let mut r = Renderer::new(common::gpu(), &scene, 24, 16, Settings::default()).unwrap();
        r.render_frame().unwrap();
        r.render_frame().unwrap();
        assert_eq!(
            r.effects_to_compile().unwrap(),
            None,
            "both frames compiled"
        );
        r
    };
    let with_gi = Settings {
        gi: true,
        ..Settings::default()
    };
    let warm_then_render =
        |main: &mut Renderer, preparer: restir_render::ScenePreparer, effects| {
            let warmed = preparer
                .warm_effects(scene.clone(), effects)
                .join()
                .unwrap()
                .unwrap();
            let before = main.pipeline_compiles().len();
            main.render_frame().unwrap();
            main.render_frame().unwrap();
            let compiled = main.pipeline_compiles()[before..].to_vec();
            assert!(!compiled.is_empty());
            (warmed, compiled)
        };

    let mut main = fresh();
    main.set_settings(with_gi.clone());
    let effects = main
        .effects_to_compile()
        .unwrap()
        .expect("GI needs new pipelines");
    let preparer = main.preparer();
    let (warmed, compiled) = warm_then_render(&mut main, preparer, effects);
    let missed: Vec<_> = compiled.iter().filter(|c| !covered(&warmed, c)).collect();
    assert!(missed.is_empty(), "not warmed: {missed:?}");

    let mut main = fresh();
    let stale = main.preparer();
    main.set_settings(with_gi);
    let effects = main
        .effects_to_compile()
        .unwrap()
        .expect("GI needs new pipelines");
    let (warmed, compiled) = warm_then_render(&mut main, stale, effects);
    assert!(
        compiled.iter().any(|c| !covered(&warmed, c)),
        "a warm-up of the old effects went unnoticed"
    );
}
