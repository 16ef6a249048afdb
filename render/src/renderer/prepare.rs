//! Getting a new scene ready off the window thread, so the old scene keeps drawing until
//! the new one can draw at once: its upload (BVH, light table, buffers, acceleration
//! structures) on the renderer's own device, then its first frame's pipelines compiled and
//! run once on a sibling device (a second device on the same adapter). The moving
//! camera's variant goes on warming there after the scene is handed over.
//!
//! Why a sibling: lavapipe compiles a shader when it is first dispatched, on the device's
//! queue thread, so a warm-up on the renderer's own device would hold up the old scene's
//! frames behind it for the whole compile (minutes for a cold StainedGlassLamp). On a
//! sibling the compile runs beside them, and the driver's on-disk shader cache (Mesa's,
//! and most GPU drivers') hands the compiled code to the renderer's device when the new
//! scene's first frame asks for it.

use crate::effects::{EffectSet, SceneFeatures};
use crate::gpu::Gpu;
use crate::gpu_scene::GpuScene;
use crate::gpu_scene::layout::SceneLayouts;
use crate::load_phases::{LoadEvent, LoadPhases, Watcher};
use crate::scene::{Camera, Scene};
use crate::settings::Settings;
use crate::view::{Mode, ViewSettings};

use super::{PipelineCompile, Renderer};

/// The warm-up's output size: the pipelines do not depend on it, and a tiny frame keeps
/// the run itself negligible beside the compile.
const WARM_UP_SIZE: u32 = 8;

/// What a new scene's preparation needs from the renderer: its device, its scene layouts
/// and what decides the first frames' pipelines (mode, settings, view, effects). `Send`,
/// so a loader thread can own it.
#[derive(Clone)]
pub struct ScenePreparer {
    gpu: Gpu,
    layouts: SceneLayouts,
    mode: Mode,
    settings: Settings,
    view: ViewSettings,
    forced_effects: Option<EffectSet>,
    /// Whether to warm the pipelines on a sibling device (off: upload only).
    warm_up: bool,
}

/// A scene uploaded to the renderer's device, ready for `Renderer::set_prepared_scene`.
pub struct PreparedScene {
    scene: GpuScene,
    features: SceneFeatures,
    camera: Camera,
    warmed: Vec<PipelineCompile>,
    /// The moving camera's variant, still warming on the sibling (dropped: it finishes on
    /// its own).
    warming: Option<std::thread::JoinHandle<Vec<PipelineCompile>>>,
}

impl PreparedScene {
    /// The phases so far: the loader's, the upload's and the warm-up's.
    pub fn load_phases(&self) -> &LoadPhases {
        &self.scene.info.load
    }

    /// The pipelines the warm-up compiled and ran (empty without a warm-up): the still
    /// camera's, and the moving camera's once `finish_warm_up` has waited for them.
    pub fn warmed(&self) -> &[PipelineCompile] {
        &self.warmed
    }

    /// Waits for the moving camera's warm-up (the viewer does not: it shows the scene as
    /// soon as the still camera's pipelines are warm).
    pub fn finish_warm_up(&mut self) {
        if let Some(rest) = self.warming.take().and_then(|h| h.join().ok()) {
            self.warmed.extend(rest);
        }
    }
}

impl Renderer {
    /// A preparer for scenes that this renderer, as it is set up now, will show next.
    pub fn preparer(&self) -> ScenePreparer {
        ScenePreparer {
            gpu: self.gpu.clone(),
            layouts: self.layouts.scene.clone(),
            mode: self.mode,
            settings: self.settings.clone(),
            view: self.view,
            forced_effects: self.pipelines.forced_effects.clone(),
            warm_up: true,
        }
    }

    /// Shows a prepared scene (history and accumulation restart; the camera moves to the
    /// new scene's camera). Nothing here is slow: the preparation did the work.
    pub fn set_prepared_scene(&mut self, prepared: PreparedScene) {
        self.scene = prepared.scene;
        self.features = prepared.features;
        // The light BVH is the old scene's: the next frame that samples with it builds anew.
        self.buffers.light_sampler.forget_scene();
        // The effect set is cached while settings stay the same: the new scene's features
        // decide it afresh (textures, glass, an environment).
        self.pipelines.last_effects = None;
        self.camera = prepared.camera;
        self.pipelines.first_frame_pipelines = None;
        self.pipelines.first_frame = None;
        // The resolve group binds the scene's previous-triangle buffer.
        self.bind_groups.clear();
        self.invalidate_history();
        self.reset_accumulation();
    }
}

