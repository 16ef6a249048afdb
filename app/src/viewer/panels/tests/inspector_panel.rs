//! The pixel inspector on a synthetic pixel.

use restir_render::di::constants::{DEBUG_FLAG_SPATIAL_CAP, DEBUG_FLAG_TEMPORAL_MERGED};
use restir_render::gpu_types::{GpuPtPixelDebug, GpuPtReservoir};
use restir_render::pt::constants::*;
use restir_render::renderer::{PtInspection, PtStagePath, PtVertex};

use super::*;

fn reservoir(light: u32, m: f32, source: u32) -> GpuReservoir {
    GpuReservoir {
        light,
        p_hat: 0.25,
        uv: [0.125, 0.5],
        w_sum: 3.5,
        weight: 1.75,
        m,
        source,
    }
}

pub(super) fn synthetic_inspection() -> PixelInspection {
    let stage = |name: &str, r: GpuReservoir, point: Option<[f32; 3]>| StageReservoir {
        stage: name.to_string(),
        reservoir: r,
        sample_point: point,
        environment_direction: None,
    };
    PixelInspection {
        frame: 42,
        pixel: (12, 34),
        surface: GpuSurface {
            position: [1.0, 2.0, 3.0],
            depth: 4.5,
            material: 3,
            ..Default::default()
        },
        debug: GpuPixelDebug {
            source: SOURCE_SPATIAL,
            temporal_mask: REJECT_NORMAL | REJECT_DEPTH,
            spatial_mask: REJECT_MATERIAL | REJECT_TARGET,
            flags: DEBUG_FLAG_SPATIAL_CAP,
            m_initial: 1.0,
            m_temporal: 1.0,
            m_spatial: 6.0,
            weight: 1.75,
            p_hat: 0.25,
            spatial_accepted: 4,
            proposer: PROPOSER_BVH,
            ..Default::default()
        },
        stages: vec![
            stage(
                "initial",
                reservoir(7, 1.0, SOURCE_INITIAL),
                Some([0.5, 1.9, 0.25]),
            ),
            stage("temporal", reservoir(NO_LIGHT, 0.0, SOURCE_NULL), None),
            stage(
                "spatial 1",
                reservoir(9, 6.0, SOURCE_SPATIAL),
                Some([0.1, 1.9, 0.3]),
            ),
            StageReservoir {
                stage: "spatial 2".to_string(),
                reservoir: reservoir(11, 6.0, SOURCE_SPATIAL),
                sample_point: None,
                environment_direction: Some([0.0, 1.0, 0.0]),
            },
        ],
        gi: None,
        pt: None,
        radiance: [0.5, 0.25, 0.125],
        denoise: None,
        light_pdfs: Some(restir_render::light_sampler::SelectionPdfs {
            light: 11,
            power: 0.25,
            bvh: Some(0.0625),
        }),
    }
}

#[test]
fn the_inspector_shows_every_field_of_a_pixel() {
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(synthetic_inspection());
    let h = harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        s,
    );
    for text in [
        "Pixel 12, 34",
        "Frame 42",
        "material 3",
        "Final: source spatial",
        "initial",
        "temporal",
        "spatial 1",
        "0.125, 0.500",
        "point x",
        "1.900",
        "11 environment",
        "dir 1.000",
        "null",
        "1.7500e0",
        "3.5000e0",
        "Temporal rejections: 0b00011000 normal, depth",
        "Spatial rejections: 0b00000100 material",
        "Spatial sample checks: 0b01000000 target_zero",
        "under pairwise MIS these are counted, not rejected",
        "Spatial neighbours merged: 4",
        "spatial M cap fired",
        "Light 11: selection probability 2.500e-1 by power (and tiles), 6.250e-2 by the light BVH",
        "Proposed by: light BVH",
    ] {
        assert!(shows(&h, text), "the inspector does not show '{text}'");
    }
    // A temporal candidate merged although a sample check fired: pairwise counted it.
    let mut merged = synthetic_inspection();
    merged.debug.temporal_mask = REJECT_TARGET_RATIO;
    merged.debug.flags |= DEBUG_FLAG_TEMPORAL_MERGED;
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(merged);
    let h2 = harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        s,
    );
    assert!(shows(&h2, "Temporal rejections: 0b00000000 none"));
    assert!(shows(
        &h2,
        "Temporal sample checks: 0b10000000 target_ratio — counted, not rejected"
    ));
    // Light ids as their own cells.
    assert!(h.query_by_label("7").is_some() && h.query_by_label("9").is_some());
}

