//! The whole side panel: its width, the shortcuts, file drops.

use super::accuracy_panel::{measure_frame, ready};
use super::inspector_panel::synthetic_inspection;
use super::other_panels::with_reports;
use super::*;

/// Content must wrap or scroll inside the panel, never widen it (a wider panel shrinks
/// the scene area, which resizes the render targets and restarts accumulation). Every
/// section is open and filled; the harness also fails on any glyph the fonts lack.
#[test]
fn the_side_panel_keeps_its_width_whatever_it_shows() {
    let mut s = with_reports(state());
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(synthetic_inspection());
    s.view.view = DebugView::Rejection;
    s.camera.save_viewpoint();
    s.scene.spec = "builtin:many-lights".into();
    s.scene.info = Some(restir_render::gpu_scene::SceneInfo {
        name: "many-lights".into(),
        triangles: 123_456,
        emissive_triangles: 4096,
        punctual_lights: 2,
        light_table_entries: 4098,
        power_range: Some((1e-3, 2e2)),
        total_power: 1234.5,
        bvh_nodes: 250_000,
        bvh_depth: 31,
        bvh_build_ms: 812.0,
        bvh_moving_triangles: 4096,
        load: Default::default(),
        bounds_min: [-1.0; 3],
        bounds_max: [1.0; 3],
        environment: Some(restir_render::gpu_scene::EnvironmentInfo {
            name: "/very/long/path/to/some/studio_small_09_4k.exr".into(),
            width: 4096,
            height: 2048,
            strength: 1.5,
            rotation_deg: -90.0,
            light_share: 0.62,
            distribution_build_ms: 190.0,
        }),
        extensions: vec![restir_render::scene::ExtensionUse {
            name: "KHR_materials_specular".into(),
            required: true,
            status: restir_render::scene::ExtensionStatus::PartlyUsed(
                "specularTexture, specularColorFactor and specularColorTexture ignored".into(),
            ),
        }],
        camera_automatic: true,
        accel: None,
    });
    s.camera.automatic = true;
    s.scene.effects = Some(restir_render::effects::EffectSet::all());
    s.scene.passes = vec![
        "gbuffer raster",
        "initial",
        "temporal",
        "spatial",
        "shade",
        "display",
    ];
    s.scene.loading = Some("/some/long/path/to/a/scene/with/a/long/name.gltf".into());
    s.scene.error = Some("/some/long/path/to/a/scene/with/a/long/name.gltf: not a glTF file (unexpected end of input)".into());
    s.screenshot_message = Some("saved ./restir-builtin_many-lights-00042.png and ./restir-builtin_many-lights-00042-image.png".into());
    s.preset_message = Some(
        "error: /a/long/path/preset.toml: cannot read preset: No such file or directory".into(),
    );
    s.accuracy.reference = ready();
    s.accuracy.measure_ms = Some(2.5);
    for frame in 0..40 {
        // Four curves with long labels, as after a few parameter changes.
        if frame % 10 == 0 {
            s.settings.m_cap += 1.0;
            s.settings.spatial_neighbours += 1;
            s.settings.temporal = !s.settings.temporal;
            s.settings.jitter = false;
        }
        measure_frame(&mut s, frame);
    }
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 4000.0))
        .build_ui_state(
            |ui, s: &mut ViewerState| {
                ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
                side_panel(ui, s);
            },
            s,
        );
    // The loading spinner repaints forever: step instead of running until idle.
    h.run_steps(4);
    let edge = h.get_by_label("Resize panel").rect().left();
    assert!(
        edge >= 1280.0 - PANEL_WIDTH - 16.0,
        "the panel grew to {} points",
        1280.0 - edge
    );
}

#[test]
fn the_side_panel_draws_and_the_shortcuts_work() {
    let app = |ui: &mut egui::Ui, s: &mut ViewerState| {
        shortcuts(ui.ctx(), s);
        side_panel(ui, s);
    };
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 720.0))
        .build_ui_state(app, state());
    h.run();
    assert!(h.query_by_label("Pipeline").is_some());
    for key in [egui::Key::H, egui::Key::F12, egui::Key::P, egui::Key::N] {
        h.key_press(key);
        h.run();
    }
    let s = h.state();
    assert!(!s.panel_open && s.inspector.frozen && s.inspector.step);
    assert_eq!(s.actions, vec![Action::Screenshot]);
    // Typing in a text field is not a shortcut.
    h.state_mut().panel_open = true;
    h.run();
    let field = h
        .get_all_by_value("preset.toml")
        .find(|n| n.accesskit_node().role() == Role::TextInput);
    field.expect("the preset path field").focus();
    h.key_press(egui::Key::H);
    h.run();
    assert!(h.state().panel_open);
}

/// A file as the window system hands it over on a drop.
#[derive(Debug)]
struct Dropped(std::path::PathBuf);

impl egui::DroppedFile for Dropped {
    fn path(&self) -> &std::path::Path {
        &self.0
    }
    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn a_file_dropped_on_the_window_loads_as_the_scene() {
    let mut h = harness(side_panel, state());
    let file: egui::DroppedFileHandle = std::sync::Arc::new(Dropped("/scenes/sponza.glb".into()));
    h.input_mut().dropped_files.push(file);
    h.run();
    assert_eq!(
        h.state().actions,
        vec![Action::LoadScene("/scenes/sponza.glb".into())]
    );
}

/// Picking a pixel opens the (collapsed, last) Pixel inspector section and scrolls it
/// into view; without a pick it stays collapsed.
#[test]
fn picking_a_pixel_opens_and_reveals_the_inspector() {
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(synthetic_inspection());
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 720.0))
        .build_ui_state(side_panel, s);
    h.run();
    assert!(
        !shows(&h, "Pixel 12, 34"),
        "collapsed until a pixel is picked"
    );
    h.state_mut().inspector.reveal = true;
    h.run();
    assert!(!h.state().inspector.reveal, "revealed once");
    let label = h.get_by_label("Pixel 12, 34");
    let y = label.rect().top();
    assert!((0.0..720.0).contains(&y), "scrolled into view: at y = {y}");
}

#[test]
fn an_hdr_or_exr_dropped_on_the_window_loads_as_the_environment() {
    for path in ["/skies/noon.hdr", "/skies/STUDIO.EXR"] {
        let mut h = harness(side_panel, state());
        let file: egui::DroppedFileHandle = std::sync::Arc::new(Dropped(path.into()));
        h.input_mut().dropped_files.push(file);
        h.run();
        assert_eq!(
            h.state().actions,
            vec![Action::LoadEnvironment(Some(path.into()))]
        );
    }
}
