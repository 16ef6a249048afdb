//! The line chart every curve plot shares (error per frame, error against time, lag, the
//! light sweep, the cost curves): one curve per series, its points marked and, where the
//! data hold them, each point's intervals as error bars; both axes fitted to the data with
//! the bars (axes.rs), the legend in rows under the chart (legend.rs).

use plotters::prelude::*;

use super::axes::{fit, log_ticks, tick};
use super::canvas::{Area, DrawResult, TEXT_SIZE, TITLE_SIZE, text};
use super::legend::{self, Entry, Swatch};

/// A point's intervals: low and high along x, along y.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bars {
    pub x: Option<(f64, f64)>,
    pub y: Option<(f64, f64)>,
}

/// One curve; `bars` is empty, or one per point.
pub struct Series {
    pub name: String,
    pub color: RGBColor,
    pub points: Vec<(f64, f64)>,
    pub bars: Vec<Bars>,
}

impl Series {
    pub fn new(name: String, color: RGBColor, points: Vec<(f64, f64)>) -> Series {
        Series {
            name,
            color,
            points,
            bars: Vec::new(),
        }
    }
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

/// Markers are drawn where a curve has few enough points to tell apart.
const MARKED_POINTS: usize = 20;

/// The axes' ranges: every point, every bar's ends and the markers, fitted.
pub fn ranges(chart: &LineChart, series: &[Series]) -> ((f64, f64), (f64, f64)) {
    let bars = || series.iter().flat_map(|s| s.bars.iter());
    let ends = |b: Option<(f64, f64)>| b.into_iter().flat_map(|(lo, hi)| [lo, hi]);
    let xs = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .chain(chart.markers_x.iter().map(|m| m.0))
        .chain(bars().flat_map(|b| ends(b.x)));
    let ys = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .chain(bars().flat_map(|b| ends(b.y)));
    (fit(xs, chart.log_x), fit(ys, chart.log_y))
}

/// The legend: the first marker's label, then each series.
fn entries(chart: &LineChart, series: &[Series]) -> Vec<Entry> {
    let marker = chart
        .markers_x
        .first()
        .map(|m| Entry::new(m.1, Swatch::Line(BLACK)));
    let curves = series.iter().map(|s| {
        let swatch = if !s.bars.is_empty() {
            Swatch::DotBar(s.color)
        } else if s.points.len() <= MARKED_POINTS {
            Swatch::LineDot(s.color)
        } else {
            Swatch::Line(s.color)
        };
        Entry::new(s.name.clone(), swatch)
    });
    marker.into_iter().chain(curves).collect()
}

/// The error bars of point `p`: each bar's ends, clamped to the axes (an interval reaching
/// below zero stops at a log axis), and its caps' half-extent across it in pixels.
fn bar_ends(
    (x, y): (f64, f64),
    b: &Bars,
    clamp_x: impl Fn(f64) -> f64,
    clamp_y: impl Fn(f64) -> f64,
) -> Vec<((f64, f64), (f64, f64), (i32, i32))> {
    let vertical =
        b.y.map(|(lo, hi)| ((x, clamp_y(lo)), (x, clamp_y(hi)), (6, 0)));
    let horizontal =
        b.x.map(|(lo, hi)| ((clamp_x(lo), y), (clamp_x(hi), y), (0, 6)));
    vertical.into_iter().chain(horizontal).collect()
}

/// Draws `series` as lines with markers and error bars, the legend under them, on `area`.
pub fn line_chart(area: &Area, chart: &LineChart, series: &[Series]) -> DrawResult {
    let area = legend::below(area, &entries(chart, series))?;
    let (xs, ys) = ranges(chart, series);
    // Frame numbers: a label per whole frame on a short axis, never at half a frame.
    let whole = series
        .iter()
        .flat_map(|s| &s.points)
        .all(|p| p.0.fract() == 0.0);
    let x_labels = if whole && !chart.log_x && xs.1 - xs.0 <= 12.0 {
        (xs.1 - xs.0).floor() as usize + 1
    } else {
        12
    };
    let clamp_y = |v: f64| v.clamp(ys.0, ys.1);
    let clamp_x = |v: f64| v.clamp(xs.0, xs.1);
    // plotters types a log axis differently from a linear one: one body, two instantiations.
    macro_rules! body {
        ($x:expr, $y:expr) => {{
            let mut c = ChartBuilder::on(&area)
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
                .x_labels(x_labels)
                .y_labels(10)
                .x_label_formatter(&|v| tick(*v))
                .y_label_formatter(&|v| tick(*v))
                .draw()?;
            for &(x, _) in chart.markers_x {
                c.draw_series(std::iter::once(PathElement::new(
                    vec![(x, ys.0), (x, ys.1)],
                    BLACK.stroke_width(2),
                )))?;
            }
            for s in series {
                c.draw_series(LineSeries::new(
                    s.points.iter().copied(),
                    s.color.stroke_width(3),
                ))?;
                if s.points.len() <= MARKED_POINTS {
                    c.draw_series(
                        s.points
                            .iter()
                            .map(|&p| Circle::new(p, 5, s.color.filled())),
                    )?;
                }
                for (&p, b) in s.points.iter().zip(&s.bars) {
                    let style = s.color.stroke_width(2);
                    for (from, to, across) in bar_ends(p, b, clamp_x, clamp_y) {
                        // The bar, and a cap 12 px across at either end.
                        let cap = |at: (f64, f64)| {
                            EmptyElement::at(at)
                                + PathElement::new(vec![(-across.0, -across.1), across], style)
                        };
                        c.draw_series(std::iter::once(PathElement::new(vec![from, to], style)))?;
                        c.draw_series([cap(from), cap(to)])?;
                    }
                }
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::write::plots::axes::fits;

    fn chart(markers: &[(f64, &'static str)]) -> LineChart<'static> {
        LineChart {
            title: "t",
            x_desc: "x",
            y_desc: "y",
            log_x: true,
            log_y: true,
            markers_x: markers.to_vec().leak(),
        }
    }

    #[test]
    fn a_line_charts_axes_hold_its_points_and_their_bars_and_little_else() {
        let mut s = Series::new(
            "a".into(),
            RGBColor(0, 0, 0),
            vec![(820.0, 0.0107), (1948.0, 0.0082)],
        );
        s.bars = vec![
            Bars {
                x: Some((800.0, 840.0)),
                y: Some((0.0105, 0.0109)),
            },
            Bars {
                x: None,
                y: Some((0.0080, 0.0084)),
            },
        ];
        let (xs, ys) = ranges(&chart(&[]), std::slice::from_ref(&s));
        assert!(fits(xs, &[800.0, 1948.0], true, 0.85), "{xs:?}");
        assert!(fits(ys, &[0.0080, 0.0109], true, 0.85), "{ys:?}");
        // Planted twin: a marker far off widens the axis, and the check sees it.
        let (wide, _) = ranges(&chart(&[(8000.0, "budget")]), std::slice::from_ref(&s));
        assert!(!fits(wide, &[800.0, 1948.0], true, 0.85), "{wide:?}");
    }

    #[test]
    fn a_line_chart_with_error_bars_is_drawn() {
        let path = std::env::temp_dir().join(format!("line-chart-{}.png", std::process::id()));
        let mut s = Series::new(
            "a".into(),
            RGBColor(200, 0, 0),
            vec![(1.0, 1.0), (2.0, 0.5)],
        );
        s.bars = vec![
            Bars {
                x: Some((0.9, 1.1)),
                y: Some((0.9, 1.1)),
            },
            // An interval reaching below zero on a log axis stops at the axis.
            Bars {
                x: None,
                y: Some((-1.0, 0.6)),
            },
        ];
        super::super::canvas::render_png(&path, (600, 400), |a| {
            a.fill(&WHITE)?;
            line_chart(a, &chart(&[]), &[s])
        })
        .unwrap();
        let png = image::open(&path).unwrap().to_rgb8();
        assert!(png.pixels().any(|p| p.0 == [200, 0, 0]));
        std::fs::remove_file(&path).ok();
    }
}
