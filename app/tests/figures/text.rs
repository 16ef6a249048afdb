//! The numbers a page prints, and the one rounding rule that says whether a printed
//! number is its data (docs/src/figures.md, "Rounding").

use std::ops::Range;

/// A claim a printed number makes about its value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Claim {
    /// The value, rounded to the printed digits.
    Equals,
    /// `≤`, "at most", "up to", "under", "below", "less than": the value rounded to the
    /// printed digits is at most the number (strictly below for "under", "below",
    /// "less than" and `<`).
    AtMost { strict: bool },
    /// `≥`, "at least", "over", "above", "more than", `>`.
    AtLeast { strict: bool },
}

/// One number as printed.
#[derive(Clone, Debug)]
pub struct Printed {
    pub value: f64,
    /// The place of the last printed digit: 2 for `0.10`, 7 for `7.64e-5`, 0 for `664`.
    pub decimals: i32,
    pub claim: Claim,
    /// Where the number is (sign included) in the text it was read from, and as printed.
    pub span: Range<usize>,
    pub printed: String,
    form: Form,
}

/// How a number was printed, so that a corrected value is printed the same way.
#[derive(Clone, Debug, Default)]
struct Form {
    /// Digits after the point of the mantissa.
    places: usize,
    /// `e-5`: the printed exponent.
    exponent: Option<i32>,
    /// `2^20`: a power, printed by hand, never rewritten.
    power: bool,
    /// Thousands separators (`1,328`), `−` rather than `-`, a leading `+`.
    grouped: bool,
    unicode_minus: bool,
    plus: bool,
}

/// The numbers in `text`, in order. `2^20` is one number; `–` and a `-` right after a
/// digit separate a range; a comma is a thousands separator only before three digits;
/// digits inside a name (`x86`, `bvh-4`, `m_cap2`) are not numbers.
pub fn numbers(text: &str) -> Vec<Printed> {
    let b: Vec<(usize, char)> = text.char_indices().collect();
    let at = |k: usize| b.get(k).map(|&(_, c)| c);
    let is_name = |c: char| c.is_alphanumeric() || c == '_';
    let (mut out, mut k) = (Vec::new(), 0);
    while k < b.len() {
        let c = b[k].1;
        let prev = k.checked_sub(1).and_then(at);
        let before_prev = k.checked_sub(2).and_then(at);
        let named = prev.is_some_and(|p| p.is_alphabetic() || p == '_')
            || (prev == Some('-') && before_prev.is_some_and(char::is_alphabetic));
        if c.is_ascii_digit() && named {
            while at(k).is_some_and(|c| is_name(c) || c == '.') {
                k += 1;
            }
            continue;
        }
        let signed = matches!(c, '-' | '−' | '+')
            && at(k + 1).is_some_and(|d| d.is_ascii_digit())
            && !prev.is_some_and(char::is_alphanumeric);
        if !(c.is_ascii_digit() || signed) {
            k += 1;
            continue;
        }
        let start = k;
        let mut form = Form {
            unicode_minus: c == '−',
            plus: c == '+',
            ..Form::default()
        };
        if signed {
            k += 1;
        }
        let mut digits = String::new();
        while let Some(d) = at(k) {
            if d.is_ascii_digit() {
                digits.push(d);
                k += 1;
            } else if d == ','
                && (1..=3).all(|j| at(k + j).is_some_and(|x| x.is_ascii_digit()))
                && !at(k + 4).is_some_and(|x| x.is_ascii_digit())
            {
                form.grouped = true;
                k += 1;
            } else {
                break;
            }
        }
        if at(k) == Some('.') && at(k + 1).is_some_and(|d| d.is_ascii_digit()) {
            digits.push('.');
            k += 1;
            while let Some(d) = at(k).filter(char::is_ascii_digit) {
                digits.push(d);
                form.places += 1;
                k += 1;
            }
        }
        let mut value: f64 = digits.parse().unwrap_or(f64::NAN);
        let mut decimals = form.places as i32;
        if matches!(at(k), Some('e' | 'E'))
            && let Some(len) = exponent_len(&b[k + 1..])
        {
            let e: String = b[k + 1..k + 1 + len].iter().map(|&(_, c)| c).collect();
            let e: i32 = e.replace('−', "-").parse().unwrap_or(0);
            value *= 10f64.powi(e);
            decimals -= e;
            form.exponent = Some(e);
            k += 1 + len;
        } else if at(k) == Some('^') && at(k + 1).is_some_and(|d| d.is_ascii_digit()) {
            let mut e = String::new();
            k += 1;
            while let Some(d) = at(k).filter(char::is_ascii_digit) {
                e.push(d);
                k += 1;
            }
            value = value.powi(e.parse().unwrap_or(1));
            form.power = true;
        }
        if matches!(c, '-' | '−') {
            value = -value;
        }
        let end = b.get(k).map_or(text.len(), |&(i, _)| i);
        out.push(Printed {
            value,
            decimals,
            claim: claim_before(&text[..b[start].0]),
            span: b[start].0..end,
            printed: text[b[start].0..end].to_string(),
            form,
        });
    }
    out
}

