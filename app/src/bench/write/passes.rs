//! The passes a bench timed, in pipeline order, and their columns: what results.csv, the
//! pass-time tables and plots and the light-count sweep share.

use std::collections::BTreeSet;

use crate::bench::score::result::ConfigResult;

use super::table::num;

/// The passes in pipeline order; others (from a newer renderer) follow alphabetically.
pub const PASS_ORDER: &[&str] = &[
    "gbuffer raster",
    "gbuffer resolve",
    "initial",
    "temporal",
    "spatial",
    "mutation",
    "shade",
    "display",
];

/// Every pass any result timed, in pipeline order.
pub fn pass_names<'a>(results: impl IntoIterator<Item = &'a ConfigResult>) -> Vec<String> {
    let seen: BTreeSet<&String> = results
        .into_iter()
        .flat_map(|r| r.times.pass_ms_median.keys())
        .collect();
    let mut names: Vec<String> = PASS_ORDER
        .iter()
        .filter(|p| seen.iter().any(|s| s == p))
        .map(|p| p.to_string())
        .collect();
    names.extend(
        seen.into_iter()
            .filter(|s| !PASS_ORDER.contains(&s.as_str()))
            .cloned(),
    );
    names
}

/// Column names of the passes' median times: `initial_ms`, `gbuffer_raster_ms`, ...
pub fn pass_columns(passes: &[String]) -> Vec<String> {
    passes
        .iter()
        .map(|p| format!("{}_ms", p.replace(' ', "_")))
        .collect()
}

/// The passes' median times of one result, in `pass_columns` order.
pub fn pass_cells<'a>(
    passes: &'a [String],
    r: &'a ConfigResult,
) -> impl Iterator<Item = String> + 'a {
    passes
        .iter()
        .map(|p| num(r.times.pass_ms_median.get(p).copied()))
}
