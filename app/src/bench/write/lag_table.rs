//! results.md's lag table: per configuration and light event, the lag metrics averaged over
//! the seeds (score/lag.rs; docs/src/measured/dynamic-scenes.md, "Lag and ghosting").

use std::fmt::Write;

use super::info::BenchInfo;
use super::markdown::{sig, table};
use crate::bench::score::result::ConfigResult;

/// Per configuration and event: the lag metrics (docs/src/measured/how-the-bench-measures.md,
/// "Light events: lag and ghosting").
pub fn lag_table(md: &mut String, info: &BenchInfo, results: &[ConfigResult]) {
    if results.iter().all(|r| r.lag.is_empty()) {
        return;
    }
    let source = match info.event_source {
        Some("scene") => "the scene's own event list (STEP light keys)",
        _ => "detected where the references change",
    };
    let _ = writeln!(
        md,
        "\n## Lag around events ({} seed{}, events from {source})\n",
        info.seeds,
        if info.seeds == 1 { "" } else { "s, averaged" }
    );
    let _ = writeln!(
        md,
        "Steady = median error of the event's last 5 frames; recovery = frames until 5 in a row are ≤ 1.1 × steady; lag area = Σ max(error − steady, 0); signed bias = Σ(frame − reference) / Σ reference luminance where the reference changed > 10 %, first 5 frames (+ ghosting, − dark lag).\n"
    );
    let header: Vec<String> = [
        "configuration",
        "event (frame, time)",
        "peak error",
        "steady error",
        "peak / steady",
        "recovery frames",
        "lag area",
        "signed bias",
    ]
    .map(String::from)
    .to_vec();
    let rows: Vec<Vec<String>> = results
        .iter()
        .flat_map(|r| {
            r.lag.iter().map(|e| {
                vec![
                    format!("`{}`", r.config.name),
                    format!("{}, {:.3} s", e.frame, e.time),
                    sig(e.peak_error),
                    sig(e.steady_error),
                    sig(e.peak_over_steady),
                    match e.recovery_frames {
                        Some(Some(v)) => format!("{v:.1}"),
                        Some(None) => "never".into(),
                        None => "n/a".into(),
                    },
                    sig(e.lag_area),
                    e.signed_bias
                        .map(|b| format!("{b:+.4}"))
                        .unwrap_or_else(|| "n/a".into()),
                ]
            })
        })
        .collect();
    table(md, &header, &rows);
}
