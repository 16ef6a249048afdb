//! The legend of every bench plot, in rows under its chart rather than over it: a legend
//! inside the frame hides the points it lands on, and the room once reserved for it inside
//! the axes pushed the data into a corner (axes.rs).

use std::error::Error;

use plotters::prelude::*;

use super::canvas::{Area, TEXT_SIZE, text};

/// What an entry shows before its label.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Swatch {
    /// A curve: a line, with its point marker where points are drawn.
    Line(RGBColor),
    LineDot(RGBColor),
    Dashed(RGBColor),
    /// A point, an error bar across it (a point with its interval).
    Dot(RGBColor),
    DotBar(RGBColor),
    /// A bar of a bar chart.
    Block(RGBColor),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    pub label: String,
    pub swatch: Swatch,
}

impl Entry {
    pub fn new(label: impl Into<String>, swatch: Swatch) -> Entry {
        Entry {
            label: label.into(),
            swatch,
        }
    }
}

const ROW: u32 = 28;
const SWATCH: i32 = 30;
const GAP: u32 = 28;
const LEFT: u32 = 16;

/// Each entry's place (x, row) when laid out left to right from `LEFT`, a new row where
/// the next would pass `width`; entries of `widths` pixels of label each.
fn layout(widths: &[u32], width: u32) -> Vec<(u32, u32)> {
    let mut places = Vec::new();
    let (mut x, mut row) = (LEFT, 0);
    for &w in widths {
        let span = SWATCH as u32 + 8 + w;
        if x > LEFT && x + span > width.saturating_sub(LEFT) {
            (x, row) = (LEFT, row + 1);
        }
        places.push((x, row));
        x += span + GAP;
    }
    places
}

/// Draws `entries` in rows at the bottom of `area` and returns the area above them, where
/// the chart goes (all of `area` without entries).
pub fn below<'a>(area: &Area<'a>, entries: &[Entry]) -> Result<Area<'a>, Box<dyn Error>> {
    if entries.is_empty() {
        return Ok(area.clone());
    }
    let style = text(TEXT_SIZE - 2);
    let widths: Vec<u32> = entries
        .iter()
        .map(|e| area.estimate_text_size(&e.label, &style).map(|s| s.0))
        .collect::<Result<_, _>>()?;
    let (width, height) = area.dim_in_pixel();
    let places = layout(&widths, width);
    let rows = places.last().map_or(0, |p| p.1 + 1);
    let (chart, strip) = area.split_vertically(height.saturating_sub(rows * ROW + 8));
    for (e, &(x, row)) in entries.iter().zip(&places) {
        let (x, y) = (x as i32, (row * ROW + 4) as i32 + ROW as i32 / 2);
        draw_swatch(&strip, e.swatch, (x, y))?;
        strip.draw(&Text::new(
            e.label.clone(),
            (x + SWATCH + 8, y - (TEXT_SIZE as i32) / 2),
            style.clone(),
        ))?;
    }
    Ok(chart)
}

fn draw_swatch(area: &Area, swatch: Swatch, (x, y): (i32, i32)) -> Result<(), Box<dyn Error>> {
    let line = |c: RGBColor| PathElement::new(vec![(x, y), (x + SWATCH, y)], c.stroke_width(3));
    let mid = (x + SWATCH / 2, y);
    match swatch {
        Swatch::Line(c) => area.draw(&line(c))?,
        Swatch::LineDot(c) => {
            area.draw(&line(c))?;
            area.draw(&Circle::new(mid, 5, c.filled()))?;
        }
        Swatch::Dashed(c) => {
            for k in 0..3 {
                let x0 = x + k * 12;
                area.draw(&PathElement::new(
                    vec![(x0, y), (x0 + 7, y)],
                    c.stroke_width(2),
                ))?;
            }
        }
        Swatch::Dot(c) => area.draw(&Circle::new(mid, 7, c.filled()))?,
        Swatch::DotBar(c) => {
            area.draw(&PathElement::new(
                vec![(mid.0, y - 11), (mid.0, y + 11)],
                c.stroke_width(2),
            ))?;
            area.draw(&Circle::new(mid, 5, c.filled()))?;
        }
        Swatch::Block(c) => area.draw(&Rectangle::new(
            [(x + 4, y - 8), (x + SWATCH - 4, y + 8)],
            c.filled(),
        ))?,
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legend_entries_wrap_to_the_width() {
        // Labels of 300 px on 1000: two fit a row (338 px each, 28 apart), the third wraps.
        let places = layout(&[300, 300, 300, 300], 1000);
        assert_eq!(places, vec![(16, 0), (382, 0), (16, 1), (382, 1)]);
        // One longer than the width still gets a row of its own.
        assert_eq!(layout(&[2000, 10], 1000), vec![(16, 0), (16, 1)]);
        assert_eq!(layout(&[], 1000), vec![]);
    }
}
