//! Drawing PNG charts headless: an RGB buffer behind plotters' bitmap backend, egui's
//! bundled Ubuntu font registered with plotters' ab_glyph text (no system fonts needed),
//! a colour per configuration, the axes' style, a point's label and the footnote. The
//! line chart every curve plot shares is `line_chart.rs`, axis ranges and ticks `axes.rs`,
//! legends `legend.rs`.

use std::error::Error;
use std::path::Path;
use std::sync::Once;

use anyhow::Context;
use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::tick;

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

/// A point's label, beside it on the side with room: right of a point in the left half of
/// the axes, left of one in the right half, below one near the top. With axes fitted to
/// the data (axes.rs) the outermost points sit near the frame, where a label on the
/// outside would be cut off. `at`: the point's place along each axis, 0 to 1; `stack`: how
/// many labels already stand at this point (each moves one line down).
pub fn label_beside<'a>(
    label: String,
    at: (f64, f64),
    stack: i32,
    style: TextStyle<'a>,
) -> Text<'a, (i32, i32), String> {
    let h = if at.0 > 0.5 { HPos::Right } else { HPos::Left };
    let dx = if at.0 > 0.5 { -14 } else { 14 };
    let (v, dy) = if at.1 > 0.85 {
        (VPos::Top, 12)
    } else {
        (VPos::Bottom, -10)
    };
    Text::new(label, (dx, dy + 24 * stack), style.pos(Pos::new(h, v)))
}
