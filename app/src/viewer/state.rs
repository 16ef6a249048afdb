//! Everything the panels edit, as plain data. The UI never touches the GPU: it edits
//! these structs and queues `Action`s; `apply.rs` hands them to the renderer each frame.
//! That keeps every panel testable without a device (see `panels/tests/`).

use std::collections::VecDeque;

use restir_render::effects::EffectSet;
use restir_render::gpu_scene::SceneInfo;
use restir_render::renderer::PixelInspection;
use restir_render::stats::{FrameCounters, FrameReport};
use restir_render::{Mode, Settings, ViewSettings};

use super::accuracy::AccuracyState;
use super::camera::CameraState;
use super::tour::state::TourState;
use crate::compare::CompareTarget;
use crate::probe::PixelHistory;

/// Something the UI asks for that needs the renderer or the file system.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Replace the scene (`builtin:NAME` or a glTF path); on failure the old one stays.
    LoadScene(String),
    /// Load an environment (.hdr, .exr or `builtin:sky`) in the background; `None` removes
    /// it. A failed load keeps the environment there was.
    LoadEnvironment(Option<String>),
    /// Write a screenshot (PNG of the window and of the image, EXR of the radiance).
    Screenshot,
    /// Set the exposure from the current frame's log-average luminance.
    AutoExposure,
    /// Restart the running average.
    ResetAccumulation,
    /// Measure the exposure automatically once a few frames of what is now set rendered
    /// (a tour step without an exposure of its own).
    AutoExposureSoon,
    /// Load a tour step's scene with its environment (or none), in the background.
    LoadTourScene {
        scene: String,
        env: Option<String>,
    },
    /// Write the inspected pixel's history as CSV (Pixel inspector).
    ExportPixelHistory,
    /// Start or stop recording every rendered frame (View section).
    StartRecording,
    StopRecording,
}

/// How the rendered image maps onto the window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplayOptions {
    /// The renderer renders at (scene area in physical pixels) × this, shown scaled up.
    pub render_scale: f32,
    /// Bilinear upscaling; off shows each rendered pixel as a crisp block (the inspector's
    /// pixel is then visible as one block).
    pub smooth: bool,
}

impl DisplayOptions {
    pub const SCALE_RANGE: std::ops::RangeInclusive<f32> = 0.1..=2.0;

    /// A CPU adapter (lavapipe) renders ~0.5 Mpixel/s: a quarter of the window keeps it
    /// interactive. Real GPUs render at window size.
    pub fn for_adapter(is_cpu: bool) -> DisplayOptions {
        DisplayOptions {
            render_scale: if is_cpu { 0.25 } else { 1.0 },
            smooth: false,
        }
    }
}

/// The pixel inspector's selection and what came back for it.
#[derive(Clone, Debug, PartialEq)]
pub struct InspectorState {
    /// The inspected pixel in render-target coordinates.
    pub pixel: Option<(u32, u32)>,
    /// While frozen no new frame is rendered (camera and settings wait).
    pub frozen: bool,
    /// Render exactly one frame while frozen.
    pub step: bool,
    /// The latest inspection that came back for `pixel`.
    pub last: Option<PixelInspection>,
    /// A pixel was just picked: the side panel opens the inspector and scrolls to it once.
    pub reveal: bool,
    /// The pixel's last N frames (the strip chart), and where its CSV export goes.
    pub history: PixelHistory,
    pub history_path: String,
    /// The export's result (the file written, or why not).
    pub history_message: Option<String>,
}

impl Default for InspectorState {
    fn default() -> Self {
        InspectorState {
            pixel: None,
            frozen: false,
            step: false,
            last: None,
            reveal: false,
            history: PixelHistory::new(PixelHistory::DEFAULT_FRAMES),
            history_path: "pixel-history.csv".to_string(),
            history_message: None,
        }
    }
}

/// The sliding window of frame reports the Stats panel summarises.
#[derive(Clone, Debug, Default)]
pub struct StatsHistory {
    pub reports: VecDeque<FrameReport>,
    /// Wall-clock milliseconds between presented frames (CPU + GPU, what the user feels).
    pub frame_ms: VecDeque<f64>,
    /// Every counter summed since the scene loaded: a frame with non-finite values must
    /// stay visible in the Stats panel after it leaves the summary window.
    pub since_load: FrameCounters,
}

impl StatsHistory {
    /// Frames summarised (about two seconds at 30 fps).
    pub const WINDOW: usize = 64;
    /// Frames kept for the history plot.
    pub const HISTORY: usize = 240;

    pub fn push_report(&mut self, report: FrameReport) {
        self.since_load.add(&report.counters);
        self.reports.push_back(report);
        while self.reports.len() > Self::HISTORY {
            self.reports.pop_front();
        }
    }

    pub fn push_frame_ms(&mut self, ms: f64) {
        self.frame_ms.push_back(ms);
        while self.frame_ms.len() > Self::HISTORY {
            self.frame_ms.pop_front();
        }
    }

