use super::*;
use crate::di::constants::PARAM_FLAG_PERMUTATION;
use crate::gi::constants::*;

#[test]
fn defaults_follow_the_notes() {
    let s = Settings::default();
    assert_eq!(s.light_candidates, 32);
    assert_eq!(s.bsdf_candidates, 1);
    assert_eq!(s.m_cap, 20.0);
    assert!((s.normal_threshold - 25f32.to_radians().cos()).abs() < 1e-3);
    assert_eq!(s.depth_threshold, 0.1);
    assert_eq!(s.target_ratio_clamp, 10.0);
    assert_eq!(
        (s.spatial_neighbours, s.spatial_radius, s.spatial_passes),
        (5, 30.0, 1)
    );
    assert!(s.permutation && s.temporal && s.spatial);
    assert_eq!(s.boiling_filter, 0.0);
}

#[test]
fn defaults_are_what_the_measurements_favour() {
    // Pairwise MIS measured as accurate as 1/M per frame and unbiased for ~3 %
    // more time; light tiles only where the sweep says they pay.
    let s = Settings::default();
    assert_eq!(s.bias_correction, BiasCorrection::Pairwise);
    assert_eq!(s.light_sampler, LightSampler::Auto);
    let mut t = s.clone();
    t.set_from_str("light_sampler", "bvh").unwrap();
    assert_eq!(t.light_sampler, LightSampler::Bvh);
    assert!(t.set_from_str("light_sampler", "true").is_err());
}

#[test]
fn every_row_round_trips_through_get_and_set() {
    for def in PARAMS {
        let mut s = Settings::default();
        let v = s.get(def.name).unwrap();
        assert_eq!(s.set(def.name, v.clone()), Ok(None), "{}", def.name);
        assert_eq!(s.get(def.name), Some(v));
    }
}

#[test]
fn out_of_range_values_are_clamped_with_a_warning() {
    let mut s = Settings::default();
    let w = s.set_from_str("light_candidates", "100000").unwrap();
    assert_eq!(s.light_candidates, 256);
    assert!(w.unwrap().contains("light_candidates"));
    s.set_from_str("m_cap", "-5").unwrap();
    assert_eq!(s.m_cap, 0.0);
    assert!(s.set_from_str("m_cap", "nan").is_err());
    assert!(s.set_from_str("temporal", "maybe").is_err());
    assert!(matches!(
        s.set_from_str("nope", "1"),
        Err(SettingsError::Unknown(_))
    ));
    assert!(s.set_from_str("bias_correction", "magic").is_err());
    s.set_from_str("bias_correction", "pairwise").unwrap();
    assert_eq!(s.bias_correction, BiasCorrection::Pairwise);
}

#[test]
fn presets_round_trip_and_reject_unknown_keys_and_types() {
    let s = Settings {
        m_cap: 7.5,
        temporal: false,
        bias_correction: BiasCorrection::Pairwise,
        ..Settings::default()
    };
    let text = preset::to_toml(&s);
    let (back, warnings) = preset::parse(&text, &Settings::default()).unwrap();
    assert_eq!(back, s);
    assert!(warnings.is_empty());
    let err = preset::parse("m_cup = 3\n", &Settings::default()).unwrap_err();
    assert!(err.to_string().contains("m_cup"));
    let err = preset::parse("temporal = \"yes\"\n", &Settings::default()).unwrap_err();
    assert!(err.to_string().contains("temporal"));
    assert!(preset::parse("this is not toml", &Settings::default()).is_err());
}

#[test]
fn gpu_params_reflect_checks_and_flags() {
    let mut s = Settings::default();
    assert_eq!(s.gpu_params(1080).checks, 0xff);
    s.check_normal = false;
    s.check_target_ratio = false;
    let p = s.gpu_params(1080);
    assert_eq!(p.checks & REJECT_NORMAL, 0);
    assert_eq!(p.di.target_ratio_clamp, 0.0);
    assert_eq!(p.flags & PARAM_FLAG_PERMUTATION, PARAM_FLAG_PERMUTATION);
}

