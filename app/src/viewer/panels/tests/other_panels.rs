//! The View, Scene and Stats panels.

use super::*;
use restir_render::pt::constants::PT_FAIL_NAMES;
use restir_render::shader_constants::REJECT_TEMPORAL_REASONS;

#[test]
fn the_rejection_legend_toggles_and_isolates_reasons() {
    let mut s = state();
    s.view.view = DebugView::Rejection;
    let mut h = harness(view::ui, s);
    h.get_by_role_and_label(Role::CheckBox, "show temporal normal")
        .click();
    h.run();
    assert_eq!(
        h.state().view.reason_mask,
        REJECT_TEMPORAL_REASONS & !(1 << 3)
    );
    // "only" buttons, one per temporal reason: depth is row 4.
    h.get_all_by_label("only").nth(4).unwrap().click();
    h.run();
    assert_eq!(h.state().view.reason_mask, 1 << 4, "temporal depth alone");
    h.get_by_label("All").click();
    h.run();
    assert_eq!(h.state().view.reason_mask, REJECT_TEMPORAL_REASONS);
    // The spatial part is a count of rejected neighbours, switched on and off as one.
    assert!(h.state().view.spatial_count);
    h.get_by_role_and_label(Role::CheckBox, "rejected neighbours")
        .click();
    h.run();
    assert!(!h.state().view.spatial_count);
}

/// The View panel with `view` chosen under `settings`.
fn view_panel(view: DebugView, settings: Settings) -> Harness<'static, ViewerState> {
    let mut s = state();
    s.view.view = view;
    s.settings = settings;
    harness(view::ui, s)
}

/// The PT views' legends name every colour of pt/view.wgsl's palettes (the depths up to
/// max_bounces), and say when PT is off; `indirect` is drawn by whichever of GI and PT runs.
#[test]
fn the_pt_legends_name_their_colours_and_say_when_pt_is_off() {
    let pt = |on: bool| Settings {
        pt: on,
        max_bounces: 3,
        ..Settings::default()
    };
    let h = view_panel(DebugView::PtLength, pt(false));
    assert!(shows(&h, "n = 2") && shows(&h, "n = 3") && !shows(&h, "n = 4"));
    assert!(shows(&h, "ReSTIR PT is off (Indirect section)"));
    let h = view_panel(DebugView::PtReconnection, pt(true));
    assert!(shows(&h, "x2") && shows(&h, "x3") && shows(&h, "replayed whole"));
    assert!(!shows(&h, "is off"));
    let h = view_panel(DebugView::PtFailure, pt(true));
    for name in &PT_FAIL_NAMES[1..] {
        assert!(shows(&h, name), "the pt-failure legend lacks '{name}'");
    }
    assert!(shows(&h, "every shift moved"));
    let h = view_panel(DebugView::PtJacobian, pt(true));
    assert!(shows(&h, "|J| ≤ 1/16") && shows(&h, "≥ 16"));
    // indirect: PT draws it while on; GI's views have nothing then.
    assert!(!shows(&view_panel(DebugView::Indirect, pt(true)), "is off"));
    let h = view_panel(DebugView::Indirect, pt(false));
    assert!(shows(&h, "ReSTIR GI and PT are off"));
    let h = view_panel(DebugView::GiSource, pt(true));
    assert!(shows(&h, "ReSTIR PT replaces GI while on"));
    let gi = Settings {
        gi: true,
        ..Settings::default()
    };
    assert!(!shows(&view_panel(DebugView::GiM, gi), "is off"));
    assert!(shows(
        &view_panel(DebugView::GiM, pt(false)),
        "ReSTIR GI is off"
    ));
}

#[test]
fn view_buttons_queue_actions() {
    let mut h = harness(view::ui, state());
    h.get_by_label("Auto").click();
    h.run();
    h.get_by_label("Screenshot (F12)").click();
    h.run();
    assert_eq!(
        h.state().actions,
        vec![Action::AutoExposure, Action::Screenshot]
    );
    h.get_by_label("Accumulate").click();
    h.run();
    assert!(h.state().view.accumulate);
}

#[test]
fn the_scene_panel_shows_load_errors_and_queues_loads() {
    let mut s = state();
    s.scene.spec = "builtin:cornell".into();
    s.scene.error = Some("broken.gltf: not a glTF file".into());
    s.scene.open_path = "some/scene.gltf".into();
    let mut h = harness(scene::ui, s);
    assert!(shows(&h, "broken.gltf: not a glTF file"));
    assert!(shows(&h, "previous scene is still shown"));
    h.get_by_label("Open").click();
    h.run();
    assert_eq!(
        h.state().actions,
        vec![Action::LoadScene("some/scene.gltf".into())]
    );
}

