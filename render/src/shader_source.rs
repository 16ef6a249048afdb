//! WGSL composition: one mechanism for every pass. A pass file names its modules with
//! `#include "common/x.wgsl"` (each included once) and guards optional code with
//! `#ifdef EFFECT` / `#ifndef` / `#else` / `#endif`, so a pipeline compiled for a scene
//! contains only the code paths that scene needs (see `effects.rs`). The generated
//! constants of `shader_constants.rs` come first.
//!
//! Debug builds read the files from `shaders/` on disk (edit a shader, rebuild the
//! pipelines, see the change); release builds use the copies embedded at compile time.

use std::collections::BTreeSet;
use std::path::PathBuf;

use crate::wgsl_constants::WgslValue;
use crate::{gpu_types, shader_constants as k, view};

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/embedded_shaders.rs"));
}

#[derive(Debug, thiserror::Error)]
pub enum ShaderSourceError {
    #[error("shader '{0}' does not exist")]
    Missing(String),
    #[error("{file}:{line}: {message}")]
    Syntax {
        file: String,
        line: usize,
        message: String,
    },
}

/// The on-disk shader folder, used in debug builds when it exists.
fn disk_dir() -> Option<PathBuf> {
    if cfg!(debug_assertions) {
        let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders"));
        dir.is_dir().then_some(dir)
    } else {
        None
    }
}

/// The text of one shader file (`path` relative to `shaders/`).
pub fn shader_file(path: &str) -> Result<String, ShaderSourceError> {
    if let Some(text) = disk_dir().and_then(|dir| std::fs::read_to_string(dir.join(path)).ok()) {
        return Ok(text);
    }
    embedded::EMBEDDED_SHADERS
        .iter()
        .find(|(name, _)| *name == path)
        .map(|(_, text)| text.to_string())
        .ok_or_else(|| ShaderSourceError::Missing(path.to_string()))
}

/// Composes `entry` with its includes for the given set of defines.
///
/// The `// Defines:` line names only the defines this pass's files test, not the whole
/// set: two effect sets that give a pass the same code then give it the same text. Debug
/// builds hand wgpu the text as the SPIR-V's debug source (wgpu's `InstanceFlags::DEBUG`),
/// which the driver's shader cache keys on, so a define that only some passes test
/// (a planted error, a PT shift) no longer makes a new text of all the others; on lavapipe
/// a first run's compiles are most of the test suite's time (docs/src/getting-started.md,
/// "How long the tests take").
pub fn compose(entry: &str, defines: &BTreeSet<String>) -> Result<String, ShaderSourceError> {
    let mut body = String::new();
    let mut included = BTreeSet::new();
    let mut tested = BTreeSet::new();
    append_file(entry, defines, &mut included, &mut tested, &mut body)?;
    // WGSL wants `enable` directives before any declaration.
    let mut out = if defines.contains(crate::tracing::RAY_QUERY_DEFINE) {
        String::from("enable wgpu_ray_query;\n")
    } else {
        String::new()
    };
    out.push_str(&wgsl_prelude());
    out.push_str("// Defines:");
    for d in defines.iter().filter(|d| tested.contains(d.as_str())) {
        out.push(' ');
        out.push_str(d);
    }
    out.push('\n');
    out.push_str(&body);
    Ok(out)
}

/// Appends `path` (and its includes, each once) to `out` with the `#ifdef` branches that
/// `defines` selects; `tested` collects the names of `defines` that a directive tested.
fn append_file(
    path: &str,
    defines: &BTreeSet<String>,
    included: &mut BTreeSet<String>,
    tested: &mut BTreeSet<String>,
    out: &mut String,
) -> Result<(), ShaderSourceError> {
    if !included.insert(path.to_string()) {
        return Ok(());
    }
    let text = shader_file(path)?;
    // Each entry: (this branch is active, some branch of this #if was already taken).
    let mut stack: Vec<(bool, bool)> = Vec::new();
    let syntax = |line: usize, message: &str| ShaderSourceError::Syntax {
        file: path.to_string(),
        line: line + 1,
        message: message.to_string(),
    };
    for (number, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let active = stack.iter().all(|(a, _)| *a);
        if let Some(rest) = trimmed.strip_prefix('#') {
            let mut words = rest.split_whitespace();
            let directive = words.next().unwrap_or("");
            let arg = words.next();
            match directive {
                "include" => {
                    let name = arg
                        .and_then(|a| a.strip_prefix('"')?.strip_suffix('"'))
                        .ok_or_else(|| syntax(number, "#include needs a quoted path"))?;
                    if active {
                        append_file(name, defines, included, tested, out)?;
                    }
                }
                "ifdef" | "ifndef" => {
                    let name = arg.ok_or_else(|| syntax(number, "#ifdef needs a name"))?;
                    if active && defines.contains(name) {
                        tested.insert(name.to_string());
                    }
                    let truth = defines.contains(name) == (directive == "ifdef");
                    stack.push((truth, truth));
                }
                "else" => {
                    let top = stack
                        .last_mut()
                        .ok_or_else(|| syntax(number, "#else without #ifdef"))?;
                    top.0 = !top.1;
                    top.1 = true;
                }
                "endif" => {
                    stack
                        .pop()
                        .ok_or_else(|| syntax(number, "#endif without #ifdef"))?;
                }
                other => return Err(syntax(number, &format!("unknown directive #{other}"))),
            }
            continue;
        }
        if active {
            out.push_str(line);
            out.push('\n');
        }
    }
    if !stack.is_empty() {
        return Err(syntax(text.lines().count(), "missing #endif"));
    }
    Ok(())
}

