//! Loads scenes on a background thread (glTF import and BVH build can take seconds), so
//! the window keeps drawing the old scene meanwhile.

use std::sync::mpsc::{Receiver, TryRecvError, channel};

use restir_render::{Scene, load_scene};

#[derive(Default)]
pub struct SceneLoader {
    pending: Option<(String, Receiver<Result<Scene, String>>)>,
}

impl SceneLoader {
    /// Starts loading `spec`; a load already running is abandoned (its result dropped).
    pub fn start(&mut self, spec: String) {
        let (tx, rx) = channel();
        let job = spec.clone();
        std::thread::spawn(move || {
            let _ = tx.send(load_scene(&job).map_err(|e| e.to_string()));
        });
        self.pending = Some((spec, rx));
    }

    pub fn loading(&self) -> Option<&str> {
        self.pending.as_ref().map(|(spec, _)| spec.as_str())
    }

    /// The finished load, if it has finished.
    pub fn poll(&mut self) -> Option<(String, Result<Scene, String>)> {
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

    fn wait(loader: &mut SceneLoader) -> (String, Result<Scene, String>) {
        for _ in 0..2000 {
            if let Some(done) = loader.poll() {
                return done;
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        panic!("the scene did not load in 10 s");
    }

    #[test]
    fn loads_in_the_background_and_reports_errors() {
        let mut loader = SceneLoader::default();
        loader.start("builtin:cornell".into());
        assert_eq!(loader.loading(), Some("builtin:cornell"));
        let (spec, result) = wait(&mut loader);
        assert_eq!(spec, "builtin:cornell");
        assert!(result.is_ok());
        assert_eq!(loader.loading(), None);
        loader.start("/no/such/scene.gltf".into());
        let (_, result) = wait(&mut loader);
        assert!(result.unwrap_err().contains("scene.gltf"));
    }
}
