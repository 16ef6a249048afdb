//! The viewer end to end: the real binary opens a real window on a private Xvfb server,
//! renders with wgpu on whatever adapter can present there (lavapipe in CI), and writes
//! a screenshot of the whole window. Each test starts its own Xvfb (it picks a free
//! display itself, `-displayfd`) and kills it afterwards. A missing Xvfb or GPU adapter
//! fails the test with the reason; nothing is skipped.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The default window (1280×720 logical pixels at scale factor 1) minus the side
/// panel's default width (380 points) is the scene area.
const WINDOW: (u32, u32) = (1280, 720);
const SCENE_RIGHT: u32 = 1280 - 380;
const VIEWER_TIMEOUT: Duration = Duration::from_secs(240);

/// A private X server, killed on drop.
struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    fn start() -> Xvfb {
        let mut child = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "1600x1000x24", "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("cannot start Xvfb ({e}): these tests need it (Debian/Ubuntu: apt-get install xvfb)"));
        // Xvfb writes the display number it chose once it accepts connections.
        let mut line = String::new();
        BufReader::new(child.stdout.take().expect("piped"))
            .read_line(&mut line)
            .expect("read Xvfb's display number");
        let number = line.trim();
        assert!(
            !number.is_empty() && number.chars().all(|c| c.is_ascii_digit()),
            "Xvfb did not report a display: {line:?}"
        );
        Xvfb {
            child,
            display: format!(":{number}"),
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

struct Run {
    stderr: String,
    png: image::RgbaImage,
}

fn out_path(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("viewer_window");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Runs `restir-viewer ARGS` on a fresh Xvfb; asserts exit 0 and reads `png`.
fn run_viewer(args: &[&str], png: &Path) -> Run {
    let _ = std::fs::remove_file(png);
    let x = Xvfb::start();
    let started = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args(args)
        .env("DISPLAY", &x.display)
        .env_remove("WAYLAND_DISPLAY")
        // Xvfb reports no DPI worth trusting: pin the scale so the window size is exact.
        .env("WINIT_X11_SCALE_FACTOR", "1")
        .env("RUST_LOG", "warn")
        // The split screen fetches the Accuracy reference: keep its cache out of the tree.
        .env("RESTIR_CACHE_DIR", out_path("restir-cache"))
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start restir-viewer");
    let mut stderr_pipe = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = stderr_pipe.read_to_string(&mut s);
        s
    });
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for the viewer") {
            break status;
        }
        if started.elapsed() > VIEWER_TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "restir-viewer {args:?} did not exit within {VIEWER_TIMEOUT:?}; stderr:\n{}",
                reader.join().unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let stderr = reader.join().unwrap_or_default();
    eprintln!(
        "restir-viewer {args:?}: {status} after {:.1} s",
        started.elapsed().as_secs_f32()
    );
    assert!(
        status.success(),
        "restir-viewer {args:?} failed ({status}); stderr:\n{stderr}"
    );
    let png = image::open(png)
        .unwrap_or_else(|e| panic!("{}: no screenshot ({e}); stderr:\n{stderr}", png.display()))
        .into_rgba8();
    Run { stderr, png }
}

/// The pixels of `img` inside x0..x1, y0..y1.
fn region(
    img: &image::RgbaImage,
    x: std::ops::Range<u32>,
    y: std::ops::Range<u32>,
) -> Vec<[u8; 3]> {
    y.flat_map(|y| x.clone().map(move |x| (x, y)))
        .map(|(x, y)| img.get_pixel(x, y).0)
        .map(|p| [p[0], p[1], p[2]])
        .collect()
}

fn brightness(p: [u8; 3]) -> f64 {
    (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0
}

/// Mean and standard deviation of brightness.
fn mean_and_deviation(pixels: &[[u8; 3]]) -> (f64, f64) {
    let n = pixels.len() as f64;
    let mean = pixels.iter().map(|p| brightness(*p)).sum::<f64>() / n;
    let var = pixels
        .iter()
        .map(|p| (brightness(*p) - mean).powi(2))
        .sum::<f64>()
        / n;
    (mean, var.sqrt())
}

fn close(a: [u8; 3], b: [u8; 3], tolerance: i32) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (*x as i32 - y as i32).abs() <= tolerance)
}

fn fraction(pixels: &[[u8; 3]], pred: impl Fn([u8; 3]) -> bool) -> f64 {
    pixels.iter().filter(|p| pred(**p)).count() as f64 / pixels.len() as f64
}

