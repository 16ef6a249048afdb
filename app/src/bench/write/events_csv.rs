//! A dynamic scene's lag around its light events in CSV (score/lag.rs measures it):
//! `events.csv`, one row per configuration and event, and the lag columns `results.csv`
//! carries, one row per event.

use std::path::Path;

use super::table::{Table, num};
use crate::bench::score::lag::EventLag;
use crate::bench::score::result::ConfigResult;

/// The lag columns of `results.csv`: the number of events, which one this row is (0, 1,
/// ...), and its numbers averaged over the seeds; empty without events (a static scene,
/// frozen time), where a configuration keeps its single row.
pub const LAG_COLUMNS: [&str; 12] = [
    "events",
    "event",
    "event_source",
    "event_frame",
    "event_time",
    "seeds",
    "peak_error",
    "steady_error",
    "peak_over_steady",
    "recovery_frames",
    "lag_area",
    "signed_bias",
];

/// The `LAG_COLUMNS` cells of one configuration's rows: one row per event, or a single
/// empty row without events.
pub fn lag_rows(event_source: Option<&str>, lag: &[EventLag]) -> Vec<Vec<String>> {
    if lag.is_empty() {
        return vec![vec![String::new(); LAG_COLUMNS.len()]];
    }
    lag.iter()
        .enumerate()
        .map(|(k, e)| {
            let mut cells = vec![
                lag.len().to_string(),
                k.to_string(),
                event_source.unwrap_or_default().to_string(),
            ];
            cells.extend(event_cells(e));
            cells
        })
        .collect()
}

/// Frame, time, seeds and the metrics of one event.
fn event_cells(e: &EventLag) -> Vec<String> {
    vec![
        e.frame.to_string(),
        e.time.to_string(),
        e.seeds.to_string(),
        num(e.peak_error),
        num(e.steady_error),
        num(e.peak_over_steady),
        recovery_cell(e.recovery_frames),
        num(e.lag_area),
        num(e.signed_bias),
    ]
}

/// `events.csv`: one row per configuration and event.
pub fn write_events(path: &Path, results: &[ConfigResult]) -> anyhow::Result<()> {
    let mut header = vec!["config", "event"];
    header.extend(&LAG_COLUMNS[3..]);
    let mut table = Table::new(&header);
    for r in results {
        for (k, e) in r.lag.iter().enumerate() {
            let mut cells = vec![r.config.name.clone(), k.to_string()];
            cells.extend(event_cells(e));
            table.row(cells);
        }
    }
    table.write(path)
}

/// A recovery cell: frames, "never", or empty.
pub fn recovery_cell(r: Option<Option<f64>>) -> String {
    match r {
        Some(Some(v)) => format!("{v}"),
        Some(None) => "never".into(),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(frame: usize, lag_area: f64, recovery: Option<Option<f64>>) -> EventLag {
        EventLag {
            frame,
            time: frame as f32 / 30.0,
            seeds: 2,
            peak_error: Some(0.5),
            steady_error: Some(0.1),
            peak_over_steady: Some(5.0),
            recovery_frames: recovery,
            lag_area: Some(lag_area),
            signed_bias: Some(-0.25),
        }
    }

    #[test]
    fn results_csv_has_a_row_per_event_with_that_events_numbers() {
        let column = |name: &str| LAG_COLUMNS.iter().position(|c| *c == name).unwrap();
        let rows = lag_rows(
            Some("scene"),
            &[event(9, 1.5, Some(Some(4.0))), event(39, 0.75, Some(None))],
        );
        assert_eq!(rows.len(), 2);
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), LAG_COLUMNS.len());
            assert_eq!(row[column("events")], "2");
            assert_eq!(row[column("event")], k.to_string());
            assert_eq!(row[column("event_source")], "scene");
            assert_eq!(row[column("signed_bias")], "-0.25");
        }
        // Each row carries its own event, not the first one's.
        assert_eq!(
            (
                rows[0][column("event_frame")].as_str(),
                rows[1][column("event_frame")].as_str()
            ),
            ("9", "39")
        );
        assert_eq!(rows[0][column("lag_area")], "1.5");
        assert_eq!(rows[1][column("lag_area")], "0.75");
        assert_eq!(rows[0][column("recovery_frames")], "4");
        assert_eq!(rows[1][column("recovery_frames")], "never");
        // Without events: one row of empty cells, so a static scene keeps one row per
        // configuration.
        assert_eq!(
            lag_rows(None, &[]),
            vec![vec![String::new(); LAG_COLUMNS.len()]]
        );
        // events.csv keeps its columns: config, event, then event_frame onwards.
        assert_eq!(LAG_COLUMNS[3], "event_frame");
    }
}
