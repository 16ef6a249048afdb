//! `render`'s flags as clap parses them. Only `job.rs` reads them: it resolves them (with a
//! tour step's) into the `Job` that the rest of `render` works from, so each flag's default,
//! check and error message live in one place.

use std::path::PathBuf;

use clap::Args;

use crate::cli::environment::EnvArgs;
use crate::cli::setup::{PipelineArgs, TimeArgs};

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A .gltf/.glb file or a built-in scene (`builtin:cornell`, see `scenes`); required
    /// unless `--tour` names it.
    #[arg(long)]
    pub scene: Option<String>,
    /// Output size, WxH.
    #[arg(long, default_value = "640x360")]
    pub size: String,
    /// Frames to render.
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// reference | nee | ris | restir [default: restir].
    #[arg(long)]
    pub mode: Option<String>,
    /// Samples per pixel per frame of the reference mode.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Write the average of all frames instead of the last one.
    #[arg(long)]
    pub accumulate: bool,
    /// Seed, `--set`, preset and effect set.
    #[command(flatten)]
    pub pipeline: PipelineArgs,
    /// `--env`, `--env-strength`, `--env-rotation`.
    #[command(flatten)]
    pub env: EnvArgs,
    /// Output image: .exr (linear radiance) or .png (what the display shows).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write statistics as JSON here.
    #[arg(long)]
    pub stats: Option<PathBuf>,
    /// final | source | m | rejection | w | ... | boiling | survivor-change (PNG only; see
    /// docs/src/debug-views.md) [default: final].
    #[arg(long)]
    pub debug_view: Option<String>,
    /// Samples per pixel of the reference the error and bias views compare with.
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u32,
    /// Where that reference is cached (default `$RESTIR_CACHE_DIR`, else target/restir-cache).
    #[arg(long)]
    pub cache_dir: Option<PathBuf>,
    /// Orbit the camera about the scene centre by this many degrees per frame.
    #[arg(long, default_value_t = 0.0)]
    pub orbit: f32,
    /// Jump the camera to a distant viewpoint at this frame (a camera cut).
    #[arg(long)]
    pub cut_at: Option<u32>,
    /// Exposure in EV for PNG output, or `auto` (log-average luminance to middle grey; for
    /// a recording, the first frame's) [default: auto].
    #[arg(long)]
    pub exposure: Option<String>,
    /// Split screen: this configuration left, B right of the middle. B is a mode
    /// (reference, nee, ris, restir: these settings in that mode), optionally +denoise or
    /// +raw (the denoiser on or off on B's side), or a preset .toml file.
    #[arg(long, value_name = "B")]
    pub compare: Option<String>,
    /// Scene time (`--time`, `--fps`).
    #[command(flatten)]
    pub time: TimeArgs,
    /// Write every frame into this folder: frame-00000.png, ... (see --sequence-format).
    #[arg(long, value_name = "DIR")]
    pub out_sequence: Option<PathBuf>,
    /// png (what the display shows) or exr (linear radiance) for --out-sequence.
    #[arg(long, default_value = "png")]
    pub sequence_format: String,
    /// Write every frame as an animated GIF (what the display shows, at the scene's fps).
    #[arg(long, value_name = "FILE.gif")]
    pub gif: Option<PathBuf>,
    /// Record this pixel's history (X,Y from the top left) into --probe-out.
    #[arg(long, value_name = "X,Y", requires = "probe_out")]
    pub probe: Option<String>,
    /// The pixel history as CSV: one row per frame (docs/src/viewer.md, "Pixel history").
    #[arg(long, value_name = "FILE.csv", requires = "probe")]
    pub probe_out: Option<PathBuf>,
    /// Render a step of a guided tour (docs/src/tours.md): its scene, camera, time,
    /// mode, parameters, B, view and exposure; flags given here win over the step's.
    #[arg(long, value_name = "FILE.toml")]
    pub tour: Option<PathBuf>,
    /// The tour's step, from 1.
    #[arg(long, default_value_t = 1, requires = "tour")]
    pub tour_step: usize,
}