fn srgb(linear: [f32; 3]) -> [u8; 3] {
    linear.map(|c| {
        let s = if c <= 0.0031308 {
            c * 12.92
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s.clamp(0.0, 1.0) * 255.0).round() as u8
    })
}

/// The selection-source palette of shaders/display.wgsl (`source_color`), sRGB-encoded
/// as the display pass writes it: initial, temporal, spatial.
fn source_palette() -> [[u8; 3]; 3] {
    [
        srgb([0.15, 0.35, 1.0]),
        srgb([0.1, 0.85, 0.25]),
        srgb([1.0, 0.55, 0.05]),
    ]
}

fn scene_area(img: &image::RgbaImage) -> Vec<[u8; 3]> {
    region(img, 8..SCENE_RIGHT - 8, 8..WINDOW.1 - 8)
}

/// The side panel is egui's dark panel colour with lighter text on it.
fn assert_panel_drawn(img: &image::RgbaImage) {
    let panel = region(img, SCENE_RIGHT + 16..WINDOW.0, 0..WINDOW.1);
    let fill = egui::Visuals::dark().panel_fill;
    let fill = [fill.r(), fill.g(), fill.b()];
    let background = fraction(&panel, |p| p == fill);
    let text = fraction(&panel, |p| brightness(p) > 150.0);
    assert!(
        background > 0.4,
        "the panel area is not egui's panel colour {fill:?} ({:.0} % is)",
        background * 100.0
    );
    assert!(
        text > 0.005,
        "no text drawn in the panel area ({:.2} % bright pixels)",
        text * 100.0
    );
}

fn assert_window_sized(run: &Run, size: (u32, u32)) {
    assert_eq!(
        run.png.dimensions(),
        size,
        "the screenshot is not the window's size"
    );
    let line = format!("screenshot: {}x{} window", size.0, size.1);
    assert!(
        run.stderr.contains(&line),
        "the viewer did not report '{line}':\n{}",
        run.stderr
    );
}

/// `restir-viewer view --scene builtin:cornell EXTRA… --screenshot-after FRAMES PNG --exit`.
fn run_cornell(png_name: &str, extra: &[&str], frames: &str) -> Run {
    let png = out_path(png_name);
    let png_arg = png.to_str().expect("a UTF-8 path");
    let mut args = vec!["view", "--scene", "builtin:cornell"];
    args.extend_from_slice(extra);
    args.extend(["--screenshot-after", frames, png_arg, "--exit"]);
    run_viewer(&args, &png)
}

#[test]
fn cornell_after_30_frames_shows_a_lit_scene_and_the_panels() {
    let run = run_cornell("cornell.png", &[], "30");
    assert_window_sized(&run, WINDOW);
    let scene = scene_area(&run.png);
    let (mean, deviation) = mean_and_deviation(&scene);
    assert!(
        mean > 40.0,
        "the scene area is dark (mean brightness {mean:.1})"
    );
    assert!(
        deviation > 20.0,
        "the scene area is nearly uniform (deviation {deviation:.1})"
    );
    // Red and green walls: the lit image, not a debug palette.
    assert!(
        fraction(&scene, |p| p[0] > 100 && p[1] < 60 && p[2] < 60) > 0.03,
        "no red wall"
    );
    assert!(
        fraction(&scene, |p| p[1] > 100 && p[0] < 80 && p[2] < 60) > 0.03,
        "no green wall"
    );
    let palette = source_palette();
    assert!(
        fraction(&scene, |p| palette.iter().any(|c| close(p, *c, 2))) < 0.05,
        "the final image looks like the source view"
    );
    assert_panel_drawn(&run.png);
}

#[test]
fn cornell_source_debug_view_shows_the_source_palette() {
    let run = run_cornell("cornell-source.png", &["--debug-view", "source"], "30");
    assert_window_sized(&run, WINDOW);
    let scene = scene_area(&run.png);
    let shares: Vec<f64> = source_palette()
        .iter()
        .map(|c| fraction(&scene, |p| close(p, *c, 2)))
        .collect();
    let total: f64 = shares.iter().sum();
    assert!(
        total > 0.4,
        "only {:.0} % of the scene area is in the source palette (initial, temporal, spatial: {shares:?})",
        total * 100.0
    );
    // After 30 still frames most survivors come from reuse.
    assert!(
        shares[1] > 0.05 && shares[2] > 0.05,
        "temporal and spatial survivors missing: {shares:?}"
    );
    assert_panel_drawn(&run.png);
}

