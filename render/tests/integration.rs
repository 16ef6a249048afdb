//! The renderer's integration tests, one file per subject, compiled into one test binary
//! (render/Cargo.toml, `autotests = false`): each binary would link wgpu, naga and the
//! renderer again, and libtest spreads one binary's tests over the cores where one binary
//! per file left a core idle behind each file's longest test (docs/src/getting-started.md,
//! "How long the tests take"). A test's name is its file's and its own:
//! `cargo test -p restir-render bias_matrix` runs render/tests/bias_matrix.rs,
//! `cargo test -p restir-render --test integration` all of them.

mod common;

mod bias_matrix;
mod city;
mod denoiser;
mod dynamic_pairwise;
mod dynamic_scenes;
mod environment;
mod estimators;
mod gi_wgsl_parity;
mod glass_fresnel;
mod hard_cases;
mod jittered_accuracy;
mod light_samplers;
mod load_time;
mod mcmc_mutation;
mod multi_bounce;
mod one_bounce_unchanged;
mod previous_geometry;
mod ray_backends;
mod reference_cache_reuse;
mod restir_gi;
mod restir_pt;
mod restir_pt_inspect;
mod reuse;
mod reuse_moving_camera;
mod scene_loading;
mod shader_size;
mod shaders_and_layouts;
mod smoke;
mod specialisation;
mod temporal_window;
mod transparency;
mod unbiased_reuse;
mod unlit;
mod vertex_light_sampler;

/// With `autotests = false` cargo no longer finds a new tests/*.rs file by itself: every one
/// must be named above, or its tests would silently never run.
#[test]
fn every_test_file_is_a_module_of_this_binary() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let this = std::fs::read_to_string(dir.join("integration.rs")).unwrap();
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if let Some(module) = name.strip_suffix(".rs")
            && module != "integration"
            && !this.lines().any(|l| l == format!("mod {module};"))
        {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "render/tests/{missing:?} not declared in render/tests/integration.rs: add `mod NAME;`"
    );
}
