//! The interactive viewer (`restir-viewer` or `restir-viewer view`): a winit window with
//! the renderer's image and egui panels that edit plain state (see `state.rs`).
//!
//! - `app.rs`: winit event loop; `window.rs`: what one window's viewer holds;
//! - `frame.rs`: one frame from UI to present; `actions.rs`: the UI's requests, finished
//!   loads; `clock.rs`: scene time; `tour/`: a guided tour and the teaching tools;
//! - `apply.rs`: state → renderer → state; `gpu_surface.rs`: the swapchain;
//! - `egui_layer.rs`: egui input and drawing; `scene_view.rs`: image, camera input, picking;
//! - `camera.rs`: fly camera; `panels/`: one file per panel; `screenshot.rs`;
//! - `accuracy/`: the live accuracy measurement behind the Accuracy panel;
//! - `scene_loader.rs`: background scene loads; `resize_script.rs`: the resize test.

mod accuracy;
mod actions;
mod app;
mod apply;
mod camera;
mod clock;
mod compare_side;
mod denoised_preset;
mod egui_layer;
mod frame;
mod gpu_surface;
mod panels;
mod resize_script;
mod scene_loader;
mod scene_view;
mod screenshot;
mod split_view;
mod state;
mod tour;
mod window;

use std::path::PathBuf;

use anyhow::{Context, bail};
use clap::Args;
use restir_render::{DebugView, Settings, load_scene};

use crate::cli::setup::{parse_size, settings_from};

pub use restir_render::scene::builtin::DEFAULT_SCENE;
pub const DEFAULT_WINDOW_SIZE: &str = "1280x720";

#[derive(Args, Debug, Default)]
pub struct ViewArgs {
    /// The scene to open: a .gltf/.glb file or `builtin:NAME` (same as --scene).
    #[arg(value_name = "SCENE", conflicts_with = "scene")]
    pub scene_positional: Option<String>,
    /// A .gltf/.glb file or a built-in scene (`builtin:NAME`, see `scenes`)
    /// [default: builtin:concourse].
    #[arg(long)]
    pub scene: Option<String>,
    /// A preset to start from: a TOML file (`name = value` per line) or a built-in name
    /// (`restir-denoised`).
    #[arg(long)]
    pub preset: Option<PathBuf>,
    /// Override a pipeline parameter, `name=value` (see `params`), after the preset;
    /// repeatable (as `render` and `bench` take it).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Window size in logical pixels, WxH [default: 1280x720].
    #[arg(long)]
    pub size: Option<String>,
    /// final | source | m | rejection | w | ... | gi-jacobian | pt-length | pt-reconnection |
    /// pt-failure | pt-jacobian | boiling | survivor-change (docs/src/debug-views.md)
    /// [default: final].
    #[arg(long)]
    pub debug_view: Option<String>,
    /// After N rendered frames, write a PNG of the whole window (image and panels) to FILE.
    #[arg(long, num_args = 2, value_names = ["N", "FILE.png"])]
    pub screenshot_after: Vec<String>,
    /// Start with the split screen on: this configuration left, B right (a mode, optionally
    /// +denoise or +raw, restir-denoised or a preset .toml file; the Compare section
    /// changes it).
    #[arg(long, value_name = "B")]
    pub compare: Option<String>,
    /// Start a guided tour (docs/src/tours.md): its first step's scene, camera, mode,
    /// parameters, split screen and view; PageDown / PageUp or the Tour section walk on.
    #[arg(long, value_name = "FILE.toml")]
    pub tour: Option<PathBuf>,
    /// The tour's step to start at, from 1.
    #[arg(long, default_value_t = 1, requires = "tour")]
    pub tour_step: usize,
    /// Exit (status 0) once the --screenshot-after PNG is written.
    #[arg(long, requires = "screenshot_after")]
    pub exit: bool,
    /// Test hook: resize, minimise and restore the window while rendering.
    #[arg(long, hide = true)]
    pub test_resize_script: bool,
    /// `--env`, `--env-strength`, `--env-rotation`.
    #[command(flatten)]
    pub env: crate::cli::environment::EnvArgs,
}

/// The validated command line: everything the window needs before it opens.
pub struct Launch {
    pub scene_spec: String,
    pub settings: Settings,
    /// `--preset`: also where the Pipeline panel saves and loads by default.
    pub preset: Option<PathBuf>,
    pub window_size: (u32, u32),
    pub debug_view: DebugView,
    pub screenshot_after: Option<(u64, PathBuf)>,
    pub compare: Option<String>,
    pub exit: bool,
    pub resize_script: bool,
    /// The environment of `--env` (or the tour's first step), loaded (a bad file is a
    /// command-line error), and what named it.
    pub environment: Option<std::sync::Arc<restir_render::Environment>>,
    pub env_spec: Option<String>,
    /// `--tour`, read and checked, and the step to start at (0-based).
    pub tour: Option<(crate::tour::Tour, usize)>,
}