fn exponent_len(rest: &[(usize, char)]) -> Option<usize> {
    let sign = usize::from(matches!(rest.first(), Some((_, '-' | '+' | '−'))));
    let digits = rest[sign..]
        .iter()
        .take_while(|(_, c)| c.is_ascii_digit())
        .count();
    (digits > 0).then_some(sign + digits)
}

/// The claim of the words or symbol right before a number (`≤ 0.51`, "at most 0.51").
fn claim_before(before: &str) -> Claim {
    let b = before.trim_end().to_lowercase();
    let ends = |words: &[&str]| words.iter().any(|w| b.ends_with(w));
    if ends(&["<", "under", "below", "less than"]) {
        Claim::AtMost { strict: true }
    } else if ends(&["≤", "at most", "up to"]) {
        Claim::AtMost { strict: false }
    } else if ends(&[">", "over", "above", "more than"]) {
        Claim::AtLeast { strict: true }
    } else if ends(&["≥", "at least"]) {
        Claim::AtLeast { strict: false }
    } else {
        Claim::Equals
    }
}

/// The rule (docs/src/figures.md, "Rounding"): a printed number is its value rounded to
/// the digits printed, ties either way (|value − printed| ≤ half a unit in the last
/// printed place); a bound holds for the value so rounded.
pub fn agrees(p: &Printed, value: f64) -> bool {
    if !value.is_finite() {
        return false;
    }
    let unit = 10f64.powi(-p.decimals);
    // Slack for the binary representation of both numbers, far below any printed digit.
    let eps = unit * 1e-9 + value.abs() * 1e-12;
    let rounded = (value / unit).round() * unit;
    match p.claim {
        Claim::Equals => (value - p.value).abs() <= unit / 2.0 + eps,
        Claim::AtMost { strict: false } => rounded <= p.value + eps,
        Claim::AtMost { strict: true } => rounded < p.value - eps,
        Claim::AtLeast { strict: false } => rounded >= p.value - eps,
        Claim::AtLeast { strict: true } => rounded > p.value + eps,
    }
}

