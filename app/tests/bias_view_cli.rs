//! `render --debug-view bias` end to end: it fetches the reference of the view (rendered
//! into `--cache-dir` the first time, loaded after), paints the running average's bias, and
//! refuses what has no single reference (a moving camera, scene time that plays).

mod cli_support;
use cli_support::{temp_dir, viewer};

/// Renders the bias view of the sun-lit Cornell box and returns the share of pixels it
/// painted blue (darker than the reference) and whether the reference came from the cache.
fn blue_share(cache: &str, extra: &[&str]) -> (f64, bool) {
    let dir = temp_dir("bias-out");
    let png = dir.join(format!("bias-{}.png", extra.len()));
    let png_arg = png.to_str().unwrap();
    let mut args = vec![
        "render",
        "--scene",
        "builtin:cornell",
        "--env",
        "builtin:sky",
        "--size",
        "48x36",
        "--frames",
        "96",
        "--set",
        "jitter=false",
        "--debug-view",
        "bias",
        "--reference-spp",
        "256",
        "--cache-dir",
        cache,
        "--out",
        png_arg,
    ];
    args.extend_from_slice(extra);
    let out = viewer(&args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{stderr}");
    let rendered_reference = stderr.contains("reference: ");
    let image = image::open(&png).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (48, 36));
    let blue = image
        .pixels()
        .filter(|p| p[2] > p[0] && p[2] > p[1])
        .count();
    (blue as f64 / (48.0 * 36.0), !rendered_reference)
}

#[test]
fn the_bias_view_renders_headless_against_a_cached_reference() {
    let cache = temp_dir("bias-cache");
    let cache = cache.to_str().unwrap();
    // Visibility reuse with unshadowed MIS terms darkens the sun's shadow edges
    // (docs/src/mis-and-bias.md, "Measured bias"): blue there. The first run renders the reference
    // into the cache.
    let (planted, from_cache) = blue_share(cache, &["--set", "mis_visibility=false"]);
    assert!(!from_cache, "the first run renders the reference");
    // The default estimator, against the same reference (now loaded): nearly all grey.
    let (default, from_cache) = blue_share(cache, &[]);
    assert!(
        from_cache,
        "the second run loads the reference from --cache-dir"
    );
    eprintln!("bias view blue share: mis_visibility off {planted:.3}, defaults {default:.3}");
    assert!(
        planted > 0.05,
        "the planted bias is not painted: {planted:.3}"
    );
    assert!(
        default < planted / 4.0,
        "defaults painted {default:.3} blue"
    );
}

#[test]
fn the_bias_view_refuses_what_has_no_single_reference() {
    let dir = temp_dir("bias-refuse");
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    let base = [
        "render",
        "--size",
        "16x12",
        "--frames",
        "2",
        "--debug-view",
        "bias",
        "--out",
        out,
    ];
    for (extra, needle) in [
        (
            vec!["--scene", "builtin:cornell", "--orbit", "1"],
            "still camera",
        ),
        (
            vec!["--scene", "builtin:dynamic:blinking-lights"],
            "--fps 0",
        ),
    ] {
        let args: Vec<&str> = base.iter().copied().chain(extra).collect();
        let result = viewer(&args);
        assert!(!result.status.success());
        assert_ne!(result.status.code(), Some(101), "panicked");
        let stderr = String::from_utf8_lossy(&result.stderr);
        let errors: Vec<&str> = stderr
            .lines()
            .filter(|l| l.starts_with("error: "))
            .collect();
        assert_eq!(errors.len(), 1, "{stderr}");
        assert!(errors[0].contains(needle), "{}", errors[0]);
    }
}
