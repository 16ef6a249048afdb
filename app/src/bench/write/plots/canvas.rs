//! Drawing PNG charts headless: an RGB buffer behind plotters' bitmap backend, egui's
//! bundled Ubuntu font registered with plotters' ab_glyph text (no system fonts needed),
//! a colour per configuration, and the line chart every curve plot shares.

use std::error::Error;
use std::path::Path;
use std::sync::Once;

use anyhow::Context;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;

pub type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;
pub type DrawResult = Result<(), Box<dyn Error>>;

pub const FONT: &str = "sans-serif";
pub const TITLE_SIZE: u32 = 30;
pub const TEXT_SIZE: u32 = 20;

/// Registers the font once per process (plotters' font table is global).
fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        for style in [FontStyle::Normal, FontStyle::Bold] {
            if plotters::style::register_font(FONT, style, epaint_default_fonts::UBUNTU_LIGHT)
                .is_err()
            {
                log::error!("the bundled plot font did not load: plots will have no text");
            }
        }
    });
}

/// Tableau-10: distinct in colour and in lightness.
const PALETTE: [(u8, u8, u8); 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

pub fn color(index: usize) -> RGBColor {
    let (r, g, b) = PALETTE[index % PALETTE.len()];
    RGBColor(r, g, b)
}

pub fn text(size: u32) -> TextStyle<'static> {
    (FONT, size).into_font().color(&BLACK)
}

/// Draws into a `width`×`height` white canvas with `draw` and writes it as PNG.
pub fn render_png(
    path: &Path,
    (width, height): (u32, u32),
    draw: impl FnOnce(&Area) -> DrawResult,
) -> anyhow::Result<()> {
    register_font();
    let mut buffer = vec![255u8; width as usize * height as usize * 3];
    {
        let area = BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
        draw(&area)
            .map_err(|e| anyhow::anyhow!("{}: cannot draw the plot: {e}", path.display()))?;
        area.present()
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    }
    image::save_buffer_with_format(
        path,
        &buffer,
        width,
        height,
        image::ExtendedColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .with_context(|| format!("{}: cannot write PNG", path.display()))
}

/// One curve.
pub struct Series {
    pub name: String,
    pub color: RGBColor,
    pub points: Vec<(f64, f64)>,
}

/// What a line chart shows.
pub struct LineChart<'a> {
    pub title: &'a str,
    pub x_desc: &'a str,
    pub y_desc: &'a str,
    pub log_x: bool,
    pub log_y: bool,
    /// Labelled vertical lines (the equal-time budget, a dynamic scene's events); the
    /// legend names the first.
    pub markers_x: &'a [(f64, &'a str)],
}

/// The legend box of a chart, in one style everywhere.
pub fn legend<'a, 'b: 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, BitMapBackend<'b>, CT>,
    position: SeriesLabelPosition,
) -> DrawResult {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(text(TEXT_SIZE - 2))
        .draw()?;
    Ok(())
}

/// Range of `values` padded for plotting; for log axes only positive values count.
fn range(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (mut lo, mut hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return if log { (0.1, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        (lo / 1.3, hi * 1.3)
    } else {
        if hi - lo < 1e-12 {
            hi = lo + lo.abs().max(1e-3);
        }
        lo = if lo >= 0.0 {
            0.0
        } else {
            lo - 0.05 * (hi - lo)
        };
        (lo, hi + 0.08 * (hi - lo))
    }
}

/// An axis label: three significant digits at most, no trailing zeros ("10", "0.25").
/// The axes of every plot: both descriptions, the house text sizes, light grid lines and
/// `tick` labels.
pub fn draw_axes<'a, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, Cartesian2d<X, Y>>,
    x_desc: &str,
    y_desc: &str,
) -> DrawResult
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(text(TEXT_SIZE))
        .label_style(text(TEXT_SIZE - 2))
        .light_line_style(RGBColor(235, 235, 235))
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()?;
    Ok(())
}

