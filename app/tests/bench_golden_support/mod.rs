//! Comparing a bench's output folder with the one stored under `app/tests/bench_golden/`:
//! the same files (PNGs by their size alone), every CSV and JSON number that is not a time
//! within a tolerance, every text cell identical, and `results.md` identical once the
//! cells and lines that state times are masked. Each difference comes back as one line
//! naming the file, the place, the stored value and the new one.
//!
//! Times are left out by name: lavapipe's are CPU wall-clock and move with the machine's
//! load, and so does whatever is read off them (an equal-time gain, the point where a
//! cost curve meets its target, which knob value is cheaper). The device string names the
//! machine's CPU and Mesa, so it is left out too.
//!
//! Tolerance: on this machine every number comes out bit for bit the same run after run,
//! on one lavapipe thread or many and at 128-bit vectors (`LP_NUM_THREADS=1`,
//! `LP_NATIVE_VECTOR_WIDTH=128`); without AVX and FMA (`GALLIUM_OVERRIDE_CPU_CAPS=sse4.1`)
//! numbers move by at most 0.02 %. A CPU whose code LLVM generates differently can flip a
//! pixel's random choice: llvmpipe told to use no SSE at all
//! (`GALLIUM_OVERRIDE_CPU_CAPS=nosse`, farther from this machine than any CI runner) moved
//! a number by at most 1.1 % of itself, but for a small one in a column of large ones
//! (0.01 % of its column's largest); a signed or squared bias (a difference of two
//! near-equal luminances, straddling zero) by 1.3 % of its column's largest; a 95 %
//! half-width over two seeds (t = 12.7 times their spread) by 7.6 % of its column's
//! largest. Hence a number may move by 2 % of itself plus 0.5 % of its column's largest
//! stored magnitude, a bias by 2 % of its column's largest, a half-width by 10 % of it.
//! A wiring mistake (another seed, another reference, another column) moves numbers by far
//! more: two seeds of one configuration differ by 20 % here.

use std::path::Path;

mod markdown;
mod numbers;

pub use numbers::csv_rows;

/// A number may move by this share of itself...
pub const TOLERANCE: f64 = 0.02;
/// ... plus this share of its column's largest stored magnitude.
pub const COLUMN_FLOOR: f64 = 0.005;
/// A bias (signed, or squared less the noise) may move by this share of its column's
/// largest stored magnitude.
pub const BIAS_TOLERANCE: f64 = 0.02;
/// A 95 % half-width over the seeds (`_ci95`, `half_width`) by this share of its column's.
pub const HALF_WIDTH_TOLERANCE: f64 = 0.10;

/// The file that lists a stored run's files (PNGs with their size), one per line.
pub const MANIFEST: &str = "files.txt";

/// The command line that made a folder: left out of its files, since it names the
/// folder's temporary path.
pub const COMMAND_FILE: &str = "command.txt";

/// Columns of times and of what is read off times (see the module comment).
pub fn is_timing_column(name: &str) -> bool {
    name.ends_with("_ms")
        || name.starts_with("ms_")
        || name.contains("_ms_")
        || name.starts_with("time_vs_")
        || name.starts_with("budget_")
        || name.starts_with("equal_time_gain")
        || matches!(
            name,
            // Where a cost curve meets its target depends on which point is cheaper.
            "reach"
                | "shadow_rays_per_pixel_at_target"
                | "light_candidates_per_pixel_at_target"
                | "reach_at_best"
                | "rays_per_pixel_at_best"
                // The machine, not the bench.
                | "device"
                | "timing"
        )
}

/// Every file under `dir`, relative, sorted; PNGs as `NAME.png WxH`. Leaves out the
/// command file and the reference cache.
pub fn manifest(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap().flatten() {
            let path = entry.path();
            let name = path
                .strip_prefix(dir)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            if path.is_dir() {
                if entry.file_name() != "cache" {
                    stack.push(path);
                }
                continue;
            }
            if entry.file_name() == COMMAND_FILE || entry.file_name() == MANIFEST {
                continue;
            }
            if name.ends_with(".png") {
                let (w, h) = image::image_dimensions(&path)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                out.push(format!("{name} {w}x{h}"));
            } else {
                out.push(name);
            }
        }
    }
    out.sort();
    out
}