    /// The most recent `WINDOW` reports, oldest first.
    pub fn window(&self) -> Vec<FrameReport> {
        let skip = self.reports.len().saturating_sub(Self::WINDOW);
        self.reports.iter().skip(skip).cloned().collect()
    }

    pub fn clear(&mut self) {
        self.reports.clear();
        self.frame_ms.clear();
        self.since_load = FrameCounters::default();
    }
}

/// Scene time (the Time section). The viewer advances `time` while playing and poses
/// the scene at it before each rendered frame.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeState {
    pub playing: bool,
    /// Seconds, in [0, duration].
    pub time: f32,
    /// Scene seconds per wall-clock second.
    pub speed: f32,
    pub looping: bool,
    /// Advance one frame (1/30 s) on the next rendered frame.
    pub step: bool,
    /// Frame-locked: while playing, time advances speed/F per rendered frame (as
    /// `render --fps F`) instead of with the wall clock, so a lag counts the same frames
    /// on any machine; `None` follows the wall clock.
    pub frame_fps: Option<f32>,
    /// The loop length; 0 for a static scene.
    pub duration: f32,
    /// The scene's clips, and the one playing alone (`None`: all together).
    pub clips: Vec<String>,
    pub clip: Option<usize>,
}

impl Default for TimeState {
    fn default() -> Self {
        Self {
            playing: true,
            time: 0.0,
            speed: 1.0,
            looping: true,
            step: false,
            frame_fps: None,
            duration: 0.0,
            clips: Vec::new(),
            clip: None,
        }
    }
}

impl TimeState {
    pub const SPEED_RANGE: std::ops::RangeInclusive<f32> = 0.05..=4.0;
    /// One step of `Step` (and of a frozen inspector's N while playing).
    pub const STEP: f32 = 1.0 / 30.0;

    /// The next time after `dt` wall-clock seconds: playing advances by dt × speed, a step
    /// by one frame; the end wraps (loop) or stops playback.
    pub fn advance(&mut self, dt: f32) {
        if self.duration <= 0.0 {
            return;
        }
        if std::mem::take(&mut self.step) {
            self.time += Self::STEP;
        } else if self.playing {
            let dt = match self.frame_fps {
                Some(fps) if fps > 0.0 => 1.0 / fps,
                _ => dt.clamp(0.0, 0.1),
            };
            self.time += dt * self.speed;
        }
        if self.looping {
            self.time = self.time.rem_euclid(self.duration);
        } else if self.time >= self.duration {
            self.time = self.duration;
            self.playing = false;
        }
        if !self.time.is_finite() {
            self.time = 0.0;
        }
    }
}

/// What the Scene panel shows and edits.
#[derive(Clone, Debug, Default)]
pub struct SceneState {
    /// What the current scene was loaded from (`builtin:NAME` or a path).
    pub spec: String,
    pub info: Option<SceneInfo>,
    pub effects: Option<EffectSet>,
    pub passes: Vec<&'static str>,
    /// A scene being loaded in the background.
    pub loading: Option<String>,
    /// Where that load is (its phase and how far), for the progress bar.
    pub progress: super::scene_loader::LoadProgress,
    /// The viewer's first frame waits for its pipelines to warm (`frame.rs`; `Startup` in
    /// `window.rs`).
    pub first_frame_waits: bool,
    /// A change's new pipelines are warming beside the window (`Viewer::pipelines_ready`).
    pub pipelines_warming: bool,
    /// The current scene's load phases, file to first frame (`Renderer::load_phases`).
    pub load: restir_render::load_phases::LoadPhases,
    /// The last load error (the old scene is kept).
    pub error: Option<String>,
    /// The path field of the Open row.
    pub open_path: String,
    /// The last environment load error (the previous environment is kept).
    pub env_error: Option<String>,
    /// The path field of the environment's Open row.
    pub env_open_path: String,
}

/// The split-screen comparison (Compare section): configuration B beside the current one.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareState {
    pub enabled: bool,
    /// B: `reference`, `nee`, `ris`, `restir` or a preset file (see `compare.rs`).
    pub spec: String,
    /// Where the divider is, as a fraction of the image width.
    pub divider: f32,
    /// B on the left instead of the right (X flips).
    pub flipped: bool,
    /// Why B could not be set up (the comparison is off meanwhile).
    pub error: Option<String>,
    /// Per-frame luma RMSE of each side against the Accuracy reference, when there is one.
    pub errors: Option<(f64, f64)>,
    /// B as a tour step gave it (an inline preset); `spec` is then its label, and typing
    /// another spec drops it.
    pub target: Option<CompareTarget>,
}

impl Default for CompareState {
    fn default() -> Self {
        CompareState {
            enabled: false,
            spec: "ris".to_string(),
            divider: 0.5,
            flipped: false,
            error: None,
            errors: None,
            target: None,
        }
    }
}

