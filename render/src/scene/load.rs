//! The one entry point for scenes: `builtin:NAME` or a path to a .gltf/.glb file. Every
//! scene it returns has passed `validate` (the checks live there, below both sources, so
//! the built-in generators and the glTF loader can use them without importing this).

use std::path::Path;

use super::validate::validate;
use super::{Scene, builtin, gltf_loader};
use crate::load_phases::{LoadPhases, Watcher, unwatched};

pub use super::validate::SceneError;

/// Load `builtin:NAME` (see `builtin::builtin_names`) or a .gltf/.glb file.
pub fn load_scene(spec: &str) -> Result<Scene, SceneError> {
    load_scene_watched(spec, &unwatched)
}

/// As `load_scene`, telling `watch` as each phase begins and ends; the phases are in the
/// scene's `load_phases`.
pub fn load_scene_watched(spec: &str, watch: Watcher) -> Result<Scene, SceneError> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        let mut phases = LoadPhases::default();
        let mut scene = phases.try_time(watch, "build", || {
            builtin::builtin_scene(name).map(|s| {
                let detail = format!("{} triangles", s.triangles.len());
                (s, detail)
            })
        })?;
        phases.try_time(watch, "validate", || {
            validate(&mut scene, spec).map(|()| ((), String::new()))
        })?;
        scene.load_phases = phases;
        Ok(scene)
    } else {
        // load_gltf validates too: it is public and must not return unchecked scenes.
        gltf_loader::load_gltf_watched(Path::new(spec), watch)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_prefix_dispatches_and_unknown_names_fail() {
        assert!(load_scene("builtin:plane-light").is_ok());
        let e = load_scene("builtin:nope").unwrap_err().to_string();
        assert!(e.starts_with("builtin:nope:"), "{e}");
    }
}
