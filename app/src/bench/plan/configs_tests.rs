//! The configurations parse from their names: built-ins with their modes, the suffixes
//! (`+denoise`, `@SAMPLER`, `:BACKEND`), parameters in brackets, and GI, PT and path-traced
//! configurations scored against the references of their own bounce count.

use super::*;

#[test]
fn bench_default_configs_parse_with_their_modes() {
    let configs = parse_configs(DEFAULT_CONFIGS, &Settings::default()).unwrap();
    let names: Vec<_> = configs.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names.join(","), DEFAULT_CONFIGS);
    assert_eq!(configs[0].mode, Mode::Nee);
    assert!(configs[2].settings.temporal && !configs[2].settings.spatial);
    assert!(!configs[3].settings.temporal && configs[3].settings.spatial);
    assert!(parse_configs("restir,nope", &Settings::default()).is_err());
    // Any configuration can be denoised, with or without a backend after it.
    let denoised = parse_configs(
        "ris+denoise,restir-pairwise+denoise:software,ris+temporal+denoise",
        &Settings::default(),
    )
    .unwrap();
    assert!(denoised.iter().all(|c| c.settings.denoise));
    assert_eq!(denoised[0].mode, Mode::Ris);
    assert_eq!(denoised[1].name, "restir-pairwise+denoise:software");
    assert!(denoised[2].settings.temporal && !denoised[2].settings.spatial);
    assert!(!configs.iter().any(|c| c.settings.denoise));
    // Parameters in brackets come last and name the configuration.
    let tuned = parse_configs(
        "ris[light_candidates=8],restir-pairwise+denoise@bvh[m_cap=4;denoise_iterations=2]",
        &Settings::default(),
    )
    .unwrap();
    assert_eq!(tuned[0].name, "ris[light_candidates=8]");
    assert_eq!(tuned[0].settings.light_candidates, 8);
    assert!(tuned[1].settings.denoise && tuned[1].settings.m_cap == 4.0);
    assert_eq!(
        tuned[1].settings.light_sampler,
        restir_render::settings::LightSampler::Bvh
    );
    for bad in ["ris[light_candidates=8", "ris[nope=1]", "ris[m_cap=x]"] {
        let e = format!(
            "{:#}",
            parse_configs(bad, &Settings::default()).unwrap_err()
        );
        assert!(e.contains("--configs"), "{bad}: {e}");
    }
    assert!(parse_configs("+denoise", &Settings::default()).is_err());
    assert!(parse_configs("ris,ris", &Settings::default()).is_err());
    // `restir` keeps the 1/M weights its published figures were measured with;
    // `restir-pairwise` is the default estimator (docs/src/mis-and-bias.md, "The cost
    // and the choice").
    use restir_render::settings::BiasCorrection;
    assert_eq!(
        configs[4].settings.bias_correction,
        BiasCorrection::OneOverM
    );
    assert_eq!(
        configs[5].settings.bias_correction,
        BiasCorrection::Pairwise
    );
}

#[test]
fn a_sampler_suffix_picks_the_light_sampler() {
    use restir_render::settings::LightSampler;
    let configs = parse_configs(
        "ris@bvh,restir-pairwise@regir:software,ris+denoise@tiles,ris",
        &Settings::default(),
    )
    .unwrap();
    assert_eq!(configs[0].mode, Mode::Ris);
    assert_eq!(configs[0].settings.light_sampler, LightSampler::Bvh);
    assert_eq!(configs[1].settings.light_sampler, LightSampler::Regir);
    assert_eq!(configs[1].name, "restir-pairwise@regir:software");
    assert!(configs[2].settings.denoise);
    assert_eq!(configs[2].settings.light_sampler, LightSampler::Tiles);
    assert_eq!(configs[3].settings.light_sampler, LightSampler::Auto);
    assert!(parse_configs("ris@octree", &Settings::default()).is_err());
}

#[test]
fn a_backend_suffix_picks_the_tracing_backend() {
    use restir_render::settings::RayBackendChoice;
    let configs = parse_configs(
        "nee:ray-query,restir-pairwise:software,nee",
        &Settings::default(),
    )
    .unwrap();
    assert_eq!(configs[0].name, "nee:ray-query");
    assert_eq!(configs[0].mode, Mode::Nee);
    assert_eq!(configs[0].settings.ray_backend, RayBackendChoice::RayQuery);
    assert_eq!(configs[1].settings.ray_backend, RayBackendChoice::Software);
    assert_eq!(configs[2].settings.ray_backend, RayBackendChoice::Auto);
    assert!(parse_configs("nee:warp-drive", &Settings::default()).is_err());
}

#[test]
fn path_2b_is_the_one_sample_two_bounce_reference_estimator() {
    let base = Settings::default();
    let configs = parse_configs("ris,path-2b", &base).unwrap();
    let path = &configs[1];
    assert_eq!(path.mode, Mode::Reference);
    assert_eq!(
        (path.settings.reference_spp, path.settings.max_bounces),
        (1, 2)
    );
    // Everything else is the base: jitter off with the bench's base assignments.
    let jitter_off = {
        let mut b = base.clone();
        b.apply_assignments(BASE_ASSIGNMENTS.iter().copied())
            .unwrap();
        b
    };
    let path = &parse_configs("path-2b", &jitter_off).unwrap()[0];
    assert!(!path.settings.jitter);
    // `ris` stays direct-only, so it gets the 1-bounce reference.
    assert_eq!(configs[0].settings.max_bounces, 1);
}

#[test]
fn gi_configurations_run_gi_and_are_scored_against_two_bounces() {
    use restir_render::settings::BiasCorrection;
    let configs = parse_configs("restir+gi,restir+gi-pairwise", &Settings::default()).unwrap();
    for c in &configs {
        assert_eq!(c.mode, Mode::Restir);
        assert!(c.settings.gi && c.settings.gi_temporal && c.settings.gi_spatial);
        assert_eq!(c.settings.max_bounces, 2);
    }
    assert_eq!(
        configs[0].settings.gi_bias_correction,
        BiasCorrection::OneOverM
    );
    assert_eq!(
        configs[1].settings.gi_bias_correction,
        BiasCorrection::Pairwise
    );
}
