//! The Pipeline panel: switches, sliders, presets, the mode.

use super::*;
use restir_render::Mode;
use restir_render::settings::LightSampler;

#[test]
fn toggling_reuse_stages_and_moving_a_slider_change_the_settings() {
    let mut h = harness(pipeline::ui, state());
    h.get_by_label("Temporal reuse").click();
    h.run();
    assert!(!h.state().settings.temporal);
    h.get_by_label("Spatial reuse").click();
    h.run();
    assert!(!h.state().settings.spatial);
    h.get_by_role_and_label(Role::Slider, "Light candidates")
        .set_value_accesskit(7.0);
    h.run();
    assert_eq!(h.state().settings.light_candidates, 7);
    // Only what was touched changed.
    let expected = Settings {
        temporal: false,
        spatial: false,
        light_candidates: 7,
        ..Settings::default()
    };
    assert_eq!(h.state().settings, expected);
    h.get_by_label("Temporal reuse").click();
    h.run();
    assert!(h.state().settings.temporal);
}

#[test]
fn every_parameter_of_the_table_has_a_widget_with_its_doc() {
    let mut h = harness(
        |ui, s: &mut ViewerState| {
            // Every stage group open.
            ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
            pipeline::ui(ui, s);
        },
        state(),
    );
    for def in restir_render::settings::PARAMS {
        assert!(
            shows(&h, def.label),
            "no widget labelled '{}' for {}",
            def.label,
            def.name
        );
    }
    h.get_by_role_and_label(Role::Slider, "M cap").hover();
    h.run();
    let doc = restir_render::settings::Settings::def("m_cap").unwrap().doc;
    assert!(
        shows(&h, &doc[..40]),
        "hovering M cap shows its documentation"
    );
}

/// The Indirect stage holds two techniques: PT switches on while GI is off, and each
/// switch greys out its own technique's parameters only.
#[test]
fn pt_switches_on_without_gi_and_each_switch_greys_its_own_parameters() {
    let mut h = harness(
        |ui, s: &mut ViewerState| {
            ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
            pipeline::ui(ui, s);
        },
        state(),
    );
    let greyed = |h: &Harness<'_, ViewerState>, label: &str| {
        h.get_by_label(label).accesskit_node().is_disabled()
    };
    assert!(greyed(&h, "PT temporal reuse") && greyed(&h, "GI temporal reuse"));
    assert!(!greyed(&h, "Indirect (ReSTIR PT)") && !greyed(&h, "Indirect (ReSTIR GI)"));
    // Accessibility clicks: with everything visible every popup and tooltip is open too,
    // and they cover the checkboxes from the pointer.
    h.get_by_label("Indirect (ReSTIR PT)").click_accesskit();
    h.run();
    assert!(h.state().settings.pt && !h.state().settings.gi);
    assert!(!greyed(&h, "PT temporal reuse") && greyed(&h, "GI temporal reuse"));
    h.get_by_label("PT temporal reuse").click_accesskit();
    h.run();
    assert!(!h.state().settings.pt_temporal);
}

#[test]
fn loading_a_preset_restores_the_settings() {
    let path = temp_file("preset.toml");
    let saved = Settings {
        m_cap: 7.5,
        spatial: false,
        light_candidates: 12,
        ..Settings::default()
    };
    preset::save(&path, &saved).unwrap();
    let mut s = state();
    s.preset_path = path.display().to_string();
    let mut h = harness(pipeline::ui, s);
    h.get_by_label("Temporal reuse").click();
    h.run();
    assert!(!h.state().settings.temporal);
    h.get_by_label("Load").click();
    h.run();
    assert_eq!(h.state().settings, saved);
    assert!(
        h.state()
            .preset_message
            .as_deref()
            .unwrap_or("")
            .starts_with("loaded")
    );
    // Save writes what is shown; a missing file is an error in the panel, settings kept.
    h.get_by_label("Reset to defaults").click();
    h.run();
    assert_eq!(h.state().settings, Settings::default());
    h.get_by_label("Save").click();
    h.run();
    assert_eq!(preset::load(&path, &saved).unwrap().0, Settings::default());
    h.state_mut().preset_path = temp_file("missing.toml").display().to_string();
    h.get_by_label("Load").click();
    h.run();
    assert!(
        h.state()
            .preset_message
            .as_deref()
            .unwrap_or("")
            .starts_with("error")
    );
    assert_eq!(h.state().settings, Settings::default());
    std::fs::remove_file(&path).ok();
}

#[test]
fn the_mode_selector_sets_the_mode() {
    let mut h = harness(pipeline::ui, state());
    h.get_by_label("ris").click();
    h.run();
    assert_eq!(h.state().mode, restir_render::Mode::Ris);
}

#[test]
fn pixel_unit_parameters_show_their_effective_value() {
    let mut s = state();
    s.render_size = (225, 180);
    let h = harness(
        |ui, s: &mut ViewerState| {
            ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
            pipeline::ui(ui, s);
        },
        s,
    );
    // 30 px at 1080p is 5 px on a 180-pixel-high image.
    assert!(
        shows(&h, "= 5.0 px at this 180-pixel-high image"),
        "the spatial radius's effective value is not shown"
    );
}