pub fn tick(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = (2 - v.abs().log10().floor() as i32).clamp(0, 10) as usize;
    let text = format!("{v:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// Ticks for a log axis over [lo, hi]: the first of 1-2-5, 1-2-3-5 and 1…9 × 10^k that gives
/// four or more.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let decades = lo.log10().floor() as i32..=hi.log10().ceil() as i32;
    let within = |steps: &[f64]| -> Vec<f64> {
        decades
            .clone()
            // Divide for negative powers: 3 / 10 is 0.3, 3 × 0.1 is not.
            .flat_map(|k| {
                steps.iter().map(move |m| {
                    if k < 0 {
                        m / 10f64.powi(-k)
                    } else {
                        m * 10f64.powi(k)
                    }
                })
            })
            .filter(|v| (lo..=hi).contains(v))
            .collect()
    };
    [
        &[1.0, 2.0, 5.0][..],
        &[1.0, 2.0, 3.0, 5.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ]
    .iter()
    .map(|steps| within(steps))
    .find(|ticks| ticks.len() >= 4)
    .unwrap_or_else(|| within(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]))
}

/// Draws `series` as lines with markers, with a legend, on `area`.
pub fn line_chart(area: &Area, chart: &LineChart, series: &[Series]) -> DrawResult {
    let xs = range(
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.0))
            .chain(chart.markers_x.iter().map(|m| m.0)),
        chart.log_x,
    );
    // Room on the right for the legend, so it never hides the curves' ends.
    let xs = if chart.log_x {
        (xs.0, xs.1 * 3.0)
    } else {
        (xs.0, xs.1 + 0.3 * (xs.1 - xs.0))
    };
    let ys = range(
        series.iter().flat_map(|s| s.points.iter().map(|p| p.1)),
        chart.log_y,
    );
    // plotters types a log axis differently from a linear one: one body, two instantiations.
    macro_rules! body {
        ($x:expr, $y:expr) => {{
            let mut c = ChartBuilder::on(area)
                .caption(chart.title, text(TITLE_SIZE))
                .margin(16)
                .x_label_area_size(56)
                .y_label_area_size(90)
                .build_cartesian_2d($x, $y)?;
            c.configure_mesh()
                .x_desc(chart.x_desc)
                .y_desc(chart.y_desc)
                .axis_desc_style(text(TEXT_SIZE))
                .label_style(text(TEXT_SIZE - 2))
                .light_line_style(RGBColor(235, 235, 235))
                .x_labels(12)
                .y_labels(10)
                .x_label_formatter(&|v| tick(*v))
                .y_label_formatter(&|v| tick(*v))
                .draw()?;
            for (i, &(x, label)) in chart.markers_x.iter().enumerate() {
                let line = c.draw_series(std::iter::once(PathElement::new(
                    vec![(x, ys.0), (x, ys.1)],
                    BLACK.stroke_width(2),
                )))?;
                if i == 0 {
                    line.label(label).legend(|(x, y)| {
                        PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2))
                    });
                }
            }
            for s in series {
                let style = s.color.stroke_width(3);
                c.draw_series(LineSeries::new(s.points.iter().copied(), style))?
                    .label(s.name.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
                if s.points.len() <= 20 {
                    c.draw_series(
                        s.points
                            .iter()
                            .map(|&p| Circle::new(p, 4, s.color.filled())),
                    )?;
                }
            }
            legend(&mut c, SeriesLabelPosition::UpperRight)?;
            Ok(())
        }};
    }
    // plotters' own log ticks skip whole decades: place them at 1-2-5 steps instead.
    let log_x = || {
        (xs.0..xs.1)
            .log_scale()
            .with_key_points(log_ticks(xs.0, xs.1))
    };
    let log_y = || {
        (ys.0..ys.1)
            .log_scale()
            .with_key_points(log_ticks(ys.0, ys.1))
    };
    match (chart.log_x, chart.log_y) {
        (false, false) => body!(xs.0..xs.1, ys.0..ys.1),
        (false, true) => body!(xs.0..xs.1, log_y()),
        (true, false) => body!(log_x(), ys.0..ys.1),
        (true, true) => body!(log_x(), log_y()),
    }
}

/// Splits off a strip at the bottom for a footnote (the timing caveat) and draws it.
pub fn with_footnote<'a>(area: &Area<'a>, note: &str) -> Result<Area<'a>, Box<dyn Error>> {
    let height = area.dim_in_pixel().1;
    let (main, foot) = area.split_vertically(height - 34);
    foot.draw(&Text::new(
        note.to_string(),
        (16, 6),
        text(TEXT_SIZE - 2).color(&RGBColor(90, 90, 90)),
    ))?;
    Ok(main)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_plot_ticks_read_well() {
        assert_eq!(tick(10.0), "10");
        assert_eq!(tick(0.25), "0.25");
        assert_eq!(tick(0.123456), "0.123");
        assert_eq!(tick(1234.6), "1235");
        let labels = |lo, hi| {
            log_ticks(lo, hi)
                .into_iter()
                .map(tick)
                .collect::<Vec<_>>()
                .join(" ")
        };
        assert_eq!(labels(0.15, 3.0), "0.2 0.5 1 2");
        assert_eq!(labels(0.25, 3.0), "0.3 0.5 1 2 3");
        assert_eq!(labels(0.3, 0.9), "0.3 0.4 0.5 0.6 0.7 0.8 0.9");
    }
}
