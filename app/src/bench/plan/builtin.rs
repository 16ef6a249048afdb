//! The built-in configurations a bench compares, by name: the estimators (`nee`, `ris`, the
//! reuse steps, `restir`, `restir-pairwise`), GI and PT on top, the path-traced `path-2b`,
//! and the pairs of a sweep (`tiles-on`, `tiles-off`). `configs.rs` parses names into them.

use restir_render::Mode;
use restir_render::settings::preset;

/// The built-in configurations: name, mode and the parameters that define them (applied
/// after the base settings, so `--set` cannot undo what makes a configuration itself).
pub const BUILTIN: &[(&str, Mode, &[&str], &str)] = &[
    (
        "nee",
        Mode::Nee,
        &[],
        "one power-sampled light sample per pixel",
    ),
    ("ris", Mode::Ris, &[], "initial RIS, no reuse"),
    (
        "ris+temporal",
        Mode::Restir,
        &["temporal=true", "spatial=false"],
        "RIS + temporal reuse",
    ),
    (
        "ris+spatial",
        Mode::Restir,
        &["temporal=false", "spatial=true"],
        "RIS + spatial reuse",
    ),
    (
        "restir",
        Mode::Restir,
        &[
            "temporal=true",
            "spatial=true",
            "bias_correction=one-over-m",
        ],
        "RIS + temporal + spatial, 1/M weights (biased; the default before pairwise)",
    ),
    (
        "restir-pairwise",
        Mode::Restir,
        &["temporal=true", "spatial=true", "bias_correction=pairwise"],
        "RIS + temporal + spatial, pairwise MIS (unbiased; the default)",
    ),
    (
        "path-2b",
        Mode::Reference,
        &["reference_spp=1", "max_bounces=2"],
        "one-sample brute-force path tracing, 2 bounces (the reference estimator at 1 spp, per frame; scored against a 2-bounce reference)",
    ),
    (
        "restir+gi",
        Mode::Restir,
        &["gi=true", "gi_bias_correction=one-over-m", "max_bounces=2"],
        "restir (DI) + ReSTIR GI with 1/M weights (biased); scored against a 2-bounce reference",
    ),
    (
        "restir+gi-pairwise",
        Mode::Restir,
        &["gi=true", "gi_bias_correction=pairwise", "max_bounces=2"],
        "restir (DI) + ReSTIR GI with pairwise MIS (the GI default); scored against a 2-bounce reference",
    ),
    (
        "path-3b",
        Mode::Reference,
        &["reference_spp=1", "max_bounces=3"],
        "one-sample brute-force path tracing, 3 bounces; scored against a 3-bounce reference",
    ),
    (
        "restir+pt",
        Mode::Restir,
        &["pt=true", "pt_shift=hybrid", "max_bounces=2"],
        "restir (DI) + ReSTIR PT, hybrid shift, paths of 2 bounces (GI's path space); scored against a 2-bounce reference",
    ),
    (
        "restir+pt-reconnection",
        Mode::Restir,
        &["pt=true", "pt_shift=reconnection", "max_bounces=2"],
        "restir (DI) + ReSTIR PT, reconnection shift, 2 bounces",
    ),
    (
        "restir+pt-replay",
        Mode::Restir,
        &["pt=true", "pt_shift=random-replay", "max_bounces=2"],
        "restir (DI) + ReSTIR PT, random-replay shift, 2 bounces",
    ),
    (
        "restir+pt-3b",
        Mode::Restir,
        &["pt=true", "pt_shift=hybrid", "max_bounces=3"],
        "restir (DI) + ReSTIR PT, hybrid shift, paths of up to 3 bounces; scored against a 3-bounce reference",
    ),
    (
        "restir+pt-spatial-only",
        Mode::Restir,
        &[
            "pt=true",
            "pt_shift=hybrid",
            "max_bounces=2",
            "pt_temporal=false",
        ],
        "restir (DI) + ReSTIR PT, hybrid shift, 2 bounces, spatial path reuse only (what temporal reuse adds)",
    ),
    (
        "restir+pt-clamped",
        Mode::Restir,
        &[
            "pt=true",
            "pt_shift=hybrid",
            "max_bounces=2",
            "pt_jacobian_clamp=2",
        ],
        "restir (DI) + ReSTIR PT, hybrid shift, 2 bounces, |J| clamped into [1/2, 2] (biased)",
    ),
    (
        "restir-denoised",
        Mode::Restir,
        preset::RESTIR_DENOISED,
        "the restir-denoised preset: temporal reuse at M cap 4, no spatial reuse, denoised (SVGF)",
    ),
    (
        "tiles-on",
        Mode::Restir,
        &["light_sampler=tiles"],
        "restir defaults with light tiles (the tiles sweep)",
    ),
    (
        "tiles-off",
        Mode::Restir,
        &["light_sampler=power"],
        "restir defaults with the power table (the tiles sweep)",
    ),
];
