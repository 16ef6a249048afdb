//! The reference cache: a second request with the same key loads the stored image instead of
//! rendering it again (the progress callback is the witness), a different key renders, and
//! the background job reports progress, loads from the cache and can be cancelled.
//! GPU tests: they fail with a clear message when there is no adapter.

use std::path::PathBuf;
use std::sync::Arc;

use restir_render::reference_cache::{
    Cancelled, JobState, ReferenceCache, ReferenceJob, ReferenceRequest,
};
use restir_render::{Gpu, Renderer, Scene, Settings, load_scene};

const SCENE: &str = "builtin:cornell";
const SIZE: (u32, u32) = (32, 24);

fn gpu() -> Gpu {
    Gpu::new_headless()
        .unwrap_or_else(|e| panic!("GPU tests need a wgpu adapter (lavapipe in CI): {e}"))
}

/// A fresh, empty cache directory for one test.
fn cache(name: &str) -> ReferenceCache {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("reference_cache_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    ReferenceCache::new(dir)
}

fn scene() -> Scene {
    load_scene(SCENE).unwrap_or_else(|e| panic!("{e}"))
}

fn request(scene: &Scene, spp: u32) -> ReferenceRequest {
    ReferenceRequest::new(SCENE, scene, scene.default_camera(), SIZE, spp, false)
}

#[test]
fn reference_cache_second_request_loads_instead_of_rendering() {
    let cache = cache("reuse");
    let scene = scene();
    let mut renderer = Renderer::new(gpu(), &scene, SIZE.0, SIZE.1, Settings::default())
        .unwrap_or_else(|e| panic!("{e:#}"));
    let req = request(&scene, 8);

    let mut calls = 0;
    let first = cache.get_or_render(&mut renderer, &req, &mut |_| {
        calls += 1;
        true
    });
    let first = first.unwrap_or_else(|e| panic!("{e:#}"));
    assert!(!first.from_cache);
    assert!(
        calls >= 2,
        "progress is reported while rendering ({calls} calls)"
    );
    assert!(first.path.is_file() && first.image.mean_luminance() > 0.0);
    assert_eq!(first.meta.spp, 8);
    assert!(
        first.meta.noise_rgb_rmse.is_some_and(|n| n > 0.0),
        "two halves give a noise estimate"
    );
    let mtime = std::fs::metadata(&first.path).unwrap().modified().unwrap();

    let mut calls = 0;
    let second = cache.get_or_render(&mut renderer, &req, &mut |_| {
        calls += 1;
        true
    });
    let second = second.unwrap_or_else(|e| panic!("{e:#}"));
    assert!(
        second.from_cache,
        "the second request must load the cached image"
    );
    assert_eq!(calls, 0, "a cached reference is not rendered again");
    assert_eq!(second.image, first.image, "EXR round trip is exact");
    assert_eq!(second.meta, first.meta);
    assert_eq!(
        std::fs::metadata(&second.path).unwrap().modified().unwrap(),
        mtime
    );

    // Anything in the key makes a different entry.
    let more = request(&scene, 16);
    assert_ne!(more.key().unwrap(), req.key().unwrap());
    let mut moved = req.clone();
    moved.camera.position.x += 0.01;
    assert_ne!(moved.key().unwrap(), req.key().unwrap());
    let jittered = ReferenceRequest {
        jitter: true,
        ..req.clone()
    };
    assert_ne!(jittered.key().unwrap(), req.key().unwrap());
    // Static scenes have no scene time; two moments of an animated scene differ.
    assert_eq!(req.scene_time, None);
    let at = |t: f32| ReferenceRequest {
        scene_time: Some(t),
        ..req.clone()
    };
    assert_ne!(at(1.0).key().unwrap(), at(1.5).key().unwrap());
    assert_eq!(at(1.0).key().unwrap(), at(1.0).key().unwrap());
    // 1- and 2-bounce references are different images; 1 is every older key's value.
    assert_eq!(req.max_bounces, 1);
    let two = req.clone().with_max_bounces(2);
    assert_ne!(two.key().unwrap(), req.key().unwrap());
    assert!(two.key().unwrap().description.contains("max_bounces=2"));
    assert_eq!(
        req.clone().with_max_bounces(1).key().unwrap(),
        req.key().unwrap()
    );
    assert!(cache.load(&two).unwrap().is_none());
    // ... and the render follows the request: indirect light makes the box brighter.
    let two_image = cache
        .get_or_render(&mut renderer, &two, &mut |_| true)
        .unwrap_or_else(|e| panic!("{e:#}"));
    assert!(!two_image.from_cache);
    assert!(
        two_image.image.mean_luminance() > 1.05 * first.image.mean_luminance(),
        "2 bounces {} vs 1 bounce {}",
        two_image.image.mean_luminance(),
        first.image.mean_luminance()
    );
    assert!(cache.load(&more).unwrap().is_none());
}

#[test]
fn reference_cache_background_job_renders_then_loads_and_can_be_cancelled() {
    let cache = cache("job");
    let scene = Arc::new(scene());
    let gpu = gpu();
    let req = request(&scene, 4);

    let mut job = ReferenceJob::spawn(cache.clone(), req.clone(), gpu.clone(), scene.clone());
    while !matches!(
        job.poll(),
        JobState::Done(_) | JobState::Failed(_) | JobState::Cancelled
    ) {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let progress = job.last_progress().expect("a render reports progress");
    assert_eq!((progress.samples_done, progress.samples_total), (4, 4));
    let rendered = job.wait().unwrap_or_else(|e| panic!("{e:#}"));
    assert!(!rendered.from_cache);

    let loaded = ReferenceJob::spawn(cache.clone(), req.clone(), gpu.clone(), scene.clone())
        .wait()
        .unwrap_or_else(|e| panic!("{e:#}"));
    assert!(loaded.from_cache);
    assert_eq!(loaded.image, rendered.image);

    // Cancelled before its first frame: the progress callback at 0 spp stops it.
    let big = request(&scene, 4096);
    let job = ReferenceJob::spawn(cache.clone(), big.clone(), gpu, scene);
    job.cancel();
    let err = job.wait().expect_err("cancelled");
    assert!(
        err.downcast_ref::<Cancelled>().is_some() || err.to_string().contains("cancelled"),
        "{err:#}"
    );
    assert!(
        cache.load(&big).unwrap().is_none(),
        "a cancelled render stores nothing"
    );
}
