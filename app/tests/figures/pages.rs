//! Where a page quotes data: figure links, `<!-- figures: ... -->` tables, and the
//! ratios and times it prints outside them (docs/src/figures.md).

use std::ops::Range;
use std::path::{Path, PathBuf};

/// A Markdown page, with the parts that are not prose (code, comments) marked.
pub struct Page {
    /// Relative to the repository root, as findings name it.
    pub name: String,
    pub path: PathBuf,
    pub text: String,
    /// Bytes inside fenced or inline code, and inside HTML comments.
    code: Vec<bool>,
    comment: Vec<bool>,
}

/// `[printed](data.csv "formula")`.
pub struct FigureLink {
    /// The printed text between the brackets, and the whole link.
    pub text: Range<usize>,
    pub span: Range<usize>,
    pub file: PathBuf,
    pub formula: String,
}

/// A link whose text is quoted from elsewhere or has no data: not a checked figure, but
/// not an unbound one either.
pub struct OtherLink {
    pub span: Range<usize>,
    pub target: String,
}

/// A table bound to data by the comment before it.
pub struct BoundTable {
    /// The comment, for findings.
    pub at: usize,
    pub file: PathBuf,
    pub rows: Rows,
    /// One formula per table column; None for a column that is not checked (`-`).
    pub columns: Vec<Option<String>>,
    /// Body rows: each cell's byte range in the page.
    pub body: Vec<Vec<Range<usize>>>,
}

pub enum Rows {
    /// Each body row's selector: `[file.csv:] key=value, ...`.
    Listed(Vec<String>),
    /// The body row whose first cell (code marks and emphasis dropped) is this column's cell.
    Keyed(String),
}

impl Page {
    pub fn read(root: &Path, name: &str) -> Result<Page, String> {
        let path = root.join(name);
        let text = std::fs::read_to_string(&path).map_err(|e| format!("{name}: {e}"))?;
        Ok(Page::new(name, path, text))
    }

    pub fn new(name: &str, path: PathBuf, text: String) -> Page {
        let (code, comment) = masks(&text);
        Page {
            name: name.to_string(),
            path,
            text,
            code,
            comment,
        }
    }

    pub fn line_of(&self, byte: usize) -> usize {
        self.text[..byte].matches('\n').count() + 1
    }

    /// In code or a comment: not printed prose.
    pub fn in_code(&self, byte: usize) -> bool {
        self.code.get(byte).copied().unwrap_or(false)
            || self.comment.get(byte).copied().unwrap_or(false)
    }

    fn dir(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }

    /// Every link of the page: figure links (a data file and a title) and the others.
    pub fn links(&self) -> (Vec<FigureLink>, Vec<OtherLink>) {
        let (mut figures, mut others) = (Vec::new(), Vec::new());
        let t = &self.text;
        for (i, _) in t.match_indices("](") {
            if self.in_code(i) {
                continue;
            }
            let Some(open) = opening_bracket(t, i) else {
                continue;
            };
            let rest = &t[i + 2..];
            let dest_len = rest
                .find(|c: char| c.is_whitespace() || c == ')')
                .unwrap_or(rest.len());
            let dest = &rest[..dest_len];
            let after = rest[dest_len..].trim_start();
            let title = after
                .strip_prefix('"')
                .and_then(|s| s.find("\")").or_else(|| s.find('"')).map(|e| &s[..e]));
            let text = open + 1..i;
            let close = match title {
                Some(f) => {
                    let title_at = i + 2 + dest_len + (rest[dest_len..].len() - after.len()) + 1;
                    t[title_at + f.len()..]
                        .find(')')
                        .map(|c| title_at + f.len() + c + 1)
                }
                None => rest[dest_len..].find(')').map(|c| i + 2 + dest_len + c + 1),
            };
            let span = open..close.unwrap_or(i + 2 + dest_len);
            let data = dest.ends_with(".csv") || dest.ends_with(".json");
            match title {
                Some(formula) if data => figures.push(FigureLink {
                    text,
                    span,
                    file: crate::data::normalise(&self.dir().join(dest)),
                    formula: formula.split_whitespace().collect::<Vec<_>>().join(" "),
                }),
                _ => others.push(OtherLink {
                    span,
                    target: dest.to_string(),
                }),
            }
        }
        (figures, others)
    }

