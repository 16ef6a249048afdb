//! Converged reference images (docs/src/measured/how-the-bench-measures.md, "Reference cache"),
//! cached on disk.
//!
//! A reference is the average of many frames of `Mode::Reference` (the unbiased
//! light + BSDF MIS estimator). Rendering one takes seconds to minutes, so it is stored as
//! an untonemapped EXR under the cache directory (`$RESTIR_CACHE_DIR`, else
//! `target/restir-cache`), keyed by a hash of everything it depends on (see `key.rs`), with
//! a JSON file beside it holding the key text and what is known about the image (spp, its
//! own noise, how long it took).
//!
//! Two ways to get one:
//! - [`ReferenceCache::get_or_render`] on a renderer you already have (the `bench`
//!   command): loads the cached image, or renders it on that renderer with a progress
//!   callback (which can cancel) and stores it;
//! - [`ReferenceJob::spawn`] in the background on its own renderer (the viewer's accuracy
//!   panel): poll it each frame for progress, then take the result.
//!
//! **The reference's own noise.** Every per-frame RMSE measured against a reference of
//! finite spp is inflated: E[RMSE²] = MSE_true + Var_ref. The renderer estimates its own
//! RMSE from the image after the first half of the frames, `a`, and the full average `f`:
//! a − f = ½(a − b) for the halves a and b, so RMSE(a, f) estimates RMSE(f) for k = n/2
//! (in general RMSE(f) ≈ RMSE(a, f)·√(k/(n−k))). Reports state it next to the spp.

mod job;
pub mod key;
mod render;

pub use crate::fnv::Fnv64;
pub use job::{JobState, ReferenceJob};
pub use key::{CACHE_VERSION, ReferenceKey, key_of};
use render::reference_settings;
pub use render::{render_reference, spp_per_frame};

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::Context;
use serde::{Deserialize, Serialize};

use crate::effects::{EffectSet, SceneFeatures};
use crate::image::LinearImage;
use crate::scene::{Camera, Scene};
use crate::{Renderer, Settings};

/// The seed of every reference: fixed and different from any seed a benchmark uses, so the
/// reference's random numbers are independent of the frames measured against it, and one
/// cached reference serves every `--seed`.
pub const REFERENCE_SEED: u32 = 0x7e5e_ed01;

/// What to render: the scene, the view and how converged.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceRequest {
    /// The scene as `load_scene` takes it: `builtin:NAME` or a .gltf/.glb path.
    pub scene: String,
    pub camera: Camera,
    pub width: u32,
    pub height: u32,
    /// Total samples per pixel.
    pub spp: u32,
    /// Sub-pixel jitter: off, the reference shades the rasterised pixel-centre surfaces
    /// (compare against frames rendered with `jitter=false` to measure lighting alone).
    pub jitter: bool,
    /// The pipeline variant (WGSL defines) the reference is compiled with.
    pub effects: EffectSet,
    pub seed: u32,
    /// `Environment::fingerprint` of the scene's environment (file, content, strength,
    /// rotation); `None` without one.
    pub environment: Option<String>,
    /// The scene time an animated scene was posed at (`None` for a static scene, whose
    /// keys stay what they were): references of different moments never share a file.
    pub scene_time: Option<f32>,
    /// Lights sampled by the light BVH at every vertex (`reference_light_bvh`) instead of
    /// the power table; the effects (hence the key) say so too.
    pub light_bvh: bool,
    /// Path vertices shaded (`max_bounces`): 1 is direct light only, 2 adds one bounce of
    /// indirect light. A reference is compared with frames that estimate the same integral.
    pub max_bounces: u32,
    /// Light samples per vertex (`reference_light_samples`, 1 as every reference before
    /// it): more make a sample worth more where lights are many and small.
    pub light_samples: u32,
    /// With jitter off: rasterise at this jitter phase's sub-pixel offset instead of the
    /// pixel centres, the reference of the frames of that phase (`None`: pixel centres).
    /// Jittered frames scored against it measure their estimator, not the pixel footprint
    /// (docs/src/viewer.md, "Accuracy with jitter on").
    pub jitter_phase: Option<u32>,
}

