//! `bench-load`'s compile table: where the first frame's shader compile goes, by pass and
//! effect set. A pipeline's creation plus its first dispatch, less what the pass takes once
//! compiled, is its compile (a CPU driver compiles at the first dispatch;
//! docs/src/compile-time.md). Printed as Markdown, written as CSV; never a timing assertion.

use std::collections::BTreeMap;

use restir_render::PipelineCompile;

/// One pipeline's row.
#[derive(Clone, Debug, PartialEq)]
pub struct CompileRow {
    pub pass: &'static str,
    pub variant: String,
    pub create_ms: f64,
    pub first_dispatch_ms: Option<f64>,
    /// The median of the pass's later dispatches (`None` when it ran once).
    pub steady_ms: Option<f64>,
}

impl CompileRow {
    /// Creation plus the first dispatch's excess over a steady dispatch.
    pub fn compile_ms(&self) -> f64 {
        let first = self.first_dispatch_ms.unwrap_or(0.0);
        self.create_ms + (first - self.steady_ms.unwrap_or(0.0)).max(0.0)
    }
}

/// The rows of `compiles`, the slowest first, with each pass's steady time from `frames`
/// (each frame's per-pass milliseconds, the first dispatches left out by the caller).
pub fn rows(compiles: &[PipelineCompile], frames: &[Vec<(&'static str, f64)>]) -> Vec<CompileRow> {
    let mut times: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for frame in frames {
        for (pass, ms) in frame {
            times.entry(pass).or_default().push(*ms);
        }
    }
    let mut rows: Vec<CompileRow> = compiles
        .iter()
        .map(|c| CompileRow {
            pass: c.pass,
            variant: c.variant.clone(),
            create_ms: c.ms,
            first_dispatch_ms: c.first_dispatch_ms,
            steady_ms: times.get(c.pass).map(|t| median(t)),
        })
        .collect();
    rows.sort_by(|a, b| b.compile_ms().total_cmp(&a.compile_ms()));
    rows
}

fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ms(value: Option<f64>) -> String {
    value.map_or_else(|| "–".to_string(), |v| format!("{v:.1}"))
}

/// The table, with the effect set once above it when every row shares it.
pub fn markdown(rows: &[CompileRow]) -> String {
    let total: f64 = rows.iter().map(CompileRow::compile_ms).sum();
    let mut md = format!(
        "\nCompile time by pass: {:.1} s in all (creation + first dispatch − steady dispatch)\n\n",
        total / 1e3
    );
    let one_variant = rows.windows(2).all(|w| w[0].variant == w[1].variant);
    if let (true, Some(r)) = (one_variant, rows.first()) {
        md.push_str(&format!("effect set: {}\n\n", r.variant));
    }
    md.push_str("| pass | compile ms | share | creation ms | first dispatch ms | steady ms |");
    md.push_str(if one_variant { "\n" } else { " variant |\n" });
    md.push_str("| --- | --- | --- | --- | --- | --- |");
    md.push_str(if one_variant { "\n" } else { " --- |\n" });
    for r in rows {
        md.push_str(&format!(
            "| {} | {:.1} | {:.1} % | {:.1} | {} | {} |",
            r.pass,
            r.compile_ms(),
            100.0 * r.compile_ms() / total.max(1e-9),
            r.create_ms,
            ms(r.first_dispatch_ms),
            ms(r.steady_ms)
        ));
        if !one_variant {
            md.push_str(&format!(" {} |", r.variant));
        }
        md.push('\n');
    }
    md
}

pub fn csv(scene: &str, rows: &[CompileRow]) -> String {
    let mut out =
        String::from("scene,pass,variant,compile_ms,creation_ms,first_dispatch_ms,steady_ms\n");
    let opt = |v: Option<f64>| v.map_or_else(String::new, |v| format!("{v:.3}"));
    for r in rows {
        out.push_str(&format!(
            "{scene},{},\"{}\",{:.3},{:.3},{},{}\n",
            r.pass,
            r.variant,
            r.compile_ms(),
            r.create_ms,
            opt(r.first_dispatch_ms),
            opt(r.steady_ms)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn compile(pass: &'static str, ms: f64, first: Option<f64>) -> PipelineCompile {
        PipelineCompile {
            pass,
            variant: "AREA_LIGHTS,SHADOWS".into(),
            ms,
            first_dispatch_ms: first,
        }
    }

    #[test]
    fn the_compile_is_creation_plus_the_first_dispatch_beyond_a_steady_one() {
        let compiles = [
            compile("initial", 10.0, Some(5000.0)),
            compile("shade", 5.0, Some(900.0)),
            compile("display", 1.0, None),
        ];
        let frames = vec![
            vec![("initial", 20.0), ("shade", 4.0)],
            vec![("initial", 30.0), ("shade", 6.0)],
            vec![("initial", 25.0), ("shade", 5.0)],
        ];
        let rows = rows(&compiles, &frames);
        assert_eq!(rows[0].pass, "initial", "slowest first");
        assert_eq!(rows[0].steady_ms, Some(25.0));
        assert!((rows[0].compile_ms() - (10.0 + 5000.0 - 25.0)).abs() < 1e-9);
        assert!((rows[1].compile_ms() - (5.0 + 900.0 - 5.0)).abs() < 1e-9);
        // Never dispatched: its creation alone.
        assert_eq!(rows[2].compile_ms(), 1.0);
        let md = markdown(&rows);
        assert!(md.contains("| initial | 4985.0 |"), "{md}");
        assert!(md.contains("effect set: AREA_LIGHTS,SHADOWS"), "{md}");
        let csv = csv("builtin:cornell", &rows);
        assert_eq!(csv.lines().count(), 4);
        assert!(
            csv.lines()
                .nth(1)
                .unwrap()
                .starts_with("builtin:cornell,initial,")
        );
    }
}