/// `value` printed as `p` was (the same places, exponent, separators and signs), or None
/// for what is not rewritten by hand: a bound (its words are a claim) and a power.
pub fn reprint(p: &Printed, value: f64) -> Option<String> {
    let f = &p.form;
    if f.power || p.claim != Claim::Equals || !value.is_finite() {
        return None;
    }
    let magnitude = value.abs() / 10f64.powi(f.exponent.unwrap_or(0));
    let mut s = format!("{:.*}", f.places, magnitude);
    if f.grouped {
        let (int, frac) = s.split_once('.').unwrap_or((&s, ""));
        let mut g = String::new();
        for (i, c) in int.chars().enumerate() {
            if i > 0 && (int.len() - i) % 3 == 0 {
                g.push(',');
            }
            g.push(c);
        }
        s = if frac.is_empty() {
            g
        } else {
            format!("{g}.{frac}")
        };
    }
    if let Some(e) = f.exponent {
        s = format!("{s}e{e}");
    }
    let zero = s.chars().all(|c| !c.is_ascii_digit() || c == '0');
    if value < 0.0 && !zero {
        s.insert(0, if f.unicode_minus { '−' } else { '-' });
    } else if f.plus || (value < 0.0 && p.value < 0.0) {
        // `+0.02 %` stays signed; a printed `−0.0` of a tiny negative stays `−0.0`.
        s.insert(
            0,
            if value < 0.0 {
                if f.unicode_minus { '−' } else { '-' }
            } else {
                '+'
            },
        );
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(text: &str) -> Vec<f64> {
        numbers(text).iter().map(|p| p.value).collect()
    }

    #[test]
    fn figures_printed_numbers_are_read_with_their_digits() {
        assert_eq!(values("0.84–1.07× on the others"), vec![0.84, 1.07]);
        assert_eq!(values("11 of 12 cells"), vec![11.0, 12.0]);
        assert_eq!(
            values("1,328 emissive triangles, −0.5 %"),
            vec![1328.0, -0.5]
        );
        assert_eq!(values("2^20 lights"), vec![1_048_576.0]);
        assert_eq!(values("`bvh-4` at 6.13 on x86_64"), vec![6.13]);
        assert_eq!(values("1.2-1.7×"), vec![1.2, 1.7]);
        let p = &numbers("7.64e-5")[0];
        assert_eq!((p.decimals, (p.value * 1e7).round()), (7, 764.0));
        let p = &numbers("0.10×")[0];
        assert_eq!(p.decimals, 2);
    }

    #[test]
    fn figures_round_to_the_printed_digits() {
        let p = |t: &str| numbers(t).remove(0);
        assert!(agrees(&p("0.10×"), 0.1022));
        assert!(!agrees(&p("0.10×"), 0.1051));
        assert!(agrees(&p("0.13"), 0.125) && agrees(&p("0.12"), 0.125));
        assert!(agrees(&p("664 lights"), 664.0));
        assert!(!agrees(&p("640 lights"), 664.0));
        assert!(agrees(&p("74.9 %"), 74.93));
        assert!(!agrees(&p("0.10"), f64::NAN));
    }

    #[test]
    fn figures_bounds_hold_after_rounding() {
        let p = |t: &str| numbers(t).remove(0);
        assert!(agrees(&p("at most 0.51×"), 0.5146));
        assert!(!agrees(&p("at most 0.51×"), 0.516));
        assert!(agrees(&p("≥ 5.0×"), 4.96));
        assert!(!agrees(&p("≥ 5.0×"), 4.64));
        assert!(agrees(&p("more than 2.3×"), 2.36));
        assert!(!agrees(&p("more than 2.3×"), 2.31));
        assert_eq!(p("up to 1.6×").claim, Claim::AtMost { strict: false });
    }

    #[test]
    fn figures_reprint_keeps_the_printed_form() {
        let p = |t: &str| numbers(t).remove(0);
        let r = |t: &str, v: f64| reprint(&p(t), v).unwrap_or_default();
        assert_eq!(r("0.10×", 0.1149), "0.11");
        assert_eq!(r("1,280 lights", 1328.0), "1,328");
        assert_eq!(r("−0.5 %", -0.71), "−0.7");
        assert_eq!(r("+0.02 %", 0.031), "+0.03");
        assert_eq!(r("12 ms", 12.6), "13");
        assert_eq!(r("7.64e-5", 8.123e-5), "8.12e-5");
        assert!(reprint(&p("at most 0.51×"), 0.6).is_none());
        assert!(reprint(&p("2^20"), 5.0).is_none());
    }
}