impl ReferenceRequest {
    /// A request for `scene` (loaded from `scene_spec`) with the effect set a still camera
    /// derives for it and [`REFERENCE_SEED`].
    pub fn new(
        scene_spec: &str,
        scene: &Scene,
        camera: Camera,
        (width, height): (u32, u32),
        spp: u32,
        jitter: bool,
    ) -> ReferenceRequest {
        let settings = reference_settings(jitter, 1, 1, false, 1);
        ReferenceRequest {
            scene: scene_spec.to_string(),
            camera,
            width,
            height,
            spp: spp.max(1),
            jitter,
            effects: EffectSet::detect(&SceneFeatures::of(scene), &settings, false),
            seed: REFERENCE_SEED,
            environment: scene.environment.as_ref().map(|e| e.fingerprint()),
            scene_time: scene.animation.as_ref().map(|a| a.posed_at),
            light_bvh: false,
            max_bounces: 1,
            light_samples: 1,
            jitter_phase: None,
        }
    }

    /// The same request with its lights sampled by the light BVH at every vertex
    /// (`light_bvh`) or by the power table, and the effect set that follows.
    pub fn with_light_bvh(self, light_bvh: bool, scene: &Scene) -> ReferenceRequest {
        let settings = reference_settings(self.jitter, 1, 1, light_bvh, 1);
        ReferenceRequest {
            effects: EffectSet::detect(&SceneFeatures::of(scene), &settings, false),
            light_bvh,
            ..self
        }
    }

    /// The reference of the frames of one jitter phase: jitter off (the G-buffer's
    /// surfaces), rasterised at that phase's offset.
    pub fn at_jitter_phase(self, phase: u32) -> ReferenceRequest {
        ReferenceRequest {
            jitter: false,
            jitter_phase: Some(phase % crate::renderer::JITTER_PERIOD as u32),
            ..self
        }
    }

    /// The same request with `max_bounces` path vertices (clamped to the parameter's range).
    pub fn with_max_bounces(self, max_bounces: u32) -> ReferenceRequest {
        ReferenceRequest {
            max_bounces: max_bounces.clamp(1, crate::shader_constants::MAX_BOUNCES),
            ..self
        }
    }

    /// The same request with `light_samples` per vertex (clamped as the parameter is, for
    /// its `max_bounces`: set those first).
    pub fn with_light_samples(self, light_samples: u32) -> ReferenceRequest {
        let settings = Settings {
            reference_light_samples: light_samples,
            max_bounces: self.max_bounces,
            ..Settings::default()
        };
        ReferenceRequest {
            light_samples: settings.reference_light_samples_in_use(),
            ..self
        }
    }

    pub fn key(&self) -> anyhow::Result<ReferenceKey> {
        key_of(self)
    }
}

/// Progress of a reference being rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    pub samples_done: u32,
    pub samples_total: u32,
    pub elapsed: Duration,
}

impl Progress {
    /// 0..=1.
    pub fn fraction(&self) -> f64 {
        self.samples_done as f64 / self.samples_total.max(1) as f64
    }

    /// Time left at the rate so far (None before the first frame is done).
    pub fn eta(&self) -> Option<Duration> {
        (self.samples_done > 0).then(|| {
            self.elapsed
                .mul_f64((self.samples_total - self.samples_done) as f64 / self.samples_done as f64)
        })
    }
}

/// What is known about a reference image (the JSON beside the EXR).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceMeta {
    /// The key text (see `key.rs`); a cached file is used only when it matches exactly.
    pub key: String,
    pub spp: u32,
    pub frames: u32,
    pub spp_per_frame: u32,
    /// Estimated luma RMSE of the reference itself (None for a one-frame reference).
    pub noise_luma_rmse: Option<f64>,
    /// Estimated RGB RMSE of the reference itself.
    pub noise_rgb_rmse: Option<f64>,
    pub render_seconds: f64,
    pub adapter: String,
}