#[test]
fn resizing_and_minimising_while_rendering_does_not_crash() {
    // The script runs first; the screenshot (after at least 3 frames) waits for it.
    let extra = ["--size", "640x400", "--test-resize-script"];
    let run = run_cornell("resized.png", &extra, "3");
    for step in [
        "Resize(240, 160) done",
        "Minimise done",
        "Restore done",
        "Hide done",
        "Show done",
        "Resize(720, 450) done",
    ] {
        assert!(
            run.stderr.contains(&format!("resize script: {step}")),
            "step '{step}' missing:\n{}",
            run.stderr
        );
    }
    // The screenshot comes after the script: the window has its last size.
    assert_window_sized(&run, (720, 450));
}

/// `restir-viewer builtin:NAME` (no `view`, the scene as the only positional argument).
#[test]
fn a_positional_scene_opens_the_viewer() {
    let png = out_path("positional.png");
    let png_arg = png.to_str().expect("a UTF-8 path");
    let run = run_viewer(
        &[
            "builtin:cornell",
            "--screenshot-after",
            "5",
            png_arg,
            "--exit",
        ],
        &png,
    );
    assert_window_sized(&run, WINDOW);
    let scene = scene_area(&run.png);
    assert!(
        fraction(&scene, |p| p[0] > 100 && p[1] < 60 && p[2] < 60) > 0.03,
        "no red wall: the Cornell box did not open"
    );
    assert_panel_drawn(&run.png);
}

/// `restir-viewer --scene … --compare ris` (viewer flags without `view`): restir on the
/// left of the divider, ris on the right, each with its own history. In the source view
/// the left half shows reused survivors, the right half (no reuse) only initial ones.
#[test]
fn the_split_screen_renders_both_configurations_side_by_side() {
    let png = out_path("split.png");
    let png_arg = png.to_str().expect("a UTF-8 path");
    let args = [
        "--scene",
        "builtin:cornell",
        "--compare",
        "ris",
        "--debug-view",
        "source",
        "--screenshot-after",
        "20",
        png_arg,
        "--exit",
    ];
    let run = run_viewer(&args, &png);
    assert_window_sized(&run, WINDOW);
    let half = SCENE_RIGHT / 2;
    // Away from the divider and the labels at its foot.
    let left = region(&run.png, 8..half - 40, 8..WINDOW.1 - 60);
    let right = region(&run.png, half + 40..SCENE_RIGHT - 8, 8..WINDOW.1 - 60);
    let [initial, temporal, spatial] = source_palette();
    let share = |pixels: &[[u8; 3]], c: [u8; 3]| fraction(pixels, |p| close(p, c, 2));
    let reused = |pixels: &[[u8; 3]]| share(pixels, temporal) + share(pixels, spatial);
    assert!(
        reused(&left) > 0.1,
        "A (restir) shows no reused survivors: {:.3}",
        reused(&left)
    );
    assert!(
        share(&right, initial) > 0.4 && reused(&right) < 0.01,
        "B (ris) should show initial survivors only: initial {:.3}, reused {:.3}",
        share(&right, initial),
        reused(&right)
    );
    // The divider: a white line at the middle of the scene area.
    let line = region(&run.png, half - 1..half + 1, 100..WINDOW.1 - 100);
    assert!(
        fraction(&line, |p| brightness(p) > 240.0) > 0.9,
        "no divider at x = {half}"
    );
}

/// `restir-viewer --tour FILE --tour-step 4`: the step's scene opens with the step's view
/// (the source view, concourse, no split screen) and the Tour section beside it.
#[test]
fn a_tour_opens_at_its_step_with_the_steps_view() {
    let png = out_path("tour.png");
    let png_arg = png.to_str().expect("a UTF-8 path");
    let tour = Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/tours/restir.toml");
    let args = [
        "--tour",
        tour.to_str().expect("a UTF-8 path"),
        "--tour-step",
        "4",
        "--screenshot-after",
        "8",
        png_arg,
        "--exit",
    ];
    let run = run_viewer(&args, &png);
    assert_window_sized(&run, WINDOW);
    assert_panel_drawn(&run.png);
    let scene = scene_area(&run.png);
    let [initial, temporal, spatial] = source_palette();
    let share = |c: [u8; 3]| fraction(&scene, |p| close(p, c, 2));
    let palette = share(initial) + share(temporal) + share(spatial);
    assert!(
        palette > 0.5 && share(temporal) + share(spatial) > 0.1,
        "step 4 shows the source view: palette colours cover {palette:.3} of the image"
    );
}