/// What the denoiser's companion preset replaced, restored when the denoiser goes off.
#[derive(Clone, Debug)]
pub struct BeforePreset {
    pub settings: Settings,
    pub mode: Mode,
    pub compare: CompareState,
}

/// The denoiser's companion preset (`denoised_preset.rs`): whether switching the denoiser
/// on applies it, and what to restore when it is switched off.
#[derive(Clone, Debug)]
pub struct DenoisedPreset {
    pub follow: bool,
    pub saved: Option<BeforePreset>,
}

impl Default for DenoisedPreset {
    fn default() -> Self {
        DenoisedPreset {
            follow: true,
            saved: None,
        }
    }
}

impl DenoisedPreset {
    /// Whether the switch applied the preset and has not undone it yet.
    pub fn is_on(&self) -> bool {
        self.saved.is_some()
    }
}

/// The View section's Record toggle: every rendered frame into a folder and/or a GIF.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordState {
    pub active: bool,
    /// Where the frames go (a new `recording-N` folder inside it per recording).
    pub dir: String,
    /// PNG frames (what the display shows) or EXR (linear); none: only the GIF.
    pub sequence: Option<crate::recording::SequenceFormat>,
    pub gif: bool,
    /// What the last recording wrote, or why it stopped.
    pub message: Option<String>,
}

impl Default for RecordState {
    fn default() -> Self {
        RecordState {
            active: false,
            dir: ".".to_string(),
            sequence: Some(crate::recording::SequenceFormat::Png),
            gif: true,
            message: None,
        }
    }
}

/// Facts about the device, for the Stats panel.
#[derive(Clone, Debug, Default)]
pub struct DeviceInfo {
    pub adapter: String,
    /// The driver and its version ("Mesa 25.0.7…" on lavapipe).
    pub driver: String,
    pub is_cpu: bool,
    pub timing: String,
    /// Whether the device has hardware ray queries (`ray_backend=ray-query` can run).
    pub ray_query: bool,
    /// What traced the last frame's rays.
    pub ray_backend: Option<restir_render::tracing::RayBackend>,
}

/// The whole editable state of the viewer.
#[derive(Clone, Debug)]
pub struct ViewerState {
    pub settings: Settings,
    pub mode: Mode,
    pub view: ViewSettings,
    pub display: DisplayOptions,
    pub camera: CameraState,
    pub inspector: InspectorState,
    pub stats: StatsHistory,
    pub accuracy: AccuracyState,
    pub scene: SceneState,
    pub compare: CompareState,
    pub time: TimeState,
    pub device: DeviceInfo,
    /// The preset file the Pipeline panel saves to and loads from.
    pub preset_path: String,
    /// Preset load/save result (error or confirmation).
    pub preset_message: Option<String>,
    /// The denoiser's companion preset (`denoised_preset.rs`).
    pub denoised_preset: DenoisedPreset,
    /// Where screenshots go.
    pub screenshot_dir: String,
    /// The last screenshot's files, or why it failed.
    pub screenshot_message: Option<String>,
    /// Whether the side panel is shown (H toggles).
    pub panel_open: bool,
    /// A guided tour (`--tour`), its current step and live numbers.
    pub tour: Option<TourState>,
    pub recording: RecordState,
    /// Render-target size and accumulated frames, for display.
    pub render_size: (u32, u32),
    pub accumulated_frames: u32,
    /// Frames in the boiling views' temporal window (0 while no such view is shown).
    pub window_frames: u32,
    /// `denoise_auto_depth`'s choice, once its probe has run (the Stats panel shows it).
    pub denoise_depth: Option<restir_render::denoise::depth_probe::DepthChoice>,
    pub actions: Vec<Action>,
}

impl ViewerState {
    pub fn new(settings: Settings, camera: CameraState, display: DisplayOptions) -> ViewerState {
        ViewerState {
            settings,
            mode: Mode::Restir,
            view: ViewSettings::default(),
            display,
            camera,
            inspector: InspectorState::default(),
            stats: StatsHistory::default(),
            // The cheaper reference until the viewer knows its device.
            accuracy: AccuracyState::new(true),
            scene: SceneState::default(),
            compare: CompareState::default(),
            time: TimeState::default(),
            device: DeviceInfo::default(),
            preset_path: "preset.toml".to_string(),
            preset_message: None,
            denoised_preset: Default::default(),
            screenshot_dir: ".".to_string(),
            screenshot_message: None,
            panel_open: true,
            tour: None,
            recording: RecordState::default(),
            render_size: (0, 0),
            accumulated_frames: 0,
            window_frames: 0,
            denoise_depth: None,
            actions: Vec::new(),
        }
    }

    /// Queues an action once (a button clicked on two passes of one frame is one click).
    pub fn request(&mut self, action: Action) {
        if !self.actions.contains(&action) {
            self.actions.push(action);
        }
    }
}