#[test]
fn initial_visibility_says_when_mis_visibility_traces_it_anyway() {
    let note = "traced anyway: MIS visibility needs this pixel's own V";
    let panel = |ui: &mut egui::Ui, s: &mut ViewerState| {
        ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
        pipeline::ui(ui, s);
    };
    let mut s = state();
    s.settings.initial_visibility = false;
    let h = harness(panel, s.clone());
    assert!(
        shows(&h, note),
        "off, but the default MIS visibility traces it"
    );
    s.settings.mis_visibility = false;
    let h = harness(panel, s.clone());
    assert!(!shows(&h, note), "off and nothing traces it: no note");
    s.settings.mis_visibility = true;
    s.settings
        .set_from_str("bias_correction", "one-over-m")
        .unwrap();
    let h = harness(panel, s);
    assert!(!shows(&h, note), "1/M has no MIS terms: no note");
}

#[test]
fn the_ray_backend_says_what_runs_and_why_ray_queries_cannot() {
    let panel = |ui: &mut egui::Ui, s: &mut ViewerState| {
        ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
        pipeline::ui(ui, s);
    };
    let mut s = state();
    s.device.ray_query = true;
    s.device.ray_backend = Some(restir_render::tracing::RayBackend::Software);
    let h = harness(panel, s.clone());
    assert!(shows(&h, "= software here"), "what auto chose is not shown");
    // Forced on a device without them: the one-line refusal, and what renders instead.
    s.device.ray_query = false;
    s.settings.set_from_str("ray_backend", "ray-query").unwrap();
    let h = harness(panel, s);
    assert!(
        shows(&h, "has no hardware ray queries") && shows(&h, "rendering with software"),
        "the refusal is not shown"
    );
}

/// ReGIR's rows belong to `light_sampler=regir`: greyed out while another sampler draws the
/// candidates, live once ReGIR does.
#[test]
fn regir_rows_are_greyed_out_unless_regir_draws_the_candidates() {
    let panel = |sampler: LightSampler| {
        let mut s = state();
        s.settings.light_sampler = sampler;
        harness(
            |ui, s: &mut ViewerState| {
                ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
                pipeline::ui(ui, s);
            },
            s,
        )
    };
    // The row's widgets (a slider and its label) are greyed out together.
    let greyed = |h: &Harness<'_, ViewerState>, label: &str| {
        let nodes: Vec<_> = h.get_all_by_label(label).collect();
        assert!(!nodes.is_empty(), "no widget labelled {label}");
        nodes.iter().all(|n| n.accesskit_node().is_disabled())
    };
    let bvh = panel(LightSampler::Bvh);
    assert!(greyed(&bvh, "ReGIR jitter") && greyed(&bvh, "ReGIR cells per side"));
    assert!(!greyed(&bvh, "Light candidates"));
    let regir = panel(LightSampler::Regir);
    assert!(!greyed(&regir, "ReGIR jitter") && !greyed(&regir, "ReGIR cells per side"));
}

/// Switching the denoiser on in the panel applies restir-denoised and opens the split
/// screen against denoised RIS; switching it off brings back what was there. (Accessibility
/// clicks: with everything visible the tooltips cover the checkboxes from the pointer.)
#[test]
fn the_denoiser_switch_follows_the_map_and_back() {
    let mut before = state();
    before.settings.spatial_neighbours = 7;
    before.mode = Mode::Ris;
    let mut h = harness(
        |ui, s: &mut ViewerState| {
            ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
            pipeline::ui(ui, s);
        },
        before.clone(),
    );
    h.get_by_label("Denoiser (SVGF)").click_accesskit();
    h.run();
    let s = h.state();
    assert_eq!(s.mode, Mode::Restir);
    assert!(s.settings.denoise && s.settings.temporal && !s.settings.spatial);
    assert_eq!(s.settings.m_cap, 4.0);
    assert!(s.compare.enabled);
    assert_eq!(s.compare.spec, "ris+denoise");
    assert!(
        s.preset_message
            .as_deref()
            .is_some_and(|m| m.contains("restir-denoised"))
    );
    h.get_by_label("Denoiser (SVGF)").click_accesskit();
    h.run();
    let s = h.state();
    assert_eq!(s.mode, Mode::Ris);
    assert_eq!(s.settings, before.settings);
    assert!(!s.compare.enabled);
}

#[test]
fn without_following_the_map_the_denoiser_switch_changes_only_itself() {
    let mut h = harness(
        |ui, s: &mut ViewerState| {
            ui.ctx().memory_mut(|m| m.set_everything_is_visible(true));
            pipeline::ui(ui, s);
        },
        state(),
    );
    h.get_by_label("Denoiser on: switch to restir-denoised")
        .click_accesskit();
    h.run();
    h.get_by_label("Denoiser (SVGF)").click_accesskit();
    h.run();
    let expected = Settings {
        denoise: true,
        ..Settings::default()
    };
    assert_eq!(h.state().settings, expected);
    assert!(!h.state().compare.enabled);
}

/// A stage without a switch opens from its name, not only from its arrow.
#[test]
fn clicking_a_stage_name_opens_it() {
    let mut h = harness(pipeline::ui, state());
    assert!(
        !shows(&h, "Denoiser (SVGF)"),
        "the Denoiser stage starts closed"
    );
    h.get_by_label("Denoiser").click();
    h.run();
    assert!(shows(&h, "Denoiser (SVGF)"), "clicking its name opened it");
}
