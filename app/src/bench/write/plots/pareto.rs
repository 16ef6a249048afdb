//! `pareto.png`: per-frame error against per-frame time, one labelled point per
//! configuration, the Pareto front dashed. Both axes span the points (axes.rs), each label
//! on the side of its point that has room.

use plotters::prelude::*;

use super::axes::{fit, log_ticks};
use super::canvas::{
    Area, DrawResult, TEXT_SIZE, TITLE_SIZE, color, draw_axes, label_beside, text, with_footnote,
};
use super::legend::{self, Entry, Swatch};
use crate::bench::score::result::ConfigResult;

const FRONT: RGBColor = RGBColor(120, 120, 120);

/// The front: sorted by time, each point better than every faster one.
pub fn front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for (x, y) in sorted {
        if front.last().is_none_or(|&(_, best)| y < best) {
            front.push((x, y));
        }
    }
    front
}

pub fn draw(area: &Area, note: &str, results: &[ConfigResult]) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, note)?;
    let points: Vec<(f64, f64, usize)> = results
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((r.median_frame_ms()?, r.scores.as_ref()?.mean_luma_rmse, i)))
        .collect();
    let mut entries = vec![Entry::new("Pareto front", Swatch::Dashed(FRONT))];
    entries.extend(
        points
            .iter()
            .map(|&(_, _, i)| Entry::new(results[i].config.name.clone(), Swatch::Dot(color(i)))),
    );
    let area = legend::below(&area, &entries)?;
    let xs = fit(points.iter().map(|p| p.0), false);
    // Log errors: nee's is several times the rest, which a linear axis would crowd together.
    let ys = fit(points.iter().map(|p| p.1), true);
    let mut chart = ChartBuilder::on(&area)
        .caption(
            "Error vs time per frame (Pareto: lower left is better)",
            text(TITLE_SIZE),
        )
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(90)
        .build_cartesian_2d(
            xs.0..xs.1,
            (ys.0..ys.1)
                .log_scale()
                .with_key_points(log_ticks(ys.0, ys.1)),
        )?;
    draw_axes(
        &mut chart,
        "median time per frame (ms, sum of passes; see note below)",
        "per-frame luma RMSE vs reference (mean over frames, log)",
    )?;
    let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p.0, p.1)).collect();
    chart.draw_series(DashedLineSeries::new(
        front(&pairs),
        10,
        6,
        FRONT.stroke_width(2),
    ))?;
    for &(x, y, i) in &points {
        let at = (
            (x - xs.0) / (xs.1 - xs.0),
            (y / ys.0).ln() / (ys.1 / ys.0).ln(),
        );
        chart.draw_series(std::iter::once(
            EmptyElement::at((x, y))
                + Circle::new((0, 0), 9, color(i).filled())
                + label_beside(results[i].config.name.clone(), at, 0, text(TEXT_SIZE)),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pareto_front_keeps_each_point_better_than_every_faster_one() {
        let f = front(&[(3.0, 0.1), (1.0, 0.5), (2.0, 0.6), (4.0, 0.2)]);
        assert_eq!(f, vec![(1.0, 0.5), (3.0, 0.1)]);
    }
}
