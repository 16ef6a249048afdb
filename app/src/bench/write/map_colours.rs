//! The crossover map's colours (map_png.rs): a diverging scale on the log of the cost
//! ratio, centred on 1× (white), blue below it (reuse pays: less time than the baseline to
//! the same error), red above (reuse loses), saturated at 0.5× and 2×, past which no
//! measured verdict turns. Log, so 0.8× and 1.25× lie equally far from 1; blue against red,
//! which colour-blind readers tell apart too.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::plots::canvas::{Area, DrawResult, TEXT_SIZE, text};

/// The ratios at the scale's ends.
pub const SATURATE: f64 = 2.0;

/// ColorBrewer's RdBu, five classes: blue for ratios below 1, white at 1, red above.
const STOPS: [(u8, u8, u8); 5] = [
    (5, 113, 176),
    (146, 197, 222),
    (247, 247, 247),
    (244, 165, 130),
    (202, 0, 32),
];

/// The place of `ratio` on the scale: -1 at 1/SATURATE or below, 0 at 1, 1 at SATURATE
/// or above.
pub fn scale(ratio: f64) -> f64 {
    (ratio.ln() / SATURATE.ln()).clamp(-1.0, 1.0)
}

/// The colour of a cost ratio; grey where it is not a number.
pub fn ratio_colour(ratio: f64) -> RGBColor {
    if !(ratio > 0.0 && ratio.is_finite()) {
        return RGBColor(235, 235, 235);
    }
    let u = (scale(ratio) + 1.0) * 2.0; // 0..4 over the stops
    let i = (u.floor() as usize).min(3);
    let t = u - i as f64;
    let mix = |a: u8, b: u8| (a as f64 + t * (b as f64 - a as f64)).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Black on a light colour, white on a dark one (by its luma).
pub fn text_on(c: RGBColor) -> RGBColor {
    let luma = 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
    if luma < 120.0 { WHITE } else { BLACK }
}

/// The ratios the colour bar labels, and their labels (the ends stand for everything past).
const TICKS: [(f64, &str); 7] = [
    (0.5, "≤ 0.5×"),
    (2.0 / 3.0, "0.67×"),
    (0.8, "0.8×"),
    (1.0, "1×"),
    (1.25, "1.25×"),
    (1.5, "1.5×"),
    (2.0, "≥ 2×"),
];

/// The colour bar, `width` wide from `(x, y)`: the scale, its ticks, and what either side
/// means.
pub fn colour_bar(area: &Area, (x, y): (i32, i32), width: i32) -> DrawResult {
    let h = 22;
    for k in 0..width {
        let ratio = SATURATE.powf(2.0 * k as f64 / (width - 1).max(1) as f64 - 1.0);
        area.draw(&Rectangle::new(
            [(x + k, y), (x + k + 1, y + h)],
            ratio_colour(ratio).filled(),
        ))?;
    }
    area.draw(&Rectangle::new([(x, y), (x + width, y + h)], BLACK))?;
    let at = |r: f64| x + ((scale(r) + 1.0) / 2.0 * (width - 1) as f64).round() as i32;
    let centred = text(TEXT_SIZE - 4).pos(Pos::new(HPos::Center, VPos::Top));
    for (r, label) in TICKS {
        let px = at(r);
        area.draw(&PathElement::new(vec![(px, y + h), (px, y + h + 6)], BLACK))?;
        area.draw(&Text::new(label, (px, y + h + 8), centred.clone()))?;
    }
    let side = |s: &str, anchor: HPos, px: i32| {
        Text::new(
            s.to_string(),
            (px, y - 4),
            text(TEXT_SIZE - 3).pos(Pos::new(anchor, VPos::Bottom)),
        )
    };
    area.draw(&side(
        "below 1×: cheaper than the baseline (reuse pays)",
        HPos::Left,
        x,
    ))?;
    area.draw(&side("above: dearer (reuse loses)", HPos::Right, x + width))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_map_scale_is_white_at_one_blue_below_red_above() {
        assert_eq!(ratio_colour(1.0), RGBColor(247, 247, 247));
        assert_eq!(ratio_colour(1.0 / SATURATE), RGBColor(5, 113, 176));
        assert_eq!(ratio_colour(0.01), RGBColor(5, 113, 176));
        assert_eq!(ratio_colour(SATURATE), RGBColor(202, 0, 32));
        // Symmetric in log: 0.5× is as far from white as 2×, on the other side.
        assert!((scale(0.5) + scale(2.0)).abs() < 1e-12);
        let (blue, red) = (ratio_colour(0.7), ratio_colour(1.4));
        assert!(blue.2 > blue.0 && red.0 > red.2, "{blue:?} {red:?}");
        assert_eq!(ratio_colour(f64::NAN), RGBColor(235, 235, 235));
        assert_eq!(text_on(ratio_colour(0.5)), WHITE);
        assert_eq!(text_on(ratio_colour(1.0)), BLACK);
    }
}
