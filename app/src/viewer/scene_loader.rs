//! Loads scenes and environments on a background thread and prepares them there (glTF
//! import, an HDRI's decode and distribution, the BVH, the upload and the first frames'
//! pipelines, warmed on a second device: `restir_render::ScenePreparer`), so the window
//! keeps drawing the old scene until the new one can draw at once.

use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::sync::{Arc, Mutex};

use restir_render::load_phases::LoadEvent;

use restir_render::{
    Environment, PreparedScene, Scene, ScenePreparer, load_environment, load_scene_watched,
};

/// A scene as loaded and uploaded (boxed: a scene is a few hundred bytes of handles).
pub struct Ready {
    pub scene: Box<Scene>,
    pub prepared: PreparedScene,
}

/// What a background load produced.
pub enum Loaded {
    /// A new scene under the environment it was started with.
    Scene(Ready),
    /// The shown scene under a new environment (the camera stays).
    Environment(Ready),
    /// A tour step's scene with the step's environment (or none) attached.
    SceneWithEnvironment(Ready),
    /// The shown scene prepared again: the viewer's start (`start_warm_up`).
    Warmed(PreparedScene),
}

/// Whether a load request names an environment (by extension, or `builtin:sky`).
pub fn is_environment_spec(spec: &str) -> bool {
    let lower = spec.to_ascii_lowercase();
    lower.ends_with(".hdr")
        || lower.ends_with(".exr")
        || spec == restir_render::environment::BUILTIN_SKY
}

/// `scene` under `env` (or none); a new environment keeps the old one's strength and
/// rotation (the command line's), so swapping skies compares like with like.
pub fn with_environment(scene: &Scene, env: Option<Environment>) -> Result<Scene, String> {
    let old = scene.environment.as_deref();
    let env = match env {
        Some(e) => Some(std::sync::Arc::new(e.with_strength_and_rotation(
            old.map_or(1.0, |o| o.strength),
            old.map_or(0.0, |o| o.rotation_deg),
        )?)),
        None => None,
    };
    Ok(Scene {
        environment: env,
        ..scene.clone()
    })
}

/// Where a background load is: the phase running and, for a phase that counts (images),
/// how far it is. The loader thread writes it, the Scene panel's progress bar reads it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadProgress {
    pub phase: String,
    /// Done of total within the phase, 0..=1 (`None`: the phase does not count).
    pub fraction: Option<f32>,
    /// Phases finished so far.
    pub finished: usize,
}

impl LoadProgress {
    fn hear(&mut self, e: LoadEvent) {
        match e {
            LoadEvent::Started(name) => {
                self.phase = name.to_string();
                self.fraction = None;
            }
            LoadEvent::Progress { done, total, .. } => {
                self.fraction = Some(done as f32 / total.max(1) as f32);
            }
            LoadEvent::Finished(_) => self.finished += 1,
        }
    }
}

#[derive(Default)]
pub struct SceneLoader {
    pending: Option<(String, Receiver<Result<Loaded, String>>)>,
    progress: Arc<Mutex<LoadProgress>>,
}

/// Tells `progress` of each phase as it begins, counts and ends.
fn listener(progress: &Mutex<LoadProgress>) -> impl Fn(LoadEvent) + Sync + '_ {
    |e: LoadEvent| {
        if let Ok(mut p) = progress.lock() {
            p.hear(e);
        }
    }
}

/// `load_scene`, telling `progress`.
fn load_scene_with(spec: &str, progress: &Mutex<LoadProgress>) -> Result<Scene, String> {
    load_scene_watched(spec, &listener(progress)).map_err(|e| e.to_string())
}

/// Uploads `scene` and warms its pipelines, telling `progress`.
fn prepare(
    scene: Scene,
    preparer: &ScenePreparer,
    progress: &Mutex<LoadProgress>,
) -> Result<Ready, String> {
    let prepared = preparer
        .prepare(&scene, &listener(progress))
        .map_err(|e| format!("{e:#}"))?;
    Ok(Ready {
        scene: Box::new(scene),
        prepared,
    })
}

impl SceneLoader {
    /// Starts loading the scene `spec` under `environment` (the shown scene's); a load
    /// already running is abandoned (its result dropped).
    pub fn start(
        &mut self,
        spec: String,
        environment: Option<Arc<Environment>>,
        preparer: ScenePreparer,
    ) {
        let progress = self.fresh_progress();
        self.start_with(spec, move |s| {
            let mut scene = load_scene_with(s, &progress)?;
            scene.environment = environment;
            prepare(scene, &preparer, &progress).map(Loaded::Scene)
        });
    }

    /// Prepares the shown scene `spec` again (the viewer's start: its first frame waits for
    /// the warm-up, so the window draws its panels and the progress meanwhile instead of
    /// freezing while a CPU driver compiles).
    pub fn start_warm_up(&mut self, spec: String, shown: Arc<Scene>, preparer: ScenePreparer) {
        let progress = self.fresh_progress();
        self.start_with(spec, move |_| {
            preparer
                .prepare(&shown, &listener(&progress))
                .map(Loaded::Warmed)
                .map_err(|e| format!("{e:#}"))
        });
    }

    /// Starts loading the environment `spec` (.hdr, .exr or `builtin:sky`) for `shown`.
    pub fn start_environment(&mut self, spec: String, shown: Arc<Scene>, preparer: ScenePreparer) {
        let progress = self.fresh_progress();
        self.start_with(spec, move |s| {
            let env = load_environment(s).map_err(|e| e.to_string())?;
            let scene = with_environment(&shown, Some(env))?;
            prepare(scene, &preparer, &progress).map(Loaded::Environment)
        });
    }

