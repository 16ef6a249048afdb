//! The Time section and the clock arithmetic it drives.

use super::*;
use crate::viewer::state::TimeState;

fn timed(duration: f32) -> ViewerState {
    let mut s = state();
    s.time.duration = duration;
    s
}

#[test]
fn play_pause_and_step_are_plain_flags() {
    let mut h = harness(
        |ui, s: &mut ViewerState| time::ui(ui, &mut s.time),
        timed(3.0),
    );
    assert!(h.state().time.playing, "dynamic scenes start playing");
    h.get_by_label("Pause").click();
    h.run();
    assert!(!h.state().time.playing);
    h.get_by_label("Play").click();
    h.run();
    h.get_by_label("Step").click();
    h.run();
    assert!(!h.state().time.playing && h.state().time.step);
    assert!(shows(&h, "t = 0.000 s of 3.000 s, paused"));
}

#[test]
fn a_static_scene_says_so_and_the_side_panel_hides_the_section() {
    let h = harness(
        |ui, s: &mut ViewerState| time::ui(ui, &mut s.time),
        timed(0.0),
    );
    assert!(shows(&h, "does not change with time"));
    let h = harness(side_panel, timed(0.0));
    assert!(h.query_by_label("Time").is_none());
    let h = harness(side_panel, timed(2.0));
    assert!(h.query_by_label("Time").is_some());
}

#[test]
fn time_advances_wraps_or_stops_and_steps_one_frame() {
    let mut t = TimeState {
        duration: 3.0,
        time: 2.9,
        ..TimeState::default()
    };
    t.advance(0.05);
    assert!((t.time - 2.95).abs() < 1e-6);
    t.speed = 2.0;
    t.advance(0.1);
    assert!((t.time - 0.15).abs() < 1e-5, "wrapped: {}", t.time);
    // A long stall counts as 0.1 s, not as a jump across the clip.
    t.speed = 1.0;
    t.advance(5.0);
    assert!((t.time - 0.25).abs() < 1e-5);
    t.looping = false;
    t.time = 2.99;
    t.advance(0.1);
    assert_eq!((t.time, t.playing), (3.0, false));
    // Paused: only a step moves time, by one frame.
    t.time = 1.0;
    t.step = true;
    t.advance(0.1);
    assert!((t.time - (1.0 + TimeState::STEP)).abs() < 1e-6 && !t.step);
    t.advance(0.1);
    assert!((t.time - (1.0 + TimeState::STEP)).abs() < 1e-6);
    // A static scene never moves.
    let mut s = TimeState::default();
    s.advance(1.0);
    assert_eq!(s.time, 0.0);
}

#[test]
fn the_accuracy_panel_says_what_it_cannot_measure_while_time_plays() {
    let h = harness(accuracy::ui, timed(3.0));
    assert!(shows(&h, "Scene time is playing"));
    let mut paused = timed(3.0);
    paused.time.playing = false;
    let h = harness(accuracy::ui, paused);
    assert!(!shows(&h, "Scene time is playing"));
}
