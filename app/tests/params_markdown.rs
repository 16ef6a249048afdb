//! The book's parameters page is generated from the settings table
//! (`restir-viewer params --markdown`); this test fails when docs/src/parameters.md no
//! longer matches what the command prints, so the page cannot drift from the table.

use std::path::Path;
use std::process::Command;

const REGENERATE: &str =
    "run `cargo run -p restir-viewer -- params --markdown > docs/src/parameters.md`";

fn params_markdown() -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args(["params", "--markdown"])
        .output()
        .expect("run restir-viewer params --markdown");
    assert!(
        out.status.success(),
        "`restir-viewer params --markdown` failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("the parameters page is UTF-8")
}

#[test]
fn the_parameters_page_matches_the_settings_table() {
    let generated = params_markdown();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/src/parameters.md");
    let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
    // Line endings are the checkout's business, not the page's.
    if on_disk.replace("\r\n", "\n") != generated {
        let first_difference = on_disk
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .map_or_else(
                || "one is a prefix of the other".to_string(),
                |i| format!("first difference at line {}", i + 1),
            );
        panic!("docs/src/parameters.md is stale ({first_difference}): {REGENERATE}");
    }
}

#[test]
fn the_parameters_page_lists_every_parameter_once() {
    let generated = params_markdown();
    for def in restir_render::settings::PARAMS {
        let heading = format!("\n### {}\n", def.name);
        assert_eq!(
            generated.matches(&heading).count(),
            1,
            "`params --markdown` has no single section for {}",
            def.name
        );
        assert!(
            generated.contains(&format!("| [`{0}`](#{0}) |", def.name)),
            "{} is missing from the overview table",
            def.name
        );
    }
}