#[test]
fn indirect_defaults_and_flags() {
    let s = Settings::default();
    assert!(!s.gi && s.gi_temporal && s.gi_spatial);
    assert!(s.gi_spatial_visibility && s.gi_mis_visibility);
    assert_eq!((s.gi_m_cap, s.gi_spatial_neighbours), (10.0, 3));
    assert_eq!((s.gi_spatial_radius, s.gi_jacobian_max), (30.0, 10.0));
    assert_eq!(s.gi_bias_correction, BiasCorrection::Pairwise);
    assert!(
        PARAMS
            .iter()
            .filter(|p| p.name.starts_with("gi"))
            .all(|p| p.stage == Stage::Indirect)
    );
    // GI off by default: only the pairwise-mode bit of the stage is set, and the DI flags
    // are what they were.
    let p = s.gpu_params(1080);
    let gi_bits = PARAM_FLAG_GI
        | PARAM_FLAG_GI_TEMPORAL
        | PARAM_FLAG_GI_SPATIAL
        | PARAM_FLAG_GI_SPATIAL_VISIBILITY
        | PARAM_FLAG_GI_MIS_VISIBILITY
        | PARAM_FLAG_GI_PAIRWISE;
    assert_eq!(p.flags & PARAM_FLAG_GI, 0);
    assert_eq!(p.flags & gi_bits, gi_bits & !PARAM_FLAG_GI);
    let mut t = s.clone();
    t.set_from_str("gi", "on").unwrap();
    t.set_from_str("gi_spatial_visibility", "off").unwrap();
    t.set_from_str("gi_bias_correction", "one-over-m").unwrap();
    let w = t.set_from_str("gi_jacobian_max", "0.5").unwrap();
    assert!(w.unwrap().contains("gi_jacobian_max"));
    let p = t.gpu_params(1080);
    assert_eq!(
        p.flags & gi_bits,
        PARAM_FLAG_GI
            | PARAM_FLAG_GI_TEMPORAL
            | PARAM_FLAG_GI_SPATIAL
            | PARAM_FLAG_GI_MIS_VISIBILITY
    );
    assert_eq!(p.gi.jacobian_max, 1.0);
    assert_eq!(p.flags & !gi_bits, s.gpu_params(1080).flags & !gi_bits);
}

/// The reference divides by `reference_spp` and a frame renders at most
/// PASS_INFO_SLOTS × REFERENCE_SAMPLES_PER_DISPATCH samples: a larger setting must reach the
/// GPU as that count (4096 once rendered 2048 samples and halved the image).
#[test]
fn reference_spp_reaches_the_gpu_as_the_count_a_frame_renders() {
    let most = REFERENCE_SAMPLES_PER_DISPATCH * crate::passes::PASS_INFO_SLOTS;
    let mut s = Settings {
        reference_spp: 4096,
        ..Settings::default()
    };
    assert_eq!(s.gpu_params(100).reference_spp, most);
    s.reference_spp = 64;
    assert_eq!(s.gpu_params(100).reference_spp, 64);
}

/// The reference's light samples reach the GPU within their bounds: at most
/// REFERENCE_PATH_LIGHT_SAMPLES over a path (lavapipe's loop bound), never 0.
#[test]
fn reference_light_samples_stay_within_a_paths_bound() {
    let at = |samples: u32, bounces: u32| {
        let s = Settings {
            reference_light_samples: samples,
            max_bounces: bounces,
            ..Settings::default()
        };
        s.gpu_params(100).reference_light_samples
    };
    assert_eq!(at(1, 1), 1);
    assert_eq!(at(8, 1), 8);
    assert_eq!(at(8, 2), 8);
    assert_eq!(at(16, 2), REFERENCE_PATH_LIGHT_SAMPLES / 2);
    assert_eq!(at(16, 8), 2);
    assert_eq!(at(0, 1), 1, "0 is one sample");
    assert_eq!(at(u32::MAX, 1), MAX_REFERENCE_LIGHT_SAMPLES);
}

/// With GI on, the reference traces at least 2 bounces (GI's image is direct + one bounce).
#[test]
fn the_reference_follows_gi_with_two_bounces() {
    let mut s = Settings::default();
    assert_eq!(s.reference_bounces(), 1);
    s.gi = true;
    assert_eq!(s.reference_bounces(), 2);
    assert_eq!(s.gpu_params(100).max_bounces, 2);
    s.max_bounces = 5;
    assert_eq!(s.reference_bounces(), 5);
}

/// Every row that switches a reuse stage on is marked, so nee and ris turn it off: a row
/// whose label says "reuse" and is a bool must be a `ReuseSwitch` (the next technique's
/// switch cannot be forgotten), and `without_reuse` turns each of them off. PT's were
/// forgotten before the marking existed (ris rendered PT with reuse).
#[test]
fn nee_and_ris_turn_every_reuse_stage_off() {
    for def in PARAMS {
        let says_reuse = def.label.to_lowercase().contains("reuse") && def.kind == ParamKind::Bool;
        assert_eq!(
            says_reuse,
            def.role == Role::ReuseSwitch,
            "{}: a bool row named as a reuse stage is a ReuseSwitch, and only those",
            def.name
        );
    }
    let switches: Vec<&str> = PARAMS
        .iter()
        .filter(|p| p.role == Role::ReuseSwitch)
        .map(|p| p.name)
        .collect();
    assert_eq!(
        switches,
        [
            "temporal",
            "spatial",
            "gi_temporal",
            "gi_spatial",
            "pt_temporal",
            "pt_spatial"
        ]
    );
    let on = Settings::default();
    for mode in [crate::Mode::Nee, crate::Mode::Ris] {
        let s = mode.settings(&on);
        for name in &switches {
            assert_eq!(
                s.get(name),
                Some(ParamValue::Bool(false)),
                "{mode:?} leaves {name} on"
            );
        }
    }
    // restir keeps them; nee draws one light candidate and no BSDF candidate.
    assert_eq!(crate::Mode::Restir.settings(&on), on);
    let nee = crate::Mode::Nee.settings(&on);
    assert_eq!((nee.light_candidates, nee.bsdf_candidates), (1, 0));
    assert_eq!(
        crate::Mode::Ris.settings(&on).light_candidates,
        on.light_candidates
    );
}

