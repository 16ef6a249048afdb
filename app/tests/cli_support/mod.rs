//! What the headless-command tests share: running the binary and a temp directory.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `restir-viewer` with `args` (lavapipe's runtime-dir warning kept quiet).
pub fn viewer(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("run restir-viewer")
}

/// A directory for one test's files, unique to this process.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("restir-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