    /// Starts loading a tour step's scene and its environment (`None`: none) together:
    /// one load, so neither abandons the other.
    pub fn start_with_environment(
        &mut self,
        spec: String,
        env: Option<String>,
        preparer: ScenePreparer,
    ) {
        let progress = self.fresh_progress();
        let job = move |s: &str| {
            let mut scene = load_scene_with(s, &progress)?;
            if let Some(env) = &env {
                let env = load_environment(env).map_err(|e| e.to_string())?;
                scene.environment = Some(Arc::new(env));
            }
            prepare(scene, &preparer, &progress).map(Loaded::SceneWithEnvironment)
        };
        self.start_with(spec, job);
    }

    fn start_with(
        &mut self,
        spec: String,
        load: impl FnOnce(&str) -> Result<Loaded, String> + Send + 'static,
    ) {
        let (tx, rx) = channel();
        let job = spec.clone();
        std::thread::spawn(move || {
            let _ = tx.send(load(&job));
        });
        self.pending = Some((spec, rx));
    }

    /// A new progress record for a new load (an abandoned load keeps writing its own).
    fn fresh_progress(&mut self) -> Arc<Mutex<LoadProgress>> {
        self.progress = Arc::default();
        self.progress.clone()
    }

    /// Where the running load is (default when none runs or it has not begun).
    pub fn progress(&self) -> LoadProgress {
        match &self.pending {
            Some(_) => self.progress.lock().map(|p| p.clone()).unwrap_or_default(),
            None => LoadProgress::default(),
        }
    }

    pub fn loading(&self) -> Option<&str> {
        self.pending.as_ref().map(|(spec, _)| spec.as_str())
    }

    /// The finished load, if it has finished.
    pub fn poll(&mut self) -> Option<(String, Result<Loaded, String>)> {
        let (spec, rx) = self.pending.as_ref()?;
        let result = match rx.try_recv() {
            Ok(result) => result,
            Err(TryRecvError::Empty) => return None,
            Err(TryRecvError::Disconnected) => Err("the loader stopped unexpectedly".to_string()),
        };
        let spec = spec.clone();
        self.pending = None;
        Some((spec, result))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use restir_render::{Gpu, Renderer, Settings, load_scene};

    fn wait(loader: &mut SceneLoader) -> (String, Result<Loaded, String>) {
        for _ in 0..6000 {
            if let Some(done) = loader.poll() {
                return done;
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        panic!("the scene did not load in 30 s");
    }

    /// A preparer of a small renderer; without the warm-up, which render/tests/load_time.rs
    /// tests (here it would only add compile time).
    fn preparer() -> ScenePreparer {
        let gpu = Gpu::new_headless().unwrap_or_else(|e| panic!("{e}"));
        let scene = load_scene("builtin:plane-light").unwrap();
        let renderer = Renderer::new(gpu, &scene, 8, 8, Settings::default()).unwrap();
        renderer.preparer().without_warm_up()
    }

    #[test]
    fn loads_in_the_background_and_reports_errors() {
        let mut loader = SceneLoader::default();
        let preparer = preparer();
        loader.start("builtin:cornell".into(), None, preparer.clone());
        assert_eq!(loader.loading(), Some("builtin:cornell"));
        let (spec, result) = wait(&mut loader);
        assert_eq!(spec, "builtin:cornell");
        let Ok(Loaded::Scene(ready)) = result else {
            panic!("cornell did not load");
        };
        // Loaded and uploaded: the BVH phase comes from the upload.
        assert!(ready.prepared.load_phases().get("BVH build").is_some());
        assert_eq!(loader.loading(), None);
        loader.start("/no/such/scene.gltf".into(), None, preparer);
        let (_, result) = wait(&mut loader);
        assert!(result.err().unwrap().contains("scene.gltf"));
    }

    #[test]
    fn a_new_environment_keeps_strength_and_rotation() {
        let mut scene = load_scene("builtin:plane-light").unwrap();
        let sky = load_environment("builtin:sky").unwrap();
        scene.environment = Some(std::sync::Arc::new(
            sky.clone().with_strength_and_rotation(2.5, 30.0).unwrap(),
        ));
        let swapped = with_environment(&scene, Some(sky)).unwrap();
        let env = swapped.environment.as_deref().unwrap();
        assert_eq!((env.strength, env.rotation_deg), (2.5, 30.0));
        assert_eq!(swapped.triangles, scene.triangles);
        assert!(
            with_environment(&scene, None)
                .unwrap()
                .environment
                .is_none()
        );
    }

    #[test]
    fn loads_environments_onto_the_shown_scene_and_names_a_bad_file() {
        let mut loader = SceneLoader::default();
        let shown = Arc::new(load_scene("builtin:plane-light").unwrap());
        loader.start_environment("builtin:sky".into(), shown.clone(), preparer());
        let (_, result) = wait(&mut loader);
        let Ok(Loaded::Environment(ready)) = result else {
            panic!("the sky did not load");
        };
        assert!(matches!(ready.scene.environment.as_deref(), Some(e) if e.width == 512));
        assert_eq!(ready.scene.triangles, shown.triangles);
        loader.start_environment("/no/such/sky.hdr".into(), shown, preparer());
        let (_, result) = wait(&mut loader);
        assert!(result.err().unwrap().starts_with("/no/such/sky.hdr: "));
    }
}