#[test]
fn the_scene_panel_shows_the_environment_and_queues_environment_loads() {
    let mut s = state();
    s.scene.env_error = Some("sky.hdr: cannot decode as Hdr: truncated".into());
    s.scene.env_open_path = "skies/noon.exr".into();
    let mut h = harness(scene::ui, s);
    assert!(shows(&h, "Environment: none"));
    assert!(shows(&h, "sky.hdr: cannot decode as Hdr: truncated"));
    assert!(shows(&h, "previous environment is still used"));
    h.get_by_label("Open environment").click();
    h.run();
    h.get_by_label("Built-in sky").click();
    h.run();
    assert_eq!(
        h.state().actions,
        vec![
            Action::LoadEnvironment(Some("skies/noon.exr".into())),
            Action::LoadEnvironment(Some("builtin:sky".into())),
        ]
    );
}

/// Ten frames of plausible counters and pass times.
pub(super) fn with_reports(mut s: ViewerState) -> ViewerState {
    let mut c = vec![0u32; STAT_COUNT as usize];
    c[STAT_SURFACE_PIXELS as usize] = 1000;
    c[(STAT_SOURCE + SOURCE_TEMPORAL) as usize] = 600;
    c[(STAT_SOURCE + SOURCE_SPATIAL) as usize] = 400;
    c[(STAT_TEMPORAL_REJECT + 3) as usize] = 250;
    c[STAT_TEMPORAL_CAP as usize] = 100;
    c[STAT_FALLBACK_TRIED as usize] = 551_140;
    for frame in 0..10 {
        s.stats.push_report(FrameReport {
            frame,
            counters: FrameCounters(c.clone()),
            pass_ms: vec![("initial", 2.0), ("shade", 1.0), ("gbuffer resolve", 0.5)],
            inspection: None,
        });
        s.stats.push_frame_ms(50.0);
    }
    s.device.adapter = "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan)".into();
    s.device.driver = "llvmpipe Mesa 25.0.7".into();
    s.device.is_cpu = true;
    s.device.ray_query = true;
    s.device.ray_backend = Some(restir_render::tracing::RayBackend::RayQuery);
    s
}

#[test]
fn the_stats_panel_summarises_reports() {
    let h = harness(
        |ui, s: &mut ViewerState| stats::ui(ui, s),
        with_reports(state()),
    );
    for text in [
        "driver: llvmpipe Mesa 25.0.7",
        "Rays: ray-query",
        "Frame 50.0 ms (20.0 fps)",
        "initial: 2.00 ms",
        "temporal 60.0 %",
        "spatial 40.0 %",
        "temporal 10.0 %",
        "25.0 %",
    ] {
        assert!(shows(&h, text), "the stats panel does not show '{text}'");
    }
}

#[test]
fn the_stats_panel_shows_non_finite_values_per_pass() {
    let mut s = with_reports(state());
    let mut c = vec![0u32; STAT_COUNT as usize];
    c[(STAT_NONFINITE + PASS_TEMPORAL) as usize] = 17;
    s.stats.push_report(FrameReport {
        frame: 10,
        counters: FrameCounters(c),
        ..Default::default()
    });
    let h = harness(|ui, s: &mut ViewerState| stats::ui(ui, s), s);
    assert!(shows(&h, "Non-finite values replaced, per pass"));
    for name in GUARDED_PASS_NAMES {
        assert!(shows(&h, name), "no row for the {name} pass");
    }
    // The temporal row: its count in the window and since the scene loaded.
    assert_eq!(h.get_all_by_label("17").count(), 2);
}

#[test]
fn the_compare_section_picks_b_and_shows_both_errors() {
    let mut h = harness(compare::ui, state());
    h.get_by_label("Split screen: A | B").click();
    h.run();
    assert!(h.state().compare.enabled);
    assert_eq!(h.state().compare.spec, "ris");
    assert!(shows(&h, "once the Accuracy reference"));
    h.state_mut().compare.errors = Some((0.25, 0.5));
    h.run();
    assert!(shows(&h, "A 0.2500 · B 0.5000"));
    h.get_by_label("B on the left (X)").click();
    h.run();
    assert!(h.state().compare.flipped);
}

#[test]
fn the_scene_panel_lists_the_files_extensions() {
    use restir_render::scene::{ExtensionStatus, ExtensionUse};
    let mut s = state();
    s.scene.info = Some(scene_info(vec![
        ExtensionUse {
            name: "KHR_texture_transform".into(),
            required: false,
            status: ExtensionStatus::Used,
        },
        ExtensionUse {
            name: "KHR_materials_volume".into(),
            required: false,
            status: ExtensionStatus::PartlyUsed("thickness and attenuation ignored".into()),
        },
    ]));
    let h = harness(scene::ui, s);
    assert!(shows(&h, "glTF extensions (2)"));
    assert!(shows(&h, "KHR_texture_transform: used"));
    assert!(shows(
        &h,
        "KHR_materials_volume: partly used — thickness and attenuation ignored"
    ));
    // A scene without extensions shows no such list.
    let mut s = state();
    s.scene.info = Some(scene_info(Vec::new()));
    assert!(!shows(&harness(scene::ui, s), "glTF extensions"));
}