impl ScenePreparer {
    /// Without the warm-up: the upload only (the first frame compiles, as before).
    pub fn without_warm_up(mut self) -> ScenePreparer {
        self.warm_up = false;
        self
    }

    /// Uploads `scene` and warms its pipelines, telling `watch` as each phase begins and
    /// ends. Only the upload can fail; a warm-up that cannot run is recorded and skipped
    /// (the first frame then compiles, slower but correct).
    pub fn prepare(&self, scene: &Scene, watch: Watcher) -> anyhow::Result<PreparedScene> {
        watch(LoadEvent::Started("upload"));
        let mut gpu_scene = GpuScene::upload(&self.gpu, scene, &self.layouts)?;
        for phase in &gpu_scene.info.load.phases[scene.load_phases.phases.len()..] {
            watch(LoadEvent::Finished(phase));
        }
        let (mut warmed, mut warming) = (Vec::new(), None);
        if self.warm_up {
            let start = std::time::Instant::now();
            watch(LoadEvent::Started("warm-up"));
            let detail = match self.warm_up(scene) {
                Ok((compiles, rest)) => {
                    let sum: f64 = compiles.iter().map(|c| c.ms).sum();
                    (warmed, warming) = (compiles, Some(rest));
                    format!(
                        "{} pipelines compiled and run once on a second device \
                         ({sum:.0} ms creating them)",
                        warmed.len()
                    )
                }
                Err(e) => {
                    log::warn!("pipeline warm-up skipped: {e:#}");
                    format!("skipped ({e:#}): the first frame compiles instead")
                }
            };
            let ms = start.elapsed().as_secs_f64() * 1e3;
            gpu_scene.info.load.record(watch, "warm-up", ms, detail);
        }
        Ok(PreparedScene {
            scene: gpu_scene,
            features: SceneFeatures::of(scene),
            camera: scene.default_camera(),
            warmed,
            warming,
        })
    }

    /// A tiny frame on a sibling device: returns what it compiled, and a thread that goes
    /// on with a frame from a nudged camera (a moving camera compiles the motion-vector
    /// variant, about as long again) and returns what that compiled.
    #[allow(clippy::type_complexity)]
    fn warm_up(
        &self,
        scene: &Scene,
    ) -> anyhow::Result<(
        Vec<PipelineCompile>,
        std::thread::JoinHandle<Vec<PipelineCompile>>,
    )> {
        let mut warm = self.sibling_renderer(scene)?;
        warm.render_frame()?;
        warm.gpu().wait_idle();
        warm.gpu().check()?;
        let still = warm.pipeline_compiles().to_vec();
        let moving = std::thread::spawn(move || {
            let mut nudged = warm.camera();
            nudged.position += nudged.forward() * (1e-3 * warm.scene_scale());
            warm.set_camera(nudged);
            let before = warm.pipeline_compiles().len();
            if let Err(e) = warm.render_frame() {
                log::warn!("the moving camera's warm-up failed: {e}");
            }
            warm.gpu().wait_idle();
            warm.pipeline_compiles()[before..].to_vec()
        });
        Ok((still, moving))
    }

    /// Compiles and runs the pipelines of `effects` for `scene` on a sibling device, in a
    /// thread: two tiny frames, the second with history (temporal passes run from the
    /// second frame on). The viewer renders again once it is done: its own device then
    /// finds the shaders in the driver's cache.
    pub fn warm_effects(
        mut self,
        scene: std::sync::Arc<Scene>,
        effects: EffectSet,
    ) -> std::thread::JoinHandle<Result<Vec<PipelineCompile>, String>> {
        self.forced_effects = Some(effects);
        std::thread::spawn(move || {
            let run = || -> anyhow::Result<Vec<PipelineCompile>> {
                let mut warm = self.sibling_renderer(&scene)?;
                warm.render_frame()?;
                warm.render_frame()?;
                warm.gpu().wait_idle();
                warm.gpu().check()?;
                Ok(warm.pipeline_compiles().to_vec())
            };
            run().map_err(|e| format!("{e:#}"))
        })
    }

    /// A tiny renderer of `scene` on a sibling device, set up as this preparer's renderer.
    fn sibling_renderer(&self, scene: &Scene) -> anyhow::Result<Renderer> {
        let mut warm = Renderer::new(
            self.gpu.sibling()?,
            scene,
            WARM_UP_SIZE,
            WARM_UP_SIZE,
            self.settings.clone(),
        )?;
        warm.set_mode(self.mode);
        warm.set_view(self.view);
        warm.force_effects(self.forced_effects.clone());
        Ok(warm)
    }
}