/// A reference image and where it came from.
#[derive(Clone, Debug)]
pub struct Reference {
    pub image: LinearImage,
    pub meta: ReferenceMeta,
    /// The EXR in the cache.
    pub path: PathBuf,
    /// True when it was loaded, false when it was rendered by this call.
    pub from_cache: bool,
}

/// The error a cancelled render returns (`err.downcast_ref::<Cancelled>()`).
#[derive(Debug, thiserror::Error)]
#[error("reference rendering was cancelled")]
pub struct Cancelled;

/// A directory of cached references.
#[derive(Clone, Debug)]
pub struct ReferenceCache {
    dir: PathBuf,
}

impl ReferenceCache {
    pub fn new(dir: impl Into<PathBuf>) -> ReferenceCache {
        ReferenceCache { dir: dir.into() }
    }

    /// `$RESTIR_CACHE_DIR`, else `target/restir-cache` (relative to the working directory).
    pub fn default_dir() -> PathBuf {
        match std::env::var_os("RESTIR_CACHE_DIR") {
            Some(dir) if !dir.is_empty() => PathBuf::from(dir),
            _ => PathBuf::from("target").join("restir-cache"),
        }
    }

    pub fn at_default_dir() -> ReferenceCache {
        ReferenceCache::new(ReferenceCache::default_dir())
    }

    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The EXR and JSON paths of a key.
    pub fn paths(&self, key: &ReferenceKey) -> (PathBuf, PathBuf) {
        let stem = key.stem();
        (
            self.dir.join(format!("{stem}.exr")),
            self.dir.join(format!("{stem}.json")),
        )
    }

    /// The cached reference of `request`, if there is one that matches its key exactly.
    /// A damaged or mismatching entry is treated as missing (and logged).
    pub fn load(&self, request: &ReferenceRequest) -> anyhow::Result<Option<Reference>> {
        let key = request.key()?;
        let (exr, json) = self.paths(&key);
        if !exr.is_file() || !json.is_file() {
            return Ok(None);
        }
        let loaded = (|| -> anyhow::Result<Option<Reference>> {
            let meta: ReferenceMeta = serde_json::from_slice(&std::fs::read(&json)?)?;
            if meta.key != key.description {
                log::warn!(
                    "{}: key differs (hash collision?); re-rendering",
                    json.display()
                );
                return Ok(None);
            }
            let image = LinearImage::load_exr(&exr)?;
            anyhow::ensure!(
                (image.width, image.height) == (request.width, request.height),
                "{}: image is {}x{}, expected {}x{}",
                exr.display(),
                image.width,
                image.height,
                request.width,
                request.height
            );
            Ok(Some(Reference {
                image,
                meta,
                path: exr.clone(),
                from_cache: true,
            }))
        })();
        Ok(loaded.unwrap_or_else(|e| {
            log::warn!("cached reference unusable, re-rendering: {e:#}");
            None
        }))
    }

    /// Loads the reference, or renders it on `renderer` (whose scene must be
    /// `request.scene`) and stores it. `progress` is called after every reference frame
    /// (and once before the first); returning false cancels with [`Cancelled`]. After a
    /// render the renderer is left in `Mode::Reference` with the reference's settings,
    /// camera, seed and effect set: set what you need next.
    pub fn get_or_render(
        &self,
        renderer: &mut Renderer,
        request: &ReferenceRequest,
        progress: &mut dyn FnMut(&Progress) -> bool,
    ) -> anyhow::Result<Reference> {
        if let Some(reference) = self.load(request)? {
            return Ok(reference);
        }
        let (image, meta) = render_reference(renderer, request, progress)?;
        let path = self.store(&request.key()?, &image, &meta)?;
        Ok(Reference {
            image,
            meta,
            path,
            from_cache: false,
        })
    }

