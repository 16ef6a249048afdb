//! `lag_vs_noise.png` (a dynamic scene with events): the lag/noise trade-off, one labelled
//! point per configuration. x: its steady per-frame error (the noise it settles to after an
//! event), y: its lag area (excess error summed over the frames after the event), both
//! averaged over the events long enough to have them; the label adds their recovery frames. A long
//! history (large M cap) moves a configuration right-to-left and bottom-to-top.

use std::path::Path;

use plotters::prelude::*;

use super::axes::fit;
use super::canvas::{
    Area, DrawResult, TEXT_SIZE, TITLE_SIZE, color, draw_axes, label_beside, render_png, text,
    with_footnote,
};
use crate::bench::score::lag::EventLag;
use crate::bench::write::events_csv::recovery_cell;

/// One configuration's point.
#[derive(Clone, Debug, PartialEq)]
pub struct LagNoisePoint {
    pub name: String,
    /// Mean over events of the steady per-frame luma RMSE.
    pub noise: f64,
    /// Mean over events of the lag area.
    pub lag_area: f64,
    /// Recovery frames per event, as in results.csv ("4", "never"), joined by "/".
    pub recovery: String,
}

/// The point of a configuration named `name` from its events that have a steady level
/// and a lag area (a segment shorter than 10 frames has neither: the switch-on at the end
/// of a short run); `None` when no event has them.
pub fn point(name: &str, lag: &[EventLag]) -> Option<LagNoisePoint> {
    let measured: Vec<(&EventLag, f64, f64)> = lag
        .iter()
        .filter_map(|e| Some((e, e.steady_error?, e.lag_area?)))
        .collect();
    if measured.is_empty() {
        return None;
    }
    let n = measured.len() as f64;
    Some(LagNoisePoint {
        name: name.to_string(),
        noise: measured.iter().map(|m| m.1).sum::<f64>() / n,
        lag_area: measured.iter().map(|m| m.2).sum::<f64>() / n,
        recovery: measured
            .iter()
            .map(|m| match m.0.recovery_frames {
                // A mean over seeds: one decimal is what the seeds can tell apart.
                Some(Some(r)) => format!("{}", (r * 10.0).round() / 10.0),
                other => recovery_cell(other),
            })
            .collect::<Vec<_>>()
            .join("/"),
    })
}

/// Writes the scatter of `points` to `path`, `note` under it.
pub fn write(path: &Path, note: &str, points: &[LagNoisePoint]) -> anyhow::Result<()> {
    render_png(path, (1200, 800), |a| draw(a, note, points))
}

fn draw(area: &Area, note: &str, points: &[LagNoisePoint]) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, note)?;
    let shown: Vec<&LagNoisePoint> = points
        .iter()
        .filter(|p| p.noise.is_finite() && p.lag_area.is_finite())
        .collect();
    // Linear axes spanning the points (axes.rs): a zero lag (M cap 1) is a meaningful
    // point, which a log axis could not show.
    let xs = fit(shown.iter().map(|p| p.noise), false);
    let ys = fit(shown.iter().map(|p| p.lag_area), false);
    let mut chart = ChartBuilder::on(&area)
        .caption(
            "Lag against noise after light events (lower left is better)",
            text(TITLE_SIZE),
        )
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(90)
        .build_cartesian_2d(xs.0..xs.1, ys.0..ys.1)?;
    draw_axes(
        &mut chart,
        "steady per-frame luma RMSE after the event (noise)",
        "lag area (excess luma RMSE summed over frames)",
    )?;
    for (i, p) in points.iter().enumerate() {
        if !(p.noise.is_finite() && p.lag_area.is_finite()) {
            continue;
        }
        // Labels beside their point on the side with room, in its colour; configurations
        // that land on top of each other (the ratio clamp on and off) stack their labels
        // downwards.
        let at = (
            (p.noise - xs.0) / (xs.1 - xs.0),
            (p.lag_area - ys.0) / (ys.1 - ys.0),
        );
        let close = points[..i]
            .iter()
            .filter(|q| {
                (q.noise - p.noise).abs() < 0.05 * (xs.1 - xs.0)
                    && (q.lag_area - p.lag_area).abs() < 0.05 * (ys.1 - ys.0)
            })
            .count() as i32;
        let label = format!("{} (recovery {})", p.name, p.recovery);
        let ink = color(i);
        chart.draw_series(std::iter::once(
            EmptyElement::at((p.noise, p.lag_area))
                + Circle::new((0, 0), 9, ink.filled())
                + label_beside(label, at, close, text(TEXT_SIZE).color(&ink)),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(steady: Option<f64>, lag_area: f64, recovery: Option<Option<f64>>) -> EventLag {
        EventLag {
            frame: 9,
            time: 1.0,
            seeds: 2,
            peak_error: Some(1.0),
            steady_error: steady,
            peak_over_steady: None,
            recovery_frames: recovery,
            lag_area: Some(lag_area),
            signed_bias: Some(0.0),
        }
    }

    #[test]
    fn lag_noise_points_average_the_events() {
        let p = point(
            "mcap-20",
            &[
                event(Some(0.2), 1.0, Some(Some(6.0))),
                event(Some(0.4), 3.0, Some(None)),
            ],
        )
        .unwrap();
        assert!((p.noise - 0.3).abs() < 1e-12 && (p.lag_area - 2.0).abs() < 1e-12);
        assert_eq!(p.recovery, "6/never");
        let third = point("x", &[event(Some(0.2), 1.0, Some(Some(13.0 / 3.0)))]).unwrap();
        assert_eq!(third.recovery, "4.3");
        // An event without a steady level (too short a segment) is left out of the mean.
        let q = point(
            "mcap-5",
            &[
                event(Some(0.2), 1.0, Some(Some(4.0))),
                event(None, 9.0, None),
            ],
        )
        .unwrap();
        assert_eq!((q.noise, q.lag_area, q.recovery.as_str()), (0.2, 1.0, "4"));
        // Nothing to place: no events, or none with a steady level.
        assert_eq!(point("static", &[]), None);
        assert_eq!(point("short", &[event(None, 1.0, None)]), None);
    }

    #[test]
    fn lag_vs_noise_png_is_written() {
        let dir = std::env::temp_dir().join(format!("lag_noise_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("lag_vs_noise.png");
        let points = [
            point("mcap-1", &[event(Some(0.3), 0.0, Some(Some(0.0)))]).unwrap(),
            point("mcap-100", &[event(Some(0.1), 4.0, Some(None))]).unwrap(),
        ];
        write(&path, "test note", &points).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
        let image = image::load_from_memory(&bytes).unwrap();
        assert_eq!((image.width(), image.height()), (1200, 800));
        // Something was drawn: not a blank canvas.
        let rgb = image.to_rgb8();
        assert!(rgb.pixels().any(|p| p.0 != [255, 255, 255]));
        std::fs::remove_dir_all(&dir).ok();
    }
}