    /// The tables bound by a `<!-- figures: FILE rows: ...|key: ... columns: ... -->` comment,
    /// and the comments that cannot bind their table (each with the table's cells, which
    /// are then not also reported as unbound).
    pub fn bound_tables(&self) -> (Vec<BoundTable>, Vec<(String, Vec<Range<usize>>)>) {
        let (mut out, mut broken) = (Vec::new(), Vec::new());
        for (at, _) in self.text.match_indices("<!-- figures:") {
            if self.code[at] {
                continue; // an example in a code block
            }
            let line = self.line_of(at);
            let fail = |what: &str| format!("{}:{line}: {what}", self.name);
            let Some(end) = self.text[at..].find("-->").map(|e| at + e) else {
                broken.push((fail("unclosed `<!-- figures:` comment"), Vec::new()));
                continue;
            };
            let body = match self.table_after(end + 3) {
                Ok(body) => body,
                Err(e) => {
                    broken.push((fail(&e), Vec::new()));
                    continue;
                }
            };
            match self.bind(at, &self.text[at + "<!-- figures:".len()..end], body) {
                Ok(table) => out.push(table),
                Err((what, body)) => {
                    broken.push((fail(&what), body.into_iter().flatten().collect()))
                }
            }
        }
        (out, broken)
    }

    /// One comment's table: its file, rows and columns.
    #[allow(clippy::type_complexity)]
    fn bind(
        &self,
        at: usize,
        spec: &str,
        body: Vec<Vec<Range<usize>>>,
    ) -> Result<BoundTable, (String, Vec<Vec<Range<usize>>>)> {
        let field = |name: &str| -> Option<String> {
            let start = spec.find(name)? + name.len();
            let stop = ["rows:", "key:", "columns:"]
                .iter()
                .filter_map(|k| spec[start..].find(k))
                .min()
                .map_or(spec.len(), |s| start + s);
            Some(
                spec[start..stop]
                    .split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" "),
            )
        };
        let first_field = ["rows:", "key:", "columns:"]
            .iter()
            .filter_map(|k| spec.find(k))
            .min()
            .unwrap_or(spec.len());
        let rows = match (field("rows:"), field("key:")) {
            (Some(r), None) => Rows::Listed(split_outside_quotes(&r)),
            (None, Some(k)) => Rows::Keyed(k),
            _ => return Err(("a bound table needs one of `rows:` or `key:`".into(), body)),
        };
        let Some(columns) = field("columns:") else {
            return Err(("a bound table needs `columns:`".into(), body));
        };
        let columns: Vec<Option<String>> = split_outside_quotes(&columns)
            .into_iter()
            .map(|c| Some(c).filter(|c| c != "-"))
            .collect();
        if let Some(r) = body.iter().find(|r| r.len() != columns.len()) {
            let what = format!(
                "the table has {} columns, `columns:` names {}",
                r.len(),
                columns.len()
            );
            return Err((what, body));
        }
        Ok(BoundTable {
            at,
            file: crate::data::normalise(&self.dir().join(spec[..first_field].trim())),
            rows,
            columns,
            body,
        })
    }

    /// The body cells of the Markdown table that starts on the first non-blank line after
    /// byte `from` (header and separator skipped).
    fn table_after(&self, from: usize) -> Result<Vec<Vec<Range<usize>>>, String> {
        let mut lines = Vec::new();
        let mut start = from + self.text[from..].find('\n').map_or(0, |n| n + 1);
        let mut seen_table = false;
        while start < self.text.len() {
            let end = self.text[start..]
                .find('\n')
                .map_or(self.text.len(), |n| start + n);
            let line = &self.text[start..end];
            if line.trim_start().starts_with('|') {
                seen_table = true;
                lines.push(start..end);
            } else if seen_table || !line.trim().is_empty() {
                break;
            }
            start = end + 1;
        }
        if lines.len() < 3 {
            return Err("a `<!-- figures:` comment with no table of data rows after it".into());
        }
        Ok(lines[2..].iter().map(|l| self.cells(l.clone())).collect())
    }

    /// The cells of one table line: split at `|` outside code and not escaped.
    fn cells(&self, line: Range<usize>) -> Vec<Range<usize>> {
        let t = &self.text;
        let mut bars: Vec<usize> = Vec::new();
        let mut in_code = false;
        for (i, c) in t[line.clone()].char_indices() {
            let at = line.start + i;
            match c {
                '`' => in_code = !in_code,
                '|' if !in_code && !t[..at].ends_with('\\') => bars.push(at),
                _ => {}
            }
        }
        bars.windows(2).map(|w| w[0] + 1..w[1]).collect()
    }

    /// Prose ranges that print a ratio (`1.3×`) or a time (`12 ms`) outside code, figure
    /// links, quotes from elsewhere (an http link) and `skip` (bound table cells).
    pub fn unbound_figures(&self, skip: &[Range<usize>]) -> Vec<Range<usize>> {
        let mut covered: Vec<bool> = self
            .code
            .iter()
            .zip(&self.comment)
            .map(|(a, b)| *a || *b)
            .collect();
        for r in skip {
            covered[r.clone()].iter_mut().for_each(|b| *b = true);
        }
        let mut out = Vec::new();
        for p in crate::text::numbers(&self.text) {
            if covered[p.span.start] {
                continue;
            }
            // `1.3×` is a measured ratio; `4×4` and `14 × 5 m` are sizes, `2 × (1 + 2)`
            // arithmetic (a space before the sign).
            let next = &self.text[p.span.end..];
            let ratio = next.starts_with('×')
                && !next['×'.len_utf8()..]
                    .trim_start()
                    .starts_with(|c: char| c.is_ascii_digit());
            let after = next.trim_start_matches([' ', '\u{a0}', '\u{2009}']);
            let time =
                after.starts_with("ms") && !after[2..].starts_with(|c: char| c.is_alphanumeric());
            if ratio || time {
                out.push(p.span);
            }
        }
        out
    }
}