/// Behind glass the inspector says what the surface's shading is worth and what the layers
/// add; an opaque pixel says nothing of layers.
#[test]
fn the_inspector_shows_the_layers_in_front() {
    let mut behind_glass = synthetic_inspection();
    behind_glass.surface.transparent_first = 1;
    behind_glass.surface.throughput = [0.5, 0.25, 0.125];
    behind_glass.surface.emission = [0.0625, 0.0, 2.0];
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(behind_glass);
    let h = harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        s,
    );
    assert!(shows(
        &h,
        "Seen through transparent layers: shading × (0.500, 0.250, 0.125) · added: (0.062, 0.000, 2.000)"
    ));
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(synthetic_inspection());
    let h = harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        s,
    );
    assert!(!shows(&h, "Seen through transparent layers"));
}

/// With GI on, the inspector adds the GI reservoir after each GI stage and the GI checks.
#[test]
fn the_inspector_shows_the_gi_stages() {
    let gi_reservoir = |source: u32, flags: u32, m: f32| GpuGiReservoir {
        position: [0.25, 1.5, -0.75],
        normal: 0,
        radiance: [2.0, 0.5, 0.125],
        w_sum: 0.5,
        weight: 3.25,
        m,
        p_hat: 0.0625,
        packed: GpuGiReservoir::pack(source, flags, 3),
    };
    let mut inspection = synthetic_inspection();
    inspection.gi = Some(GiInspection {
        debug: GpuGiPixelDebug {
            temporal_mask: GI_REJECT_JACOBIAN,
            spatial_mask: GI_REJECT_OCCLUDED,
            spatial_accepted: 2,
            jacobian: 1.5,
            ..Default::default()
        },
        stages: vec![
            GiStageReservoir {
                stage: "gi initial".into(),
                reservoir: gi_reservoir(SOURCE_INITIAL, 0, 1.0),
            },
            GiStageReservoir {
                stage: "gi temporal".into(),
                reservoir: gi_reservoir(SOURCE_TEMPORAL, GI_REJECT_JACOBIAN, 11.0),
            },
        ],
    });
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(inspection);
    let h = harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        s,
    );
    for text in [
        "Indirect (ReSTIR GI)",
        "gi initial",
        "gi temporal",
        "hit y",
        "1.500",
        "L_o r",
        "2.000",
        "3.2500e0",
        "jacobian",
        "GI temporal rejections: 0b10000000 jacobian",
        "GI spatial rejections: 0b100000000 occluded",
        "|J| of the survivor's last shift: 1.5000",
    ] {
        assert!(shows(&h, text), "the inspector does not show '{text}'");
    }
}

/// A path reservoir's `packed` word (shaders/pt/reservoir.wgsl): source | n << 4 | end << 8 |
/// k << 9 | lobes << 13.
fn pt_packed(source: u32, n: u32, end: u32, k: u32, lobes: u32) -> u32 {
    source | n << 4 | end << 8 | k << 9 | lobes << 13
}

fn pt_vertex(position: [f32; 3], reconnection: bool, light: bool, direction: bool) -> PtVertex {
    PtVertex {
        position,
        reconnection,
        light,
        direction,
    }
}

/// Three PT stages: a 3-bounce path reconnected at x2 after a specular first bounce, the
/// temporal stage's null path, and a spatial 2-bounce path replayed whole to the sky.
fn synthetic_pt() -> PtInspection {
    let reservoir = |packed: u32, weight: f32, m: f32| GpuPtReservoir {
        value: [0.25, 0.5, 0.75],
        p_hat: 0.5,
        weight,
        m,
        packed,
        light: 4,
        rc_suffix: [1.5, 1.25, 1.0],
        jacobian: 0.75,
        ..Default::default()
    };
    PtInspection {
        debug: GpuPtPixelDebug {
            temporal_failure: PT_FAIL_REPLAY,
            // Two neighbours moved, one's reconnection was occluded.
            spatial_outcomes: 2 << (4 * PT_FAIL_NONE) | 1 << (4 * PT_FAIL_OCCLUDED),
            spatial_tried: 3,
            jacobian: 0.75,
            m_initial: 1.0,
            m_temporal: 10.0,
            m_spatial: 13.0,
            ..Default::default()
        },
        stages: vec![
            PtStagePath {
                stage: "pt initial",
                // Lobe bit b is bounce ω_b: ω_1 specular, ω_2 diffuse (x_3 → z is NEE).
                reservoir: reservoir(pt_packed(SOURCE_INITIAL, 3, PT_END_NEE, 1, 0b10), 2.5, 1.0),
                vertices: vec![
                    pt_vertex([0.1, 0.2, 0.3], false, false, false),
                    pt_vertex([1.0, 2.0, 3.0], true, false, false),
                    pt_vertex([-1.0, 0.5, 2.0], false, false, false),
                    pt_vertex([0.0, 4.0, 0.0], false, true, false),
                ],
            },
            PtStagePath {
                stage: "pt temporal",
                reservoir: reservoir(pt_packed(SOURCE_NULL, 0, 0, PT_RC_NONE, 0), 0.0, 0.0),
                vertices: Vec::new(),
            },
            PtStagePath {
                stage: "pt spatial",
                reservoir: reservoir(
                    pt_packed(SOURCE_SPATIAL, 2, PT_END_BSDF, PT_RC_NONE, 0),
                    3.5,
                    13.0,
                ),
                vertices: vec![
                    pt_vertex([0.5, 0.5, 0.5], false, false, false),
                    pt_vertex([0.5, 1.5, 0.5], false, false, false),
                    pt_vertex([0.0, 1.0, 0.0], false, true, true),
                ],
            },
        ],
    }
}

