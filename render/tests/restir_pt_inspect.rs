//! What ReSTIR PT shows a person (docs/src/restir-pt.md, "What a person sees"): the inspector's
//! rebuilt paths and the debug records behind the PT views, checked against the path records they
//! describe.

use crate::common;

use common::indirect::render_planted;
use restir_render::pt::constants::*;
use restir_render::renderer::PtStagePath;
use restir_render::view::{DebugView, ViewSettings};
use restir_render::{Renderer, load_scene};

const W: u32 = 64;
const H: u32 = 48;
const SETTINGS: [&str; 3] = ["pt=true", "max_bounces=3", "pt_spatial_radius=300"];

fn renderer(shift: &str, frames: u32) -> Renderer {
    planted_renderer(&[shift], None, frames)
}

fn planted_renderer(assignments: &[&str], planted: Option<&str>, frames: u32) -> Renderer {
    let scene = load_scene("builtin:glossy").unwrap();
    let all = [&SETTINGS[..], assignments].concat();
    render_planted(&scene, (W, H), &all, planted, frames)
}

fn distance2(a: [f32; 3], b: [f32; 3]) -> f32 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum()
}

/// How a probed path's reconnection compares with its record.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Reconnection {
    /// Replayed whole, or the rebuild stopped before x_(k+1).
    NotChecked,
    /// |x_k − x_(k+1)|² is the record's rc_from_d2: after a replayed prefix when k ≥ 2.
    Matches {
        replayed: bool,
    },
    Mismatch,
}

/// The probe's vertices agree with the record: x_1 is the pixel's visible point, a
/// complete path has n surface vertices and its light end, the reconnection vertex sits at
/// x_{k+1}, and its distance from x_k is the record's rc_from_d2 (x_k replayed from this
/// pixel with the path's numbers, x_{k+1} from the stored triangle: a replay that drew the
/// wrong numbers lands elsewhere, the planted twin below).
fn check_path(path: &PtStagePath, visible_point: [f32; 3]) -> Reconnection {
    let v = &path.vertices;
    assert!(!v.is_empty(), "{}: a non-null path has x_1", path.stage);
    assert!(
        distance2(v[0].position, visible_point) < 1e-8,
        "{}: x_1",
        path.stage
    );
    let n = path.length() as usize;
    let complete = v.last().is_some_and(|z| z.light);
    if complete {
        assert_eq!(v.len(), n + 1, "{}: x_1 … x_n and z", path.stage);
    }
    let marked: Vec<usize> = (0..v.len()).filter(|&i| v[i].reconnection).collect();
    match path.reconnection_step() {
        None => {
            assert!(
                marked.is_empty(),
                "{}: a replayed path has no reconnection",
                path.stage
            );
            Reconnection::NotChecked
        }
        Some(k) if v.len() > k as usize => {
            let k = k as usize;
            assert_eq!(marked, [k], "{}: x_(k+1) is vertices[k]", path.stage);
            let d2 = distance2(v[k - 1].position, v[k].position);
            let stored = path.reservoir.rc_from_d2;
            // 1e-3: f32 positions a few units from the origin, squared distances of
            // 0.01–10 units², rebuilt by the same arithmetic as where the record was made.
            if (d2 / stored - 1.0).abs() < 1e-3 {
                Reconnection::Matches { replayed: k >= 2 }
            } else {
                eprintln!(
                    "{} (source {}): |x_k − x_(k+1)|² {d2} vs the record's {stored}",
                    path.stage,
                    path.source_name()
                );
                Reconnection::Mismatch
            }
        }
        Some(_) => Reconnection::NotChecked,
    }
}

/// Inspects 12 pixels, one a frame, and checks every non-null stage's path; returns the
/// outcomes of the reconnection checks.
fn probe_paths(r: &mut Renderer) -> Vec<Reconnection> {
    let mut outcomes = Vec::new();
    for i in 0..12u32 {
        let pixel = (4 + (i * 13) % (W - 8), 6 + (i * 7) % (H - 12));
        let inspection = common::inspect_next_frame(r, pixel);
        let pt = inspection
            .pt
            .expect("PT ran: its part of the inspection is there");
        let names: Vec<&str> = pt.stages.iter().map(|s| s.stage).collect();
        assert_eq!(names, ["pt initial", "pt temporal", "pt spatial"]);
        let index = (pixel.1 * W + pixel.0) as usize;
        assert_eq!(pt.stages[2].reservoir, r.read_pt_reservoirs()[index]);
        if inspection.surface.depth <= 0.0 {
            continue;
        }
        for path in pt.stages.iter().filter(|p| !p.is_null()) {
            outcomes.push(check_path(path, inspection.surface.position));
        }
    }
    outcomes
}

/// Hybrid with `pt_rough_threshold=1`: only purely diffuse vertices are rough, so paths off
/// the glossy floor replay their first bounce and reconnect at x_3 (the rebuild's replay is
/// what is checked).
const LATE_RECONNECTION: [&str; 2] = ["pt_shift=hybrid", "pt_rough_threshold=1"];

