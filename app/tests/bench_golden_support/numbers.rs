//! Cells, numbers and their tolerance: CSV rows, JSON leaves, and the numbers inside a line
//! of text.

/// The rows of a CSV text, each split into cells (quotes honoured, as the bench tests
/// read them).
pub fn csv_rows(text: &str) -> Vec<Vec<String>> {
    text.lines().map(crate::bench_support::split_csv).collect()
}

/// The largest magnitude among the cells that are numbers (0 without any).
pub fn scale<'a>(cells: impl Iterator<Item = &'a str>) -> f64 {
    cells
        .filter_map(|c| c.parse::<f64>().ok())
        .filter(|v| v.is_finite())
        .fold(0.0, |m, v| m.max(v.abs()))
}

/// Two cells agree when both are numbers no farther apart than `allowed(stored, now)`, or
/// the same text.
pub fn cells_agree(stored: &str, now: &str, allowed: impl Fn(f64, f64) -> f64) -> bool {
    match (stored.parse::<f64>(), now.parse::<f64>()) {
        (Ok(s), Ok(n)) if s.is_finite() && n.is_finite() => (s - n).abs() <= allowed(s, n),
        _ => stored == now,
    }
}

/// Every leaf of a JSON value with its path (`[0].figures.seeds`), as text.
pub fn leaves(value: &serde_json::Value, path: String, out: &mut Vec<(String, String)>) {
    match value {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                leaves(v, format!("{path}.{k}"), out);
            }
        }
        serde_json::Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                leaves(v, format!("{path}[{i}]"), out);
            }
        }
        leaf => out.push((path, leaf.to_string())),
    }
}

/// A path with its array positions left out: the leaves that form one column.
pub fn without_positions(path: &str) -> String {
    let mut out = String::new();
    let mut in_brackets = false;
    for c in path.chars() {
        match c {
            '[' => in_brackets = true,
            ']' => in_brackets = false,
            c if !in_brackets => out.push(c),
            _ => {}
        }
    }
    out
}

/// A line's text with each number replaced by `#`, and the numbers: `+0.95 % ± 15.68 %`
/// gives `# % ± # %` and [0.95, 15.68]. A sign belongs to a number only where no letter or
/// digit stands before it (`restir-pairwise` holds no number).
pub fn split_numbers(line: &str) -> (String, Vec<(f64, f64)>) {
    let chars: Vec<char> = line.chars().collect();
    let (mut skeleton, mut numbers) = (String::new(), Vec::new());
    let mut i = 0;
    while i < chars.len() {
        let word_before = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        let signed = matches!(chars[i], '+' | '-')
            && !word_before
            && chars.get(i + 1).is_some_and(char::is_ascii_digit);
        if !(chars[i].is_ascii_digit() && !word_before || signed) {
            skeleton.push(chars[i]);
            i += 1;
            continue;
        }
        let start = i;
        i += 1;
        while i < chars.len() && chars[i].is_ascii_digit() {
            i += 1;
        }
        let mut decimals = 0;
        if chars.get(i) == Some(&'.') && chars.get(i + 1).is_some_and(char::is_ascii_digit) {
            i += 1;
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
                decimals += 1;
            }
        }
        let mut exponent = 0;
        if chars.get(i) == Some(&'e') {
            let mut j = i + 1;
            if matches!(chars.get(j), Some('+' | '-')) {
                j += 1;
            }
            if chars.get(j).is_some_and(char::is_ascii_digit) {
                while j < chars.len() && chars[j].is_ascii_digit() {
                    j += 1;
                }
                let text: String = chars[i + 1..j].iter().collect();
                exponent = text.parse().unwrap_or(0);
                i = j;
            }
        }
        let text: String = chars[start..i].iter().collect();
        // One unit in the last printed digit: what rounding alone can move.
        let unit = 10f64.powi(exponent - decimals);
        numbers.push((text.parse().unwrap_or(f64::NAN), unit));
        skeleton.push('#');
    }
    (skeleton, numbers)
}
