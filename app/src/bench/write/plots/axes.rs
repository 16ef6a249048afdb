//! The axes every bench plot shares. Each spans its data with a small margin, on a log axis
//! too (there the margin is a share of the decades the data cover): padding an axis by a
//! fixed factor, or reserving room inside it for a legend, left a cost curve's points in
//! one corner of an axis drawn to three times their largest time. Then the ticks: their
//! positions on a log axis and every label's digits.

/// The share of the data's span added on either side (of its log span on a log axis).
pub const MARGIN: f64 = 0.05;

/// The axis over `values`: from the least to the largest, widened by `MARGIN` of that span
/// on either side. On a log axis only positive values count and the margin is taken in
/// log. Strictly positive data keep a linear axis above zero. A single value gets an axis
/// of ±10 % around it, no value at all a unit one.
pub fn fit(values: impl IntoIterator<Item = f64>, log: bool) -> (f64, f64) {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return if log { (0.1, 1.0) } else { (0.0, 1.0) };
    }
    if log {
        let (a, b) = (lo.ln(), hi.ln());
        let pad = if b - a < 1e-9 { 0.1 } else { MARGIN * (b - a) };
        return ((a - pad).exp(), (b + pad).exp());
    }
    let pad = if hi - lo <= 1e-12 * lo.abs().max(1.0) {
        0.1 * lo.abs().max(1e-3)
    } else {
        MARGIN * (hi - lo)
    };
    let low = if lo > 0.0 {
        (lo - pad).max(0.0)
    } else {
        lo - pad
    };
    (low, hi + pad)
}

/// An axis label: three significant digits at most, no trailing zeros ("10", "0.25").
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

/// Ticks for a log axis over [lo, hi]: the first of 1-2-5 and 1-2-3-5 × 10^k that gives
/// four or more; else 1-2-3-5 or then 1…9 if either gives three (1…9's labels crowd the top
/// of each decade, so it comes last); an axis fitted to a narrow span holds fewer than
/// three of those, and gets evenly spaced round values instead.
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
    let (few, more) = (within(&[1.0, 2.0, 5.0]), within(&[1.0, 2.0, 3.0, 5.0]));
    let nine = within(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    [(few, 4), (more.clone(), 4), (more, 3), (nine, 3)]
        .into_iter()
        .find(|(ticks, least)| ticks.len() >= *least)
        .map_or_else(|| even_ticks(lo, hi), |(ticks, _)| ticks)
}

/// Round values (1, 2 or 5 × 10^k apart) within [lo, hi], four to ten of them.
fn even_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let raw = (hi - lo) / 5.0;
    if !(raw > 0.0 && raw.is_finite()) {
        return vec![lo];
    }
    let power = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * power)
        .find(|s| (hi - lo) / s <= 8.0)
        .unwrap_or(10.0 * power);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    // Rounded to the step's own digits, so 0.0085 does not print as 0.0085000000001.
    let digits = (-step.log10().floor()).max(0.0) as i32 + 1;
    let round = |v: f64| (v * 10f64.powi(digits)).round() / 10f64.powi(digits);
    (first..=last).map(|i| round(i as f64 * step)).collect()
}

/// Whether an axis fits its data: it holds every value, and the data span at least
/// `share` of it (in log on a log axis). The tests' check, and the planted twin's.
#[cfg(test)]
pub fn fits(axis: (f64, f64), values: &[f64], log: bool, share: f64) -> bool {
    let scale = |v: f64| if log { v.ln() } else { v };
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let inside = values.iter().all(|&v| axis.0 <= v && v <= axis.1);
    inside && (scale(hi) - scale(lo)) >= share * (scale(axis.1) - scale(axis.0))
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
        // Most of a decade: three evenly read labels rather than 0.06 0.07 0.08 0.09 0.1.
        assert_eq!(labels(0.058, 0.45), "0.1 0.2 0.3");
        // A fitted cost curve's error axis spans less than a third of a decade.
        assert_eq!(labels(0.0081, 0.0109), "0.0085 0.009 0.0095 0.01 0.0105");
        assert_eq!(labels(780.0, 2050.0), "800 900 1000 2000");
    }

    #[test]
    fn bench_plot_axes_span_their_data() {
        // The points of docs/bench/crossover/map/concourse-384x256-static/cost_curves.png:
        // 820–1948 ms, errors 0.0082–0.0107, both axes log.
        let ms = [820.2, 891.1, 1042.8, 1573.1, 1948.1];
        let rmse = [0.00821, 0.00865, 0.00972, 0.01072];
        for (values, log) in [(&ms[..], true), (&rmse[..], true), (&ms[..], false)] {
            let axis = fit(values.iter().copied(), log);
            assert!(fits(axis, values, log, 0.85), "{axis:?} for {values:?}");
        }
        // Strictly positive data keep a linear axis above zero; one value gets room.
        assert!(fit([0.01, 5.0], false).0 >= 0.0);
        let one = fit([2.0], true);
        assert!(one.0 < 2.0 && 2.0 < one.1);
        assert_eq!(fit([f64::NAN, -1.0], true), (0.1, 1.0));
    }

    #[test]
    fn planted_twin_an_axis_padded_for_a_legend_is_caught() {
        // The old padding: ×1.3 either side, then ×3 on the right for the legend.
        let ms = [820.2, 1948.1];
        let padded = (820.2 / 1.3, 1948.1 * 1.3 * 3.0);
        assert!(!fits(padded, &ms, true, 0.85));
        // And an axis that leaves a point out.
        assert!(!fits((900.0, 2000.0), &ms, true, 0.5));
    }
}
