//! What the bench tests share: a temp directory, running `bench`, reading its CSV files and
//! checking its PNGs. Each test file uses a part, so the rest is dead code there.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh directory under cargo's per-test temp dir.
pub fn temp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bench_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `bench` with `args`; returns stderr. Fails with the command's output when it fails.
pub fn bench(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_restir-viewer"))
        .arg("bench")
        .args(args)
        .output()
        .expect("the restir-viewer binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        out.status.success(),
        "bench {args:?} failed (GPU tests need a wgpu adapter, lavapipe in CI):\n{stderr}"
    );
    stderr
}

/// A bench of `scene` at `size` with `args` added, quiet, its references cached in its own
/// output folder `temp(name)`: the rows of its results.csv.
pub fn quick_bench(
    name: &str,
    scene: &str,
    size: &str,
    args: &[&str],
) -> Vec<std::collections::HashMap<String, String>> {
    let out = temp(name);
    let cache = out.join("cache");
    let mut all = vec![
        "--scene",
        scene,
        "--size",
        size,
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--cache-dir",
        cache.to_str().unwrap(),
    ];
    all.extend(args);
    bench(&all);
    csv(&out.join("results.csv"))
}

/// Splits one CSV line, honouring quotes ("" inside quotes is a quote).
pub fn split_csv(line: &str) -> Vec<String> {
    let (mut cells, mut cell, mut quoted) = (Vec::new(), String::new(), false);
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => cells.push(std::mem::take(&mut cell)),
            _ => cell.push(c),
        }
    }
    cells.push(cell);
    cells
}

/// The rows of a CSV file as maps from header to cell.
pub fn csv(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = split_csv(lines.next().expect("a header"));
    lines
        .map(|l| header.iter().cloned().zip(split_csv(l)).collect())
        .collect()
}

pub fn assert_png(path: &Path) {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: not a PNG: {e}", path.display()));
    assert!(
        img.width() >= 800 && img.height() >= 300,
        "{}",
        path.display()
    );
    // Not blank: some pixels are neither white nor one colour.
    let rgb = img.to_rgb8();
    let dark = rgb
        .pixels()
        .filter(|p| p.0.iter().all(|&c| c < 100))
        .count();
    assert!(
        dark > 500,
        "{}: no text or axes drawn ({dark} dark pixels)",
        path.display()
    );
}