    /// Writes an image and its metadata (through temporary files, so a reader never sees
    /// half an entry). Returns the EXR's path.
    pub fn store(
        &self,
        key: &ReferenceKey,
        image: &LinearImage,
        meta: &ReferenceMeta,
    ) -> anyhow::Result<PathBuf> {
        std::fs::create_dir_all(&self.dir).with_context(|| {
            format!("{}: cannot create the reference cache", self.dir.display())
        })?;
        let (exr, json) = self.paths(key);
        let unique = format!("{}-{:?}", std::process::id(), std::thread::current().id());
        let tmp_exr = exr.with_extension(format!("{unique}.tmp.exr"));
        let tmp_json = json.with_extension(format!("{unique}.tmp.json"));
        image.save_exr(&tmp_exr)?;
        std::fs::write(&tmp_json, serde_json::to_string_pretty(meta)?)
            .with_context(|| format!("{}: cannot write", tmp_json.display()))?;
        // The image first: `load` needs both, and checks the JSON's key.
        std::fs::rename(&tmp_exr, &exr)
            .with_context(|| format!("{}: cannot write", exr.display()))?;
        std::fs::rename(&tmp_json, &json)
            .with_context(|| format!("{}: cannot write", json.display()))?;
        Ok(exr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A phase's reference is its own cache entry, jitter off; the pixel centres' key text
    /// is what it was before phases existed (their cached files stay valid).
    #[test]
    fn a_jitter_phase_has_its_own_key() {
        let scene = crate::scene::builtin::builtin_scene("cornell").unwrap();
        let request = |jitter| {
            ReferenceRequest::new(
                "builtin:cornell",
                &scene,
                scene.default_camera(),
                (8, 6),
                4,
                jitter,
            )
        };
        let centres = request(false);
        assert!(!centres.key().unwrap().description.contains("jitter_phase"));
        let phase = request(true).at_jitter_phase(5);
        assert!(!phase.jitter);
        assert_eq!(phase.jitter_phase, Some(5));
        let key = phase.key().unwrap();
        assert!(key.description.contains("jitter_phase=5\n"));
        assert_ne!(key, centres.key().unwrap());
        assert_ne!(key, request(false).at_jitter_phase(6).key().unwrap());
        // Phases wrap with the period, as frames do.
        assert_eq!(request(false).at_jitter_phase(5 + 64).jitter_phase, Some(5));
    }

    /// Light samples per vertex are in the key only beyond one (every cached reference of
    /// before keeps its key), and follow the parameter's clamp for the bounces.
    #[test]
    fn light_samples_have_their_own_key() {
        let scene = crate::scene::builtin::builtin_scene("cornell").unwrap();
        let one = ReferenceRequest::new(
            "builtin:cornell",
            &scene,
            scene.default_camera(),
            (8, 6),
            4,
            false,
        );
        let same = one.clone().with_light_samples(1);
        assert_eq!(same.key().unwrap(), one.key().unwrap());
        assert!(!one.key().unwrap().description.contains("light_samples"));
        let eight = one.clone().with_light_samples(8);
        assert!(
            eight
                .key()
                .unwrap()
                .description
                .contains("light_samples=8\n")
        );
        assert_ne!(eight.key().unwrap(), one.key().unwrap());
        let deep = one.with_max_bounces(8).with_light_samples(8);
        assert_eq!(deep.light_samples, 2, "16 light samples per path at most");
    }

    #[test]
    fn progress_fraction_and_eta() {
        let p = Progress {
            samples_done: 25,
            samples_total: 100,
            elapsed: Duration::from_secs(1),
        };
        assert_eq!(p.fraction(), 0.25);
        assert_eq!(p.eta(), Some(Duration::from_secs(3)));
        assert_eq!(
            Progress {
                samples_done: 0,
                ..p
            }
            .eta(),
            None
        );
    }
}