/// The checks that temporal and spatial reuse share are one stage, so turning temporal
/// reuse off in the viewer does not grey them out.
#[test]
fn the_shared_validation_checks_are_their_own_stage() {
    for name in [
        "normal_threshold",
        "depth_threshold",
        "check_offscreen",
        "check_surface",
        "check_material",
        "check_normal",
        "check_depth",
        "check_reservoir",
        "check_target",
    ] {
        assert_eq!(
            Settings::def(name).unwrap().stage,
            Stage::Validation,
            "{name}"
        );
    }
    assert_eq!(
        Settings::def("check_target_ratio").unwrap().stage,
        Stage::Temporal
    );
}

/// Every numeric row answers a bad value with one line that names it: not a number is an
/// error, a number outside the range is clamped with a warning.
#[test]
fn every_numeric_row_answers_bad_values_in_one_line() {
    for def in PARAMS {
        let (low, high) = match def.kind {
            ParamKind::Int { min, max } => (min as f64 - 1.0, max as f64 + 1.0),
            ParamKind::Float { min, max } => (min - 1.0, max * 2.0 + 1.0),
            _ => continue,
        };
        let mut s = Settings::default();
        let err = s.set_from_str(def.name, "nan").unwrap_err().to_string();
        assert!(
            err.contains(def.name) && !err.contains('\n'),
            "{}: {err}",
            def.name
        );
        for value in [low, high] {
            let warning = s
                .set_from_str(def.name, &value.to_string())
                .unwrap_or_else(|e| panic!("{}: {e}", def.name))
                .unwrap_or_else(|| panic!("{} = {value}: no warning", def.name));
            assert!(
                warning.contains(def.name) && !warning.contains('\n'),
                "{}: {warning}",
                def.name
            );
        }
    }
}

#[test]
fn built_in_presets_apply_cleanly_by_name() {
    for (name, assignments, _) in preset::BUILTIN {
        let (s, warnings) = preset::load(Path::new(name), &Settings::default()).unwrap();
        assert!(warnings.is_empty(), "{name}: {warnings:?}");
        let mut expected = Settings::default();
        expected
            .apply_assignments(assignments.iter().copied())
            .unwrap();
        assert_eq!(s, expected, "{name}");
    }
    let denoised = preset::builtin("restir-denoised").unwrap();
    assert!(denoised.contains(&"denoise=true") && denoised.contains(&"m_cap=4"));
}

#[test]
fn gi_light_candidates_default_to_di_s_and_the_reference_keeps_the_table() {
    let mut s = Settings::default();
    assert_eq!(s.gpu_params(1080).gi.light_candidates, s.light_candidates);
    s.gi_light_candidates = 4;
    assert_eq!(s.gpu_params(1080).gi.light_candidates, 4);
    s.light_sampler = LightSampler::Bvh;
    s.bvh_at_vertices = false;
    let reference = s.for_reference();
    assert_eq!(reference.light_sampler, LightSampler::Power);
    assert!(reference.bvh_at_vertices);
    s.reference_light_bvh = true;
    assert_eq!(s.for_reference().light_sampler, LightSampler::Bvh);
}

/// Every `Params.flags` bit has one meaning: DI's, GI's and the denoiser's bits are
/// declared in their folders, the shared ones in shader_constants.rs.
#[test]
fn every_param_flag_is_its_own_bit() {
    use crate::denoise::constants::*;
    use crate::di::constants::*;
    use crate::gi::constants::*;
    let flags = [
        PARAM_FLAG_PERMUTATION,
        PARAM_FLAG_PAIRWISE,
        PARAM_FLAG_JITTER,
        PARAM_FLAG_INITIAL_VISIBILITY,
        PARAM_FLAG_PREVIOUS_LIGHTS,
        PARAM_FLAG_MIS_VISIBILITY,
        PARAM_FLAG_PREVIOUS_GEOMETRY,
        PARAM_FLAG_GRADIENT_ONLY,
        PARAM_FLAG_DENOISE_GRADIENTS,
        PARAM_FLAG_GI,
        PARAM_FLAG_GI_TEMPORAL,
        PARAM_FLAG_GI_SPATIAL,
        PARAM_FLAG_GI_SPATIAL_VISIBILITY,
        PARAM_FLAG_GI_PAIRWISE,
        PARAM_FLAG_GI_MIS_VISIBILITY,
    ];
    let mut seen = 0u32;
    for f in flags {
        assert_eq!(f.count_ones(), 1);
        assert_eq!(seen & f, 0, "flag {f:#x} used twice");
        seen |= f;
    }
}