/// The BVH's moving part: how many triangles the tree keeps apart, or none.
#[test]
fn the_scene_panel_says_when_moving_triangles_have_their_own_subtree() {
    let mut s = state();
    let mut info = scene_info(Vec::new());
    info.bvh_moving_triangles = 102;
    s.scene.info = Some(info);
    let h = harness(scene::ui, s);
    assert!(shows(&h, "BVH moving part") && shows(&h, "102 triangles, own subtree"));
    let mut s = state();
    s.scene.info = Some(scene_info(Vec::new()));
    let h = harness(scene::ui, s);
    assert!(shows(&h, "1 nodes, depth 1, 0 ms") && !shows(&h, "own subtree"));
}

/// The phases from file to first frame (docs/src/load-time.md, "Loading in the viewer"), and
/// a load's phase on its progress bar.
#[test]
fn the_scene_panel_lists_load_phases_and_shows_a_loads_progress() {
    use restir_render::load_phases::{LoadPhases, Phase};
    let mut s = state();
    s.scene.info = Some(scene_info(Vec::new()));
    s.scene.load = LoadPhases {
        phases: vec![
            Phase {
                name: "images",
                ms: 812.0,
                detail: "13 decoded".into(),
            },
            Phase {
                name: "pipelines",
                ms: 4200.0,
                detail: "17 compiled".into(),
            },
        ],
    };
    s.scene.loading = Some("lamp.gltf".into());
    s.scene.progress.phase = "images".into();
    s.scene.progress.fraction = Some(0.5);
    let h = harness(
        |ui: &mut egui::Ui, s: &mut ViewerState| {
            ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
            scene::ui(ui, s);
        },
        s,
    );
    for text in [
        "Load phases (5.0 s)",
        "images",
        "812 ms",
        "4200 ms",
        "loading: images",
        "stays interactive while the file loads",
    ] {
        assert!(shows(&h, text), "{text} is not shown");
    }
}

#[test]
fn the_camera_panel_says_when_the_camera_was_chosen_automatically() {
    let mut s = state();
    assert!(!shows(
        &harness(|ui, s| camera::ui(ui, &mut s.camera), s),
        "chosen automatically"
    ));
    let mut s2 = state();
    s2.camera.automatic = true;
    assert!(shows(
        &harness(|ui, s| camera::ui(ui, &mut s.camera), s2),
        "chosen automatically (the file has no camera)"
    ));
    // F frames the scene from the current direction: direction kept, bounds in view.
    s = state();
    let before = s.camera.camera;
    s.camera.camera.position = glam::Vec3::new(0.0, 0.0, 50.0);
    let mut h = harness(|ui, s| super::shortcuts(ui.ctx(), s), s);
    h.key_press(egui::Key::F);
    h.run();
    let after = h.state().camera.camera;
    assert_eq!(after.rotation, before.rotation);
    assert!(
        after.position.z < 10.0 && after.position.z > 1.0,
        "{after:?}"
    );
}

fn scene_info(
    extensions: Vec<restir_render::scene::ExtensionUse>,
) -> restir_render::gpu_scene::SceneInfo {
    restir_render::gpu_scene::SceneInfo {
        name: "quad.gltf".into(),
        triangles: 2,
        emissive_triangles: 0,
        punctual_lights: 0,
        light_table_entries: 0,
        power_range: None,
        total_power: 0.0,
        bvh_nodes: 1,
        bvh_depth: 1,
        bvh_build_ms: 0.1,
        bvh_moving_triangles: 0,
        load: Default::default(),
        bounds_min: [0.0; 3],
        bounds_max: [1.0; 3],
        environment: None,
        extensions,
        camera_automatic: true,
        accel: None,
    }
}

/// With `denoise_auto_depth` on, the Stats panel says it is waiting for the probe, then the
/// depth it chose, every depth's error against the held-out frame and what the probe cost.
#[test]
fn the_stats_panel_shows_the_depth_the_probe_chose() {
    let mut s = with_reports(state());
    s.settings.denoise = true;
    s.settings.denoise_auto_depth = true;
    let h = harness(|ui, s: &mut ViewerState| stats::ui(ui, s), s.clone());
    assert!(shows(&h, "probing once the history is warm"));
    s.denoise_depth = Some(restir_render::denoise::depth_probe::DepthChoice {
        iterations: 2,
        held_out_error: vec![0.5, 0.2, 0.1, 0.15, 0.3, 0.4],
        pixels: 98_304,
        probe_ms: 412.0,
    });
    let h = harness(|ui, s: &mut ViewerState| stats::ui(ui, s), s.clone());
    for text in [
        "denoiser depth: 2 à-trous iterations",
        "412 ms",
        "98304 pixels",
        "2: 1.00e-1",
    ] {
        assert!(shows(&h, text), "the stats panel does not show '{text}'");
    }
    s.settings.denoise_auto_depth = false;
    let h = harness(|ui, s: &mut ViewerState| stats::ui(ui, s), s);
    assert!(!shows(&h, "denoiser depth"), "shown with the probe off");
}