/// Every shader file name known to the library (for tests that compile them all).
pub fn all_shader_files() -> Vec<&'static str> {
    embedded::EMBEDDED_SHADERS
        .iter()
        .map(|(name, _)| *name)
        .collect()
}

/// The WGSL prelude: every constant declared in a `wgsl_constants!` block (in
/// shader_constants.rs, gpu_types.rs, view.rs and each technique's constants.rs) as a WGSL `const`: one row emits the Rust
/// constant and its WGSL line. It is assembled here, above the blocks, so that the constant
/// modules need not know one another (docs/src/source-layout.md, "Layers").
pub fn wgsl_prelude() -> String {
    let mut out = String::from(
        "// Generated from the wgsl_constants! blocks (render/src/shader_constants.rs, each technique's constants.rs): edit there.\n",
    );
    let blocks: [fn() -> Vec<(&'static str, WgslValue)>; 22] = [
        gpu_types::absent_markers,
        gpu_types::material_flags,
        gpu_types::texture_packing,
        gpu_types::light_kinds,
        gpu_types::punctual_kinds,
        view::view_codes,
        k::rejection_bits,
        k::surface_checks,
        k::sources,
        k::proposers,
        k::shared_flags_and_passes,
        k::counters,
        k::indirect_techniques,
        k::streams_and_limits,
        k::motion_and_view_limits,
        k::tonemappers_and_gi_rejections,
        k::inspector,
        // Each technique's own constants.
        crate::di::constants::packing_and_flags,
        crate::gi::constants::packing_and_flags,
        crate::pt::constants::shifts_and_failures,
        crate::pt::constants::probe,
        crate::denoise::constants::denoiser,
    ];
    for block in blocks {
        for (name, value) in block() {
            out.push_str(&value.declaration(name));
            out.push('\n');
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn defines(names: &[&str]) -> BTreeSet<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn includes_each_module_once() {
        let src = compose("di/initial.wgsl", &defines(&["AREA_LIGHTS"])).unwrap();
        assert_eq!(src.matches("struct Reservoir {").count(), 1);
        assert!(src.contains("fn reservoir_update"));
    }

    #[test]
    fn ifdef_removes_code_of_absent_effects() {
        let without = compose("common/brdf.wgsl", &defines(&[])).unwrap();
        let with = compose("common/brdf.wgsl", &defines(&["SPECULAR"])).unwrap();
        assert!(!without.contains("ggx_d"));
        assert!(with.contains("fn ggx_d"));
    }

    #[test]
    fn the_text_names_only_the_defines_its_files_test() {
        let brdf = compose("common/brdf.wgsl", &defines(&["SPECULAR"])).unwrap();
        assert!(brdf.contains("// Defines: SPECULAR\n"), "{brdf}");
        // A define no file of the pass tests (here a planted error of PT's) leaves the
        // text, and so the driver's cached compile of it, as it was.
        let planted = compose(
            "common/brdf.wgsl",
            &defines(&["SPECULAR", "PLANTED_PT_NO_JACOBIAN"]),
        )
        .unwrap();
        assert_eq!(brdf, planted);
    }

    #[test]
    fn missing_file_is_named() {
        let (mut included, mut tested) = (BTreeSet::new(), BTreeSet::new());
        let mut out = String::new();
        // A missing file is reported by name.
        let err = append_file(
            "no/such.wgsl",
            &defines(&[]),
            &mut included,
            &mut tested,
            &mut out,
        )
        .unwrap_err();
        assert!(err.to_string().contains("no/such.wgsl"));
    }
}
