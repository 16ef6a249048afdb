//! The Accuracy panel on synthetic state (no GPU): progress while the reference renders,
//! a new curve when a parameter changes with the previous one kept, jitter off in one
//! click. A "frame" here pushes a made-up measurement as the tracker would.

use std::time::Duration;

use restir_render::reference_cache::{Progress, ReferenceMeta};

use super::*;
use crate::viewer::accuracy::{Config, CurvePoint, PhaseStatus, ReferenceInfo, ReferenceStatus};

pub(super) fn ready() -> ReferenceStatus {
    ReferenceStatus::Ready(ReferenceInfo {
        meta: ReferenceMeta {
            key: String::new(),
            spp: 256,
            frames: 16,
            spp_per_frame: 16,
            noise_luma_rmse: Some(2.5e-3),
            noise_rgb_rmse: Some(3e-3),
            render_seconds: 9.5,
            adapter: "llvmpipe".into(),
        },
        from_cache: true,
        path: "target/restir-cache/ref-0123456789abcdef.exr".into(),
    })
}

/// What the tracker does after a rendered frame: the point goes into the curve of the
/// configuration the frame was rendered with.
pub(super) fn measure_frame(s: &mut ViewerState, frame: u64) {
    let config = Config {
        mode: s.mode,
        settings: s.settings.clone(),
    };
    let curves = &mut s.accuracy.curves;
    curves.curve_for(&config, frame);
    let first = curves.current.as_ref().map_or(frame, |c| c.first_frame);
    let n = (frame - first + 1) as f64;
    curves.push(CurvePoint {
        x: frame - first + 1,
        frame,
        luma_rmse: 0.02 + 0.01 / n,
        stability: (n > 1.0).then_some(0.01),
        accumulated_rgb_rmse: 0.02 / n.sqrt(),
        luma_ratio: 0.98,
        signed_bias: -0.0213,
        pass_ms: vec![("initial", 2.0), ("shade", 1.0)],
    });
}

#[test]
fn progress_is_shown_while_the_reference_renders() {
    let mut s = state();
    s.accuracy.reference = ReferenceStatus::Rendering(Progress {
        samples_done: 64,
        samples_total: 256,
        elapsed: Duration::from_secs(3),
    });
    let mut h = harness(accuracy::ui, s);
    h.run();
    assert!(shows(&h, "Rendering the reference"));
    let bar = h.get_by_role(Role::ProgressIndicator);
    assert!(
        bar.accesskit_node()
            .label()
            .is_some_and(|l| l.contains("64/256 spp") && l.contains("~9 s left")),
        "the progress bar says how far the reference is"
    );
    assert!(shows(&h, "Curves start once the reference is there"));
    // The error view's legend shows the same progress.
    h.state_mut().view.view = DebugView::Error;
    let mut state = h.state().clone();
    let h = harness(view::ui, state.clone());
    assert!(h.query_by_role(Role::ProgressIndicator).is_some());
    // So does the bias view's, under a legend that says grey is noise.
    state.view.view = DebugView::Bias;
    let h = harness(view::ui, state);
    assert!(h.query_by_role(Role::ProgressIndicator).is_some());
    assert!(shows(&h, "noise, not bias"));
    assert!(shows(&h, "+25 %"));
}

#[test]
fn a_parameter_change_starts_a_new_curve_and_keeps_the_previous_one() {
    let mut s = state();
    s.accuracy.reference = ready();
    let mut frame = 0;
    // The Pipeline panel to change a parameter, the Accuracy panel to show the curves.
    let mut h = harness(
        move |ui, s: &mut ViewerState| {
            pipeline::ui(ui, s);
            accuracy::ui(ui, s);
            measure_frame(s, frame);
            frame += 1;
        },
        s,
    );
    h.run_steps(5);
    assert!(shows(&h, "Reference: 256 spp, loaded from the cache"));
    assert!(shows(&h, "1: restir"));
    // The signed bias is reported next to the errors, per curve and for the current one.
    assert!(shows(&h, "-2.13 %"), "the signed bias row");
    assert!(
        shows(&h, "bias -2.13 %"),
        "the signed bias in the curve's legend line"
    );
    assert_eq!(h.state().accuracy.curves.previous.len(), 0);
    h.get_by_label("Temporal reuse").click();
    h.run_steps(5);
    let curves = &h.state().accuracy.curves;
    let current = curves.current.as_ref().expect("a current curve");
    assert_eq!(current.label, "temporal off");
    assert_eq!(
        current.points[0].x, 1,
        "the new curve starts at its frame 1"
    );
    assert_eq!(curves.previous.len(), 1, "the previous curve is kept");
    assert_eq!(curves.previous[0].label, "restir");
    assert!(shows(&h, "2: temporal off") && shows(&h, "1: restir"));
    assert!(shows(&h, "Per-frame luma RMSE"));
    assert!(shows(&h, "Median ms per pass"));
    h.get_by_label("Clear curves").click();
    h.run_steps(1);
    assert!(h.state().accuracy.curves.previous.is_empty());
}

#[test]
fn jitter_goes_off_in_one_click() {
    let mut s = state();
    s.settings.jitter = true;
    s.accuracy.phases = Some(PhaseStatus {
        ready: 3,
        rendering: None,
        failed: None,
    });
    let mut h = harness(accuracy::ui, s);
    h.run();
    assert!(shows(
        &h,
        "against the reference of its own sub-pixel offset"
    ));
    assert!(shows(&h, "Offsets with a reference: 3 of 64"));
    h.get_by_label("Jitter off for measuring").click();
    h.run();
    assert!(!h.state().settings.jitter);
    assert!(shows(&h, "errors measure lighting alone"));
}