/// The inspector rebuilds each PT stage's path (pt initial, pt temporal, pt spatial) for
/// the pixel it inspects, with every shift; the last stage is what the frame left in the
/// PT buffers. Planted twin: a rebuild with another path's random numbers puts the
/// replayed x_k elsewhere, and the check says so.
#[test]
fn the_inspector_rebuilds_each_pt_stages_path() {
    let count = |outcomes: &[Reconnection], wanted: fn(&Reconnection) -> bool| {
        outcomes.iter().filter(|o| wanted(o)).count()
    };
    for shift in [
        &["pt_shift=reconnection"][..],
        &["pt_shift=random-replay"],
        &["pt_shift=hybrid"],
        &LATE_RECONNECTION,
    ] {
        let outcomes = probe_paths(&mut planted_renderer(shift, None, 3));
        let matched = count(&outcomes, |o| matches!(o, Reconnection::Matches { .. }));
        let replayed = count(&outcomes, |o| {
            *o == Reconnection::Matches { replayed: true }
        });
        eprintln!(
            "{shift:?}: {} paths, {matched} reconnections checked, {replayed} after a replayed prefix",
            outcomes.len()
        );
        assert!(outcomes.len() >= 12, "{shift:?}: too few paths to check");
        assert_eq!(
            count(&outcomes, |o| *o == Reconnection::Mismatch),
            0,
            "{shift:?}"
        );
        if shift[0] != "pt_shift=random-replay" {
            assert!(matched >= 6, "{shift:?}: {matched} reconnections checked");
        }
        if shift == LATE_RECONNECTION {
            assert!(
                replayed >= 4,
                "{shift:?}: {replayed} replayed prefixes checked"
            );
        }
    }
    let mut planted = planted_renderer(
        &LATE_RECONNECTION,
        Some("PLANTED_PT_PROBE_WRONG_NUMBERS"),
        3,
    );
    let outcomes = probe_paths(&mut planted);
    let wrong = count(&outcomes, |o| *o == Reconnection::Mismatch);
    eprintln!(
        "planted wrong numbers: {wrong} of {} paths mismatch",
        outcomes.len()
    );
    assert!(
        wrong >= 3,
        "the check must see a rebuild with the wrong numbers ({wrong})"
    );
}

/// The PT debug records count every neighbour's shift once, by outcome, and each shift
/// fails only in the ways it can: reconnection never replays (nothing to leave) nor
/// reconnects elsewhere; random replay never reconnects; hybrid can do all of these. On
/// the glossy room each shift fails somewhere (the views have something to show).
#[test]
fn pt_debug_records_classify_every_shift_into_the_pixel() {
    let can_fail = |shift: &str, failure: u32| match shift {
        "pt_shift=reconnection" => {
            [PT_FAIL_UNDEFINED, PT_FAIL_OCCLUDED, PT_FAIL_ZERO].contains(&failure)
        }
        "pt_shift=random-replay" => [PT_FAIL_REPLAY, PT_FAIL_ZERO].contains(&failure),
        _ => failure != PT_FAIL_NONE,
    };
    for shift in [
        "pt_shift=reconnection",
        "pt_shift=random-replay",
        "pt_shift=hybrid",
    ] {
        let r = renderer(shift, 4);
        let debug = r.read_pt_debug();
        let mut counts = [0u64; PT_FAIL_REASON_COUNT];
        for d in &debug {
            let outcomes: u32 = (0..PT_FAIL_REASON_COUNT as u32)
                .map(|f| d.spatial_count(f))
                .sum();
            assert_eq!(
                outcomes, d.spatial_tried,
                "{shift}: each tried shift counted once"
            );
            assert!(d.spatial_tried <= 3, "{shift}: 3 neighbours");
            for f in 0..PT_FAIL_REASON_COUNT as u32 {
                counts[f as usize] += d.spatial_count(f) as u64;
            }
            if d.temporal_failure != PT_FAIL_NOT_TRIED {
                assert!((d.temporal_failure as usize) < PT_FAIL_REASON_COUNT);
                counts[d.temporal_failure as usize] += 1;
            }
            assert!(d.m_temporal >= d.m_initial && d.m_spatial >= d.m_temporal - 1e-6);
        }
        eprintln!(
            "{shift}: outcomes {:?}",
            PT_FAIL_NAMES.iter().zip(counts).collect::<Vec<_>>()
        );
        assert!(
            counts[PT_FAIL_NONE as usize] > 0,
            "{shift}: some paths move"
        );
        for f in 1..PT_FAIL_REASON_COUNT {
            if counts[f] > 0 {
                assert!(
                    can_fail(shift, f as u32),
                    "{shift} cannot fail with {}",
                    PT_FAIL_NAMES[f]
                );
            }
        }
        let failed: u64 = counts[1..].iter().sum();
        assert!(failed > 0, "{shift}: no shift failed on the glossy room");
    }
}

/// Each PT view draws something that varies over the image (not one flat colour), and
/// changing the view does not change the estimate.
#[test]
fn the_pt_views_draw_their_data() {
    let mut r = renderer("pt_shift=hybrid", 3);
    let radiance = r.read_radiance();
    for view in [
        DebugView::PtLength,
        DebugView::PtReconnection,
        DebugView::PtFailure,
        DebugView::PtJacobian,
        DebugView::Indirect,
    ] {
        r.set_view(ViewSettings {
            view,
            ..ViewSettings::default()
        });
        r.redisplay().unwrap();
        let rgba = r.read_display_rgba8();
        let mut colours: Vec<[u8; 3]> = rgba.chunks(4).map(|p| [p[0], p[1], p[2]]).collect();
        colours.sort();
        colours.dedup();
        assert!(
            colours.len() >= 3,
            "{view:?} draws {} colours",
            colours.len()
        );
    }
    assert_eq!(r.read_radiance().pixels, radiance.pixels);
}