fn inspector_showing(pt: PtInspection) -> Harness<'static, ViewerState> {
    let mut inspection = synthetic_inspection();
    inspection.pt = Some(pt);
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(inspection);
    harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        s,
    )
}

/// With PT on, the inspector adds how the shifts into the pixel went, each PT stage's
/// path reservoir and the path's vertices with the reconnection vertex marked.
#[test]
fn the_inspector_shows_the_pt_paths() {
    let h = inspector_showing(synthetic_pt());
    for text in [
        "Indirect (ReSTIR PT)",
        "PT temporal rejections: 0b00000000 none",
        "PT temporal shift: replay left the path",
        "PT spatial shifts (3 neighbours tried): moved × 2, reconnection occluded × 1",
        "PT M after initial / temporal / spatial: 1 / 10 / 13",
        "|J| of the survivor's last shift: 0.7500",
        "pt initial",
        "length n",
        "light sampling",
        "BSDF hit",
        "1 (at x2)",
        "none (replayed whole)",
        "specular, diffuse",
        "value g",
        "0.500",
        "2.5000e0",
        "rc suffix r",
        "1.500",
        "pt initial path",
        "x1 (0.100, 0.200, 0.300)",
        "x2 ◊ reconnection (1.000, 2.000, 3.000)",
        "x3 (-1.000, 0.500, 2.000)",
        "z light (0.000, 4.000, 0.000)",
        "pt temporal path",
        "no path",
        "z direction (0.000, 1.000, 0.000)",
    ] {
        assert!(shows(&h, text), "the inspector does not show '{text}'");
    }
    assert!(!shows(&h, "rebuilt"), "every path is whole");
    // A path the rebuild could not follow to its end says so; an untried temporal shift
    // and the previous pixel's failed checks are named.
    let mut partial = synthetic_pt();
    partial.stages[0].vertices.truncate(2);
    partial.debug.temporal_failure = PT_FAIL_NOT_TRIED;
    partial.debug.temporal_mask = REJECT_NORMAL;
    let h = inspector_showing(partial);
    for text in [
        "rebuilt 2 of 4 vertices",
        "PT temporal rejections: 0b00001000 normal",
        "PT temporal shift: not tried",
    ] {
        assert!(shows(&h, text), "the inspector does not show '{text}'");
    }
}

/// The stage table fits the side panel at its default width: three stages (initial,
/// temporal, one spatial pass) without sideways scrolling.
#[test]
fn the_stage_table_fits_the_default_panel_width() {
    let mut s = state();
    s.inspector.pixel = Some((12, 34));
    s.inspector.last = Some(synthetic_inspection());
    let h = Harness::builder()
        .with_size(egui::vec2(PANEL_WIDTH - 16.0, 1400.0))
        .build_ui_state(
            |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
            s,
        );
    let right = h
        .query_all_by_label_contains("e0")
        .chain(h.query_all_by_label("spatial 1"))
        .map(|n| n.rect().right())
        .fold(0.0f32, f32::max);
    assert!(
        right > 0.0 && right <= PANEL_WIDTH - 16.0,
        "the table's right edge is at {right} points"
    );
}

#[test]
fn freeze_and_step_are_plain_flags() {
    let mut h = harness(
        |ui, s: &mut ViewerState| inspector::ui(ui, &mut s.inspector),
        state(),
    );
    h.get_by_label("Freeze").click();
    h.run();
    assert!(h.state().inspector.frozen);
    h.get_by_label("Step").click();
    h.run();
    assert!(h.state().inspector.step);
}
