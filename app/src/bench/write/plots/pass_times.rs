//! `pass_times.png`: median time of each pass, stacked per configuration. The bars start
//! at zero (a stacked bar's length is its total), and the axis ends a little past the
//! longest, room for its total written after it; the legend is under the bars (legend.rs).

use plotters::prelude::*;

use super::canvas::{Area, DrawResult, TEXT_SIZE, TITLE_SIZE, color, text, with_footnote};
use super::legend::{self, Entry, Swatch};
use crate::bench::score::result::ConfigResult;
use crate::bench::write::passes::pass_names;

pub fn draw(area: &Area, note: &str, results: &[ConfigResult]) -> DrawResult {
    area.fill(&WHITE)?;
    let area = with_footnote(area, note)?;
    let passes = pass_names(results);
    let entries: Vec<Entry> = passes
        .iter()
        .enumerate()
        .map(|(p, pass)| Entry::new(pass.as_str(), Swatch::Block(color(p))))
        .collect();
    let area = legend::below(&area, &entries)?;
    let totals: Vec<f64> = results
        .iter()
        .map(|r| {
            passes
                .iter()
                .filter_map(|p| r.times.pass_ms_median.get(p))
                .sum()
        })
        .collect();
    let max_x = totals.iter().copied().fold(0.0, f64::max).max(1e-3) * 1.12;
    let names: Vec<String> = results.iter().map(|r| r.config.name.clone()).collect();
    let n = results.len().max(1);
    let mut chart = ChartBuilder::on(&area)
        .caption("Median time per pass (stacked)", text(TITLE_SIZE))
        .margin(16)
        .x_label_area_size(56)
        .y_label_area_size(170)
        .build_cartesian_2d(0.0..max_x, (0..n - 1).into_segmented())?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .y_labels(n)
        .y_label_formatter(&|v| match v {
            SegmentValue::CenterOf(i) => names.get(*i).cloned().unwrap_or_default(),
            _ => String::new(),
        })
        .x_desc("median time (ms; see note below)")
        .axis_desc_style(text(TEXT_SIZE))
        .label_style(text(TEXT_SIZE - 2))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    for (p, pass) in passes.iter().enumerate() {
        let c = color(p);
        let bars: Vec<Rectangle<(f64, SegmentValue<usize>)>> = results
            .iter()
            .enumerate()
            .filter_map(|(i, r)| {
                let ms = *r.times.pass_ms_median.get(pass)?;
                let before: f64 = passes[..p]
                    .iter()
                    .filter_map(|q| r.times.pass_ms_median.get(q))
                    .sum();
                let mut bar = Rectangle::new(
                    [
                        (before, SegmentValue::Exact(i)),
                        (before + ms, SegmentValue::Exact(i + 1)),
                    ],
                    c.filled(),
                );
                bar.set_margin(10, 10, 0, 0);
                Some(bar)
            })
            .collect();
        chart.draw_series(bars)?;
    }
    chart.draw_series(totals.iter().enumerate().map(|(i, t)| {
        Text::new(
            format!("{t:.1} ms"),
            (*t, SegmentValue::CenterOf(i)),
            text(TEXT_SIZE - 2),
        )
    }))?;
    Ok(())
}
