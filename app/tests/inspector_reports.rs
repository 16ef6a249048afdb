//! What the viewer's pixel inspector relies on, headless: while a pixel is selected,
//! every frame's report comes back with that pixel's inspection, also when the reports
//! are collected without waiting (as the viewer does once per drawn frame).

use std::time::{Duration, Instant};

use restir_render::{Gpu, Renderer, Settings, load_scene};

#[test]
fn every_report_carries_the_inspection_when_collected_without_waiting() {
    let scene = load_scene("builtin:cornell").expect("built-in scene");
    let gpu = Gpu::new_headless().unwrap_or_else(|e| panic!("no GPU adapter: {e}"));
    let mut renderer = Renderer::new(gpu, &scene, 48, 32, Settings::default()).unwrap();
    renderer.set_inspected_pixel(Some((24, 16)));
    let frames = 6;
    let mut reports = Vec::new();
    let deadline = Instant::now() + Duration::from_secs(60);
    for _ in 0..frames {
        renderer.render_frame().unwrap();
        reports.extend(renderer.collect_reports(false));
    }
    while reports.len() < frames && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(5));
        reports.extend(renderer.collect_reports(false));
    }
    assert_eq!(reports.len(), frames, "reports missing");
    for report in &reports {
        let inspection = report
            .inspection
            .as_ref()
            .unwrap_or_else(|| panic!("frame {} has no inspection", report.frame));
        assert_eq!(
            (inspection.frame, inspection.pixel),
            (report.frame, (24, 16))
        );
        let stages: Vec<&str> = inspection.stages.iter().map(|s| s.stage.as_str()).collect();
        assert_eq!(
            stages,
            ["initial", "temporal", "spatial 1"],
            "frame {}",
            report.frame
        );
    }
}