/// `a; b='x;y'; c` as `a`, `b='x;y'`, `c`: a `;` inside a quoted filter value is the value's.
fn split_outside_quotes(list: &str) -> Vec<String> {
    let (mut out, mut part, mut quoted) = (Vec::new(), String::new(), false);
    for c in list.chars() {
        match c {
            '\'' => {
                quoted = !quoted;
                part.push(c);
            }
            ';' if !quoted => out.push(std::mem::take(&mut part).trim().to_string()),
            c => part.push(c),
        }
    }
    out.push(part.trim().to_string());
    out
}

/// The `[` that opens the link text ending at `close` (the `]` of `](`), brackets nested.
fn opening_bracket(t: &str, close: usize) -> Option<usize> {
    let mut depth = 0;
    for (i, c) in t[..close].char_indices().rev() {
        match c {
            ']' => depth += 1,
            '[' if depth == 0 => return Some(i),
            '[' => depth -= 1,
            '\n' if t[..i].ends_with('\n') => return None, // a blank line ends a paragraph
            _ => {}
        }
        if close - i > 600 {
            return None;
        }
    }
    None
}

/// Fenced code blocks and inline code spans; HTML comments outside them.
fn masks(text: &str) -> (Vec<bool>, Vec<bool>) {
    let mut mask = vec![false; text.len()];
    let mut fenced = false;
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        let end = start + line.len();
        if line.trim_start().starts_with("```") {
            mask[start..end].iter_mut().for_each(|b| *b = true);
            fenced = !fenced;
        } else if fenced {
            mask[start..end].iter_mut().for_each(|b| *b = true);
        } else {
            let mut open = None;
            for (i, c) in line.char_indices() {
                if c == '`' {
                    match open {
                        None => open = Some(start + i),
                        Some(o) => {
                            mask[o..=start + i].iter_mut().for_each(|b| *b = true);
                            open = None;
                        }
                    }
                }
            }
        }
        start = end;
    }
    let mut comment = vec![false; text.len()];
    let mut from = 0;
    while let Some(s) = text[from..].find("<!--") {
        let s = from + s;
        let e = text[s..].find("-->").map_or(text.len(), |e| s + e + 3);
        if !mask[s] {
            comment[s..e].iter_mut().for_each(|b| *b = true);
        }
        from = e;
    }
    (mask, comment)
}
