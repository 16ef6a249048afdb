//! What the bias matrix runs (docs/src/measured/unbiased-reuse.md, "The bias matrix"): every
//! built-in scene (the families at a stated N), the real-world models, and every estimator a user
//! can pick. A cell is one scene and one estimator; each runs as one `bench` command.

use crate::bench::plan::jobs::slug;

/// Light count of the families in the matrix: large enough that the tiles, ReGIR and the
/// light BVH all have work, small enough to build in a second.
pub const FAMILY_N: usize = 16_384;

/// The families (`NAME:N`) run at [`FAMILY_N`]; `many-lights` and `dynamic:many-lights` are
/// already in the named list at their default count.
const FAMILIES: [&str; 3] = ["city", "city-roofs", "city-traffic"];

/// The models written by other tools: the ones the repository ships under `assets/`, and
/// two Khronos samples read from the shared scenes folder beside the checkout (relative to
/// the working directory: run from the repository root).
pub const MODELS: [&str; 5] = [
    "assets/blender-2.79-cornell/cornellBox-2.79-Cycles-gltf.gltf",
    "assets/blender-2.80-cornell/cornellBox-2.80-Eevee-gltf.gltf",
    "assets/khronos/LightsPunctualLamp/glTF/LightsPunctualLamp.gltf",
    "../shared/scenes/khronos/EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf",
    "../shared/scenes/khronos/StainedGlassLamp/StainedGlassLamp.gltf",
];

/// Every estimator a user can pick in the matrix's order: DI without and with reuse, both
/// bias corrections, GI's two, PT's three shifts, the light samplers under the default
/// ReSTIR, then the denoiser on one of each family (bench configuration names,
/// app/src/bench/plan/configs.rs).
pub const ESTIMATORS: [&str; 18] = [
    "nee",
    "ris",
    "ris+temporal",
    "ris+spatial",
    "restir-pairwise",
    "restir",
    "restir+gi-pairwise",
    "restir+gi",
    "restir+pt",
    "restir+pt-reconnection",
    "restir+pt-replay",
    "restir-pairwise@tiles",
    "restir-pairwise@regir",
    "restir-pairwise@bvh",
    "ris+denoise",
    "restir-pairwise+denoise",
    "restir+gi-pairwise+denoise",
    "restir+pt+denoise",
];

/// The default scene list: every built-in scene, the families at [`FAMILY_N`], the models.
pub fn all_scenes() -> Vec<String> {
    let mut scenes = restir_render::scene::builtin::builtin_names();
    scenes.extend(FAMILIES.iter().map(|f| format!("builtin:{f}:{FAMILY_N}")));
    scenes.extend(MODELS.iter().map(|m| m.to_string()));
    scenes
}

/// One cell: a scene and an estimator.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cell {
    pub scene: String,
    pub estimator: String,
}

impl Cell {
    /// The folder under `cells/` this cell's bench writes to: `SCENE/ESTIMATOR`, each a
    /// file-name-safe slug (a model by its file stem).
    pub fn folder(&self) -> String {
        format!(
            "{}/{}",
            slug(&scene_label(&self.scene)),
            slug(&self.estimator)
        )
    }
}

/// How a scene is named in the table: `builtin:NAME` as is, a model by its file stem.
pub fn scene_label(scene: &str) -> String {
    if scene.starts_with("builtin:") {
        return scene.to_string();
    }
    std::path::Path::new(scene)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(scene)
        .to_string()
}

/// The cells of `scenes` × `estimators`, scene-major.
pub fn cells(scenes: &[String], estimators: &[String]) -> Vec<Cell> {
    scenes
        .iter()
        .flat_map(|s| {
            estimators.iter().map(move |e| Cell {
                scene: s.clone(),
                estimator: e.clone(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_cell_has_its_own_folder() {
        let cells = cells(&all_scenes(), &ESTIMATORS.map(String::from));
        let mut folders: Vec<String> = cells.iter().map(Cell::folder).collect();
        let n = folders.len();
        folders.sort();
        folders.dedup();
        assert_eq!(folders.len(), n, "two cells share a folder");
        assert!(folders.iter().all(|f| !f.contains(':') && !f.contains('+')));
    }

    #[test]
    fn every_estimator_is_a_bench_configuration() {
        let base = restir_render::Settings::default();
        crate::bench::plan::configs::parse_configs(&ESTIMATORS.join(","), &base).unwrap();
    }
}
