//! `results.md`, `sweep.md` and `map.md` against their stored versions: line by line the
//! same text once every number is set aside, and the numbers close. Cells and lines that
//! state times (or what is read off them) are masked; table headers are compared whole.
//!
//! A Markdown number is a CSV number rounded, and the CSV comparison holds those to 2 % of
//! their column (`super::TOLERANCE`). Here a number may move by 10 % of itself plus one
//! unit in its last printed digit: the widest spread seen (a 2-seed half-width, see the
//! module comment of `super`), without which rounding alone (0.09995 printed as 0.1000)
//! would be reported.

use super::numbers::split_numbers;

/// How far a Markdown number may move, as a share of its magnitude.
const MARKDOWN_TOLERANCE: f64 = 0.10;

/// Table columns of times or read off times, by their exact header.
const TIMING_HEADERS: [&str; 13] = [
    "ms/frame[^t]",
    "time × nee[^t]",
    "ms/frame (seeds' medians)",
    "equal-time gain[^g]",
    "verdict",
    "time used (ms)[^t]",
    "ms per frame at the target",
    "vs the first",
    "shadow rays / px",
    "light candidates / px",
    "scene load (ms)[^t]",
    "upload (ms)[^t]",
    "BVH build (ms)[^t]",
];

/// Lines (outside tables) that state the machine or times.
const TIMING_LINES: [&str; 4] = [
    "- Device: ",
    ": time per frame ",
    " is faster than ",
    "- neither `",
];

/// Which columns of a table are masked: those of `TIMING_HEADERS` and per-configuration
/// times (`` `nee` ms/frame[^t] ``); every column but the first under a heading of times
/// (the pass table, the sweep's relative times); every configuration column of the
/// crossover map, whose cells are cost ratios.
fn masked_columns(header: &[String], heading: &str) -> Vec<bool> {
    let all_times = heading.contains("time per pass") || heading.contains("ratios within this run");
    let map = header.iter().any(|h| h == "cheapest");
    header
        .iter()
        .enumerate()
        .map(|(i, h)| {
            if all_times {
                i > 0
            } else if map {
                !matches!(h.as_str(), "scene" | "camera" | "settings")
            } else {
                TIMING_HEADERS.contains(&h.as_str())
                    || h.ends_with(" ms/frame[^t]")
                    || h.ends_with(" (ms)[^t]")
            }
        })
        .collect()
}

/// The cells of a table row (`| a | b |`), `\|` kept inside its cell.
fn cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
    let mut out = vec![String::new()];
    let mut chars = inner.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                out.last_mut().unwrap().push_str("\\|");
                chars.next();
            }
            '|' => out.push(String::new()),
            c => out.last_mut().unwrap().push(c),
        }
    }
    out.into_iter().map(|c| c.trim().to_string()).collect()
}

/// Whether two pieces of text agree: the same skeleton, each number within the tolerance.
fn agree(stored: &str, now: &str) -> bool {
    let (s, sn) = split_numbers(stored);
    let (n, nn) = split_numbers(now);
    s == n
        && sn.len() == nn.len()
        && sn.iter().zip(&nn).all(|((a, unit), (b, _))| {
            (a - b).abs() <= MARKDOWN_TOLERANCE * a.abs().max(b.abs()) + unit
        })
}

pub fn compare(name: &str, golden: &str, actual: &str) -> Vec<String> {
    let (g, a): (Vec<&str>, Vec<&str>) = (golden.lines().collect(), actual.lines().collect());
    if g.len() != a.len() {
        return vec![format!("{name}: {} lines stored, {} now", g.len(), a.len())];
    }
    let mut out = Vec::new();
    let mut heading = "";
    let mut masks: Option<Vec<bool>> = None;
    for (n, (s, w)) in g.iter().zip(&a).enumerate() {
        let line = n + 1;
        if !s.starts_with('|') {
            masks = None;
            if s.starts_with('#') {
                heading = s;
            }
            if !TIMING_LINES.iter().any(|t| s.contains(t)) && !agree(s, w) {
                out.push(format!("{name}:{line}: stored '{s}', now '{w}'"));
            }
            continue;
        }
        let (sc, wc) = (cells(s), cells(w));
        let Some(mask) = &masks else {
            // A table's first row: its header, whole.
            if s != w {
                out.push(format!("{name}:{line}: header stored '{s}', now '{w}'"));
            }
            masks = Some(masked_columns(&sc, heading));
            continue;
        };
        if sc.len() != wc.len() {
            out.push(format!(
                "{name}:{line}: {} cells stored, {} now",
                sc.len(),
                wc.len()
            ));
            continue;
        }
        for (i, (x, y)) in sc.iter().zip(&wc).enumerate() {
            if !mask.get(i).copied().unwrap_or(false) && !agree(x, y) {
                out.push(format!(
                    "{name}:{line}, cell {}: stored '{x}', now '{y}'",
                    i + 1
                ));
            }
        }
    }
    out
}
