//! Markdown as every bench table is written: numbers to 4 significant digits, times to two
//! decimals, ratios with ×, tables, the timing footnote, and the pass-time table that
//! results.md and the light-count sweep share.

use super::passes::pass_names;
use crate::bench::score::result::ConfigResult;

/// A number with 4 significant digits (errors), or "n/a".
pub fn sig(x: Option<f64>) -> String {
    match x {
        Some(0.0) => "0".into(),
        Some(v) if v.is_finite() => {
            let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 8) as usize;
            format!("{v:.digits$}")
        }
        Some(v) => format!("{v}"),
        None => "n/a".into(),
    }
}

/// Milliseconds with two decimals (or "n/a").
pub fn ms(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.2}")).unwrap_or_else(|| "n/a".into())
}

/// A ratio like `1.23×`.
pub fn ratio(x: Option<f64>) -> String {
    x.map(|v| format!("{v:.2}×"))
        .unwrap_or_else(|| "n/a".into())
}

/// One Markdown table.
pub fn table(out: &mut String, header: &[String], rows: &[Vec<String>]) {
    let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
    out.push_str(&line(header));
    out.push_str(&line(&vec!["---".to_string(); header.len()]));
    for r in rows {
        out.push_str(&line(r));
    }
}

/// The `[^t]` footnote on every time: what kind of time it is.
pub fn time_footnote(note: &str) -> String {
    format!("[^t]: {note}.\n")
}

/// Median time of each pass (columns) per labelled result (rows), and the frame's.
pub fn pass_table(md: &mut String, label: &str, labelled: &[(String, &ConfigResult)]) {
    let passes = pass_names(labelled.iter().map(|(_, r)| *r));
    let mut header = vec![label.to_string()];
    header.extend(passes.iter().cloned());
    header.push("frame".into());
    let rows: Vec<Vec<String>> = labelled
        .iter()
        .map(|(name, r)| {
            let mut row = vec![name.clone()];
            row.extend(passes.iter().map(|p| {
                r.times
                    .pass_ms_median
                    .get(p)
                    .map(|v| format!("{v:.2}"))
                    .unwrap_or_else(|| "–".into())
            }));
            row.push(ms(r.median_frame_ms()));
            row
        })
        .collect();
    table(md, &header, &rows);
}

/// "on" or "off".
pub fn on_off(b: bool) -> &'static str {
    if b { "on" } else { "off" }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_numbers_format_for_tables() {
        assert_eq!(sig(Some(0.145912)), "0.1459");
        assert_eq!(sig(Some(0.0041987)), "0.004199");
        assert_eq!(sig(Some(123.456)), "123.5");
        assert_eq!(sig(None), "n/a");
        assert_eq!(ms(Some(1.23456)), "1.23");
        assert_eq!(ratio(Some(0.5)), "0.50×");
        let mut out = String::new();
        table(
            &mut out,
            &["a".into(), "b".into()],
            &[vec!["1".into(), "2".into()]],
        );
        assert_eq!(out, "| a | b |\n| --- | --- |\n| 1 | 2 |\n");
    }
}
