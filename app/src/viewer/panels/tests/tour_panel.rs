//! The Tour section and the inspector's pixel history chart.

use super::inspector_panel::synthetic_inspection;
use super::*;
use crate::tour::Tour;
use crate::viewer::state::Action;
use crate::viewer::tour::{self as tour_state, state::TourState};

fn with_tour() -> ViewerState {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/tours/restir.toml");
    let tour = Tour::load(&path).unwrap_or_else(|e| panic!("{e:#}"));
    let mut s = state();
    s.scene.spec = tour.steps[0].scene.clone();
    s.tour = Some(TourState::new(tour, None));
    tour_state::go(&mut s, 0);
    s
}

fn current(h: &Harness<'_, ViewerState>) -> usize {
    h.state().tour.as_ref().unwrap().current
}

#[test]
fn the_tour_section_steps_forward_and_back_and_applies_each_step() {
    let mut h = harness(super::super::tour::ui, with_tour());
    let count = h.state().tour.as_ref().unwrap().tour.steps.len();
    assert!(shows(&h, &format!("Step 1 of {count}")));
    assert!(shows(&h, "NEE against RIS") && shows(&h, "one light sample per pixel"));
    assert_eq!(h.state().mode, restir_render::Mode::Nee);
    assert!(h.state().compare.enabled && h.state().compare.spec == "ris");
    assert!(shows(
        &h,
        "Per-frame luma RMSE: once the Accuracy reference is ready"
    ));
    h.get_by_label("Next").click();
    h.run();
    assert_eq!(current(&h), 1);
    assert!(shows(&h, &format!("Step 2 of {count}")) && shows(&h, "Temporal reuse"));
    let s = h.state();
    assert_eq!(s.mode, restir_render::Mode::Restir);
    assert!(!s.settings.spatial && s.settings.temporal);
    h.get_by_label("Back").click();
    h.run();
    assert_eq!((current(&h), h.state().mode), (0, restir_render::Mode::Nee));
    // Back is disabled on the first step: clicking it changes nothing.
    h.get_by_label("Back").click();
    h.run();
    assert_eq!(current(&h), 0);
}

#[test]
fn page_down_and_up_walk_the_tour_and_a_new_scene_loads_in_the_background() {
    let mut h = harness(
        |ui, s: &mut ViewerState| {
            shortcuts(ui.ctx(), s);
            side_panel(ui, s);
        },
        with_tour(),
    );
    assert!(
        h.query_by_label("Tour").is_some(),
        "the Tour section is shown"
    );
    for _ in 0..2 {
        h.key_press(egui::Key::PageDown);
        h.run();
    }
    assert_eq!(current(&h), 2);
    h.key_press(egui::Key::PageUp);
    h.run();
    assert_eq!(current(&h), 1);
    // The ghosting step is on another scene: it is requested, and its camera and time
    // wait for it (pending) while its parameters and B apply at once.
    let ghosting = h
        .state()
        .tour
        .as_ref()
        .unwrap()
        .tour
        .steps
        .iter()
        .position(|s| s.scene == "builtin:dynamic:blinking-lights")
        .unwrap();
    let s = h.state_mut();
    s.actions.clear();
    tour_state::go(s, ghosting);
    assert_eq!(s.tour.as_ref().unwrap().pending, Some(ghosting));
    assert!(s.actions.iter().any(|a| matches!(
        a,
        Action::LoadTourScene { scene, .. } if scene == "builtin:dynamic:blinking-lights"
    )));
    assert_eq!(
        (s.settings.m_cap, s.compare.spec.as_str()),
        (5.0, "M cap 20")
    );
    assert_eq!(s.compare.target.as_ref().unwrap().settings.m_cap, 20.0);
    // The scene arrives: a 3 s clip, time frame-locked from 0.7 s.
    s.scene.spec = "builtin:dynamic:blinking-lights".to_string();
    s.time.duration = 3.0;
    tour_state::after_load(s, ghosting);
    assert_eq!(s.tour.as_ref().unwrap().pending, None);
    assert_eq!(
        (s.time.time, s.time.frame_fps, s.time.playing),
        (0.7, Some(30.0), true)
    );
}

#[test]
fn the_inspector_chart_appears_when_a_pixel_is_picked() {
    let mut s = state();
    let h = harness(
        |ui, s: &mut ViewerState| {
            inspector::ui(ui, &mut s.inspector);
            pixel_history::ui(ui, s);
        },
        s.clone(),
    );
    assert!(!shows(&h, "Pixel history"), "no pixel, no chart");
    // Pick a pixel; frames come back with its inspection.
    s.inspector.pixel = Some((12, 34));
    let teaching = crate::viewer::tour::teaching::Teaching::default();
    for frame in 40..46 {
        let mut i = synthetic_inspection();
        i.frame = frame;
        i.radiance = [frame as f32 * 0.01; 3];
        crate::viewer::tour::driver::push_history(&mut s, &teaching, &i, Some(0.4));
    }
    s.inspector.last = s
        .inspector
        .history
        .samples
        .back()
        .map(|_| synthetic_inspection());
    let mut h = harness(
        |ui, s: &mut ViewerState| {
            inspector::ui(ui, &mut s.inspector);
            pixel_history::ui(ui, s);
        },
        s,
    );
    for text in [
        "Pixel history",
        "luminance (reference dashed",
        "M and age",
        "log10 W",
        "survivor's source",
        "frame 45 · luminance 0.4500 (reference 0.4000) · M 6 · W 1.750e0 · spatial · age 0",
    ] {
        assert!(shows(&h, text), "the chart does not show '{text}'");
    }
    h.get_by_label("Export CSV").click();
    h.run();
    assert!(h.state().actions.contains(&Action::ExportPixelHistory));
}