impl Launch {
    fn from_args(args: ViewArgs) -> anyhow::Result<Launch> {
        let debug_view_name = args.debug_view.as_deref().unwrap_or("final");
        let debug_view = DebugView::from_name(debug_view_name).with_context(|| {
            let names: Vec<_> = DebugView::ALL.iter().map(|v| v.name()).collect();
            format!(
                "--debug-view '{debug_view_name}': expected one of {}",
                names.join(", ")
            )
        })?;
        let screenshot_after = match args.screenshot_after.as_slice() {
            [] => None,
            [n, file] => {
                let n: u64 = n.parse().ok().filter(|n| *n >= 1).with_context(|| {
                    format!("--screenshot-after '{n}': expected a frame count of at least 1")
                })?;
                if !file.to_ascii_lowercase().ends_with(".png") {
                    bail!("--screenshot-after: '{file}' is not a .png file");
                }
                Some((n, PathBuf::from(file)))
            }
            _ => bail!("--screenshot-after takes a frame count and a file: N FILE.png"),
        };
        let tour = args
            .tour
            .as_deref()
            .map(crate::tour::Tour::load)
            .transpose()?;
        let first = tour.as_ref().map(|t| t.step(args.tour_step)).transpose()?;
        let mut env = args.env.clone();
        if env.env.is_none() {
            env.env = first.and_then(|s| s.env.clone());
        }
        Ok(Launch {
            scene_spec: args
                .scene
                .or(args.scene_positional)
                .or_else(|| first.map(|s| s.scene.clone()))
                .unwrap_or_else(|| DEFAULT_SCENE.to_string()),
            settings: settings_from(args.preset.as_ref(), &args.set)?,
            preset: args.preset,
            window_size: parse_size(args.size.as_deref().unwrap_or(DEFAULT_WINDOW_SIZE))?,
            debug_view,
            screenshot_after,
            compare: args.compare,
            exit: args.exit,
            resize_script: args.test_resize_script,
            environment: env.load()?,
            env_spec: env.env,
            tour: tour.map(|t| (t, args.tour_step - 1)),
        })
    }
}

/// Opens the viewer and runs until the window closes (or `--exit`).
pub fn run(args: ViewArgs) -> anyhow::Result<()> {
    let launch = Launch::from_args(args)?;
    // Load before opening a window: a bad --scene is a command-line error.
    let mut scene = load_scene(&launch.scene_spec)?;
    scene.environment = launch.environment.clone();
    let event_loop = winit::event_loop::EventLoop::new()
        .context("cannot open a window: no display (set DISPLAY or WAYLAND_DISPLAY, or use `render` headless)")?;
    let mut app = app::App::new(launch, scene);
    event_loop
        .run_app(&mut app)
        .context("the window's event loop failed")?;
    match app.error.take() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_are_checked_before_a_window_opens() {
        let ok = Launch::from_args(ViewArgs {
            screenshot_after: vec!["30".into(), "f.png".into()],
            ..Default::default()
        })
        .unwrap();
        assert_eq!(ok.scene_spec, DEFAULT_SCENE);
        assert_eq!(ok.window_size, (1280, 720));
        assert_eq!(ok.screenshot_after, Some((30, PathBuf::from("f.png"))));
        let err = |args: ViewArgs| {
            Launch::from_args(args)
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default()
        };
        assert!(
            err(ViewArgs {
                debug_view: Some("nope".into()),
                ..Default::default()
            })
            .contains("--debug-view")
        );
        assert!(
            err(ViewArgs {
                screenshot_after: vec!["0".into(), "f.png".into()],
                ..Default::default()
            })
            .contains("at least 1")
        );
        assert!(
            err(ViewArgs {
                screenshot_after: vec!["3".into(), "f.jpg".into()],
                ..Default::default()
            })
            .contains(".png")
        );
        assert!(
            err(ViewArgs {
                size: Some("0x5".into()),
                ..Default::default()
            })
            .contains("--size")
        );
    }

    /// `view --set` overrides a parameter as `render --set` does; a bad one is a
    /// command-line error naming `--set`, before a window opens.
    #[test]
    fn set_overrides_a_parameter() {
        let launch = |set: &[&str]| {
            Launch::from_args(ViewArgs {
                set: set.iter().map(|s| s.to_string()).collect(),
                ..Default::default()
            })
        };
        assert!(launch(&[]).unwrap().settings.jitter);
        assert!(!launch(&["jitter=false"]).unwrap().settings.jitter);
        for bad in ["jitter=maybe", "no_such_parameter=1"] {
            let err = launch(&[bad]).err().map(|e| e.to_string());
            assert!(
                err.as_deref().is_some_and(|e| e.contains("--set")),
                "{bad}: {err:?}"
            );
        }
    }
}