/// The differences between the stored run `golden` and the new one `actual`.
pub fn compare_dirs(golden: &Path, actual: &Path) -> Vec<String> {
    let listed = std::fs::read_to_string(golden.join(MANIFEST))
        .unwrap_or_else(|e| panic!("{}: {e}", golden.join(MANIFEST).display()));
    let stored: Vec<String> = listed.lines().map(str::to_string).collect();
    let found = manifest(actual);
    let mut out = Vec::new();
    for f in stored.iter().filter(|f| !found.contains(f)) {
        out.push(format!("{f}: stored, not written now"));
    }
    for f in found.iter().filter(|f| !stored.contains(f)) {
        out.push(format!("{f}: written now, not stored"));
    }
    // A PNG's line holds its size after a space; a text file's holds its name alone.
    for f in stored.iter().filter(|f| !f.contains(' ')) {
        let (Ok(g), Ok(a)) = (
            std::fs::read_to_string(golden.join(f)),
            std::fs::read_to_string(actual.join(f)),
        ) else {
            continue;
        };
        out.extend(compare_text(f, &g, &a));
    }
    out
}

/// The differences between two versions of one file, by its kind.
pub fn compare_text(name: &str, golden: &str, actual: &str) -> Vec<String> {
    if name.ends_with(".csv") {
        compare_csv(name, golden, actual)
    } else if name.ends_with(".json") {
        compare_json(name, golden, actual)
    } else if name.ends_with(".md") {
        markdown::compare(name, golden, actual)
    } else if golden == actual {
        Vec::new()
    } else {
        vec![format!("{name}: differs")]
    }
}

/// How far a number of column `name` may move from `stored`, its column's largest stored
/// magnitude being `scale`.
fn allowed(name: &str, stored: f64, now: f64, scale: f64) -> f64 {
    if name.contains("ci95") || name.contains("half_width") {
        HALF_WIDTH_TOLERANCE * scale
    } else if name.contains("bias") {
        BIAS_TOLERANCE * scale
    } else {
        TOLERANCE * stored.abs().max(now.abs()) + COLUMN_FLOOR * scale
    }
}

fn compare_csv(name: &str, golden: &str, actual: &str) -> Vec<String> {
    let (g, a) = (numbers::csv_rows(golden), numbers::csv_rows(actual));
    if g.first() != a.first() {
        return vec![format!("{name}: header differs")];
    }
    if g.len() != a.len() {
        return vec![format!("{name}: {} rows stored, {} now", g.len(), a.len())];
    }
    let header = &g[0];
    let mut out = Vec::new();
    for (j, column) in header.iter().enumerate() {
        if is_timing_column(column) {
            continue;
        }
        let values: Vec<(&str, &str)> = g[1..]
            .iter()
            .zip(&a[1..])
            .map(|(gr, ar)| (cell(gr, j), cell(ar, j)))
            .collect();
        let scale = numbers::scale(values.iter().map(|(s, _)| *s));
        for (row, (s, n)) in values.iter().enumerate() {
            if !numbers::cells_agree(s, n, |a, b| allowed(column, a, b, scale)) {
                let key = cell(&g[row + 1], 0);
                out.push(format!(
                    "{name}: row {} ({key}), {column}: stored '{s}', now '{n}'",
                    row + 1
                ));
            }
        }
    }
    out
}

fn cell(row: &[String], j: usize) -> &str {
    row.get(j).map_or("", String::as_str)
}

/// Compares every leaf of two JSON documents; numbers within the tolerance of the largest
/// stored value at the same path (array positions alike).
fn compare_json(name: &str, golden: &str, actual: &str) -> Vec<String> {
    let parse = |t: &str| serde_json::from_str::<serde_json::Value>(t);
    let (Ok(g), Ok(a)) = (parse(golden), parse(actual)) else {
        return vec![format!("{name}: not JSON")];
    };
    let (mut gl, mut al) = (Vec::new(), Vec::new());
    numbers::leaves(&g, String::new(), &mut gl);
    numbers::leaves(&a, String::new(), &mut al);
    if gl.iter().map(|l| &l.0).ne(al.iter().map(|l| &l.0)) {
        return vec![format!("{name}: the fields differ")];
    }
    let mut out = Vec::new();
    for ((path, s), (_, n)) in gl.iter().zip(&al) {
        let shape = numbers::without_positions(path);
        let scale = numbers::scale(
            gl.iter()
                .filter(|(p, _)| numbers::without_positions(p) == shape)
                .map(|(_, v)| v.as_str()),
        );
        if !numbers::cells_agree(s, n, |a, b| allowed(path, a, b, scale)) {
            out.push(format!("{name}: {path}: stored {s}, now {n}"));
        }
    }
    out
}
