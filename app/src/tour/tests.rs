//! The tour parser: the shipped tour reads, and every kind of broken file gets one line
//! naming the file, the step and the problem.

use std::path::{Path, PathBuf};

use restir_render::settings::PtShift;
use restir_render::{DebugView, Mode};

use super::{LiveNumber, Tour};

fn shipped() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/tours/restir.toml")
}

#[test]
fn the_shipped_tour_covers_the_issue_list() {
    let tour = Tour::load(&shipped()).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(tour.steps.len() >= 13, "{} steps", tour.steps.len());
    let first = &tour.steps[0];
    assert_eq!(
        (first.mode, first.compare.as_ref().map(|c| c.mode)),
        (Mode::Nee, Some(Mode::Ris))
    );
    let views: Vec<DebugView> = tour.steps.iter().map(|s| s.debug_view).collect();
    for v in [
        DebugView::Source,
        DebugView::M,
        DebugView::Rejection,
        DebugView::Boiling,
    ] {
        assert!(views.contains(&v), "no step shows the {} view", v.name());
    }
    let ghosting = tour
        .steps
        .iter()
        .find(|s| s.show.contains(&LiveNumber::Lag))
        .expect("a lag step");
    assert_eq!(ghosting.scene, "builtin:dynamic:blinking-lights");
    assert_eq!(ghosting.settings.m_cap, 5.0);
    assert_eq!(ghosting.compare.as_ref().unwrap().settings.m_cap, 20.0);
    assert_eq!(ghosting.time.fps, Some(30.0));
    assert!(tour.steps.iter().any(|s| s.settings.gi));
    assert!(
        tour.steps
            .iter()
            .any(|s| s.env.as_deref() == Some("builtin:sky"))
    );
    // Path reuse: reconnection against hybrid where it matters, a glossy chain.
    let shifts = tour
        .steps
        .iter()
        .find(|s| s.settings.pt)
        .expect("a ReSTIR PT step");
    assert_eq!(
        (shifts.scene.as_str(), shifts.settings.max_bounces),
        ("builtin:glossy", 3)
    );
    let b = &shifts.compare.as_ref().expect("a split screen").settings;
    assert_eq!(
        (shifts.settings.pt_shift, b.pt_shift, b.pt),
        (PtShift::Reconnection, PtShift::Hybrid, true)
    );
    assert!(tour.steps.iter().all(|s| !s.caption.is_empty()));
}

/// Writes `text` as a tour file and returns the one-line error it gets.
fn error_of(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("restir-tour-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let e = format!("{:#}", Tour::load(&path).expect_err("a broken tour"));
    assert!(!e.contains('\n'), "not one line: {e}");
    assert!(e.contains(name), "the error does not name the file: {e}");
    e
}

#[test]
fn broken_tours_get_one_line_naming_the_file_the_step_and_the_problem() {
    let e = error_of("syntax.toml", "[[step]]\ntitle = \"a\nscene = 3\n");
    assert!(e.contains("not a valid tour at line 2"), "{e}");
    let e = error_of("empty.toml", "title = \"nothing\"\n");
    assert!(e.contains("no steps"), "{e}");
    let e = error_of(
        "param.toml",
        "[[step]]\ntitle = \"one\"\n[[step]]\ntitle = \"two\"\nm_capp = 5\n",
    );
    assert!(
        e.contains("step 2 (\"two\")") && e.contains("unknown parameter 'm_capp'"),
        "{e}"
    );
    let e = error_of("scene.toml", "[[step]]\nscene = \"builtin:nowhere\"\n");
    assert!(
        e.contains("step 1") && e.contains("unknown scene 'builtin:nowhere'"),
        "{e}"
    );
    let e = error_of("file.toml", "[[step]]\nscene = \"missing.gltf\"\n");
    assert!(e.contains("scene 'missing.gltf': no such file"), "{e}");
    let e = error_of("view.toml", "[[step]]\ndebug_view = \"sparkles\"\n");
    assert!(e.contains("debug_view 'sparkles'"), "{e}");
    let e = error_of("value.toml", "[[step]]\nm_cap = \"many\"\n");
    assert!(e.contains("parameter 'm_cap'"), "{e}");
    let e = error_of("camera.toml", "[[step]]\ncamera = { position = [0, 1] }\n");
    assert!(e.contains("camera.position: expected 3 numbers"), "{e}");
    let e = error_of("b.toml", "[[step]]\ncompare = { m_cap = 5, wobble = 1 }\n");
    assert!(e.contains("compare: unknown parameter 'wobble'"), "{e}");
    let e = error_of("show.toml", "[[step]]\nshow = [\"fps\"]\n");
    assert!(
        e.contains("show: '\"fps\"' is not one of rmse, bias, lag"),
        "{e}"
    );
    let e = error_of("top.toml", "titel = \"x\"\n[[step]]\n");
    assert!(e.contains("unknown key 'titel'"), "{e}");
}

#[test]
fn steps_keep_the_previous_scene_and_read_cameras_and_inline_b() {
    let dir = std::env::temp_dir().join(format!("restir-tour-ok-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("b.toml"), "m_cap = 3\n").unwrap();
    let path = dir.join("ok.toml");
    std::fs::write(
        &path,
        r#"
[[step]]
scene = "builtin:cornell"
camera = { position = [0, 1, 3], look_at = [0, 1, 0], yfov_degrees = 40 }
compare = "b.toml"
[[step]]
mode = "ris"
exposure = -1
camera = { position = [1, 2, 3], rotation = [0, 0, 0, 2] }
compare = { label = "short", mode = "nee", light_candidates = 4 }
"#,
    )
    .unwrap();
    let tour = Tour::load(&path).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(tour.title, "ok");
    let [a, b] = &tour.steps[..] else {
        panic!("two steps")
    };
    assert_eq!(
        (a.scene.as_str(), b.scene.as_str()),
        ("builtin:cornell", "builtin:cornell")
    );
    let cam = a.camera.unwrap();
    assert!((cam.forward() - glam::Vec3::NEG_Z).length() < 1e-5);
    assert!((cam.yfov.to_degrees() - 40.0).abs() < 1e-4);
    assert_eq!(a.compare.as_ref().unwrap().settings.m_cap, 3.0);
    assert_eq!(b.camera.unwrap().rotation, glam::Quat::IDENTITY);
    let inline = b.compare.as_ref().unwrap();
    assert_eq!(
        (
            inline.label.as_str(),
            inline.mode,
            inline.settings.light_candidates
        ),
        ("short", Mode::Nee, 4)
    );
    assert_eq!((b.mode, b.exposure), (Mode::Ris, Some(-1.0)));
    assert!(tour.step(3).is_err() && tour.step(0).is_err() && tour.step(2).is_ok());
}
