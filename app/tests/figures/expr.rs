//! The formula in a figure's link title: which cells of its data file the figure is, and
//! what arithmetic turns them into the number the page prints (docs/src/figures.md,
//! "Formulas").
//!
//! `column` is a column of the figure's file; `column[key=value, other!=a|b]` keeps the rows
//! whose cells match (`*` in a value matches any text, `'...'` quotes a value holding
//! commas, brackets or `|`, `$name` is the current table row's own cell); `path.csv:column`
//! reads another file, its path relative to the figure's file. A column over several rows
//! is a list: `min`, `max`, `mean`, `median`, `sum` and `count` reduce it (the last two
//! read a filter matching no row as nothing), `first(a, b)` takes the first that has a value,
//! arithmetic (`+ - * / ^`, comparisons giving 1 or 0) goes element by element, and commas
//! at the top separate the values of a figure with several numbers (a range, an interval, "11 of 12").

use std::path::{Path, PathBuf};
use std::rc::Rc;

use crate::data::{Table, Tables};

#[derive(Clone, Debug)]
pub enum Expr {
    Num(f64),
    Ref(Ref),
    Neg(Box<Expr>),
    Bin(char, Box<Expr>, Box<Expr>),
    Cmp(&'static str, Box<Expr>, Box<Expr>),
    Call(String, Vec<Expr>),
}

#[derive(Clone, Debug)]
pub struct Ref {
    pub file: Option<String>,
    pub column: String,
    pub filters: Option<Vec<Filter>>,
}

#[derive(Clone, Debug)]
pub struct Filter {
    pub key: String,
    pub negate: bool,
    /// A literal (with `*` as a wildcard) or, starting with `$`, the current row's cell.
    pub values: Vec<String>,
}

/// Why a formula has no value: a referenced cell is empty (a table cell that prints no
/// number then agrees), holds text (a table cell that prints the same text agrees:
/// `never`), or anything else.
#[derive(Debug)]
pub enum EvalError {
    Missing(String),
    /// A filter that matches no row: an error, except inside `count` and `sum` (none).
    NoRow(String),
    Text { cell: String, what: String },
    Other(String),
}

impl std::fmt::Display for EvalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EvalError::Missing(s) | EvalError::NoRow(s) | EvalError::Other(s) => f.write_str(s),
            EvalError::Text { what, .. } => f.write_str(what),
        }
    }
}

pub fn parse(text: &str) -> Result<Vec<Expr>, String> {
    let mut p = Parser {
        s: text.chars().collect(),
        i: 0,
    };
    let mut list = vec![p.expr()?];
    while p.eat(',') {
        list.push(p.expr()?);
    }
    p.skip_space();
    if p.i < p.s.len() {
        return Err(format!(
            "formula `{text}`: unexpected `{}` at character {}",
            p.rest(),
            p.i + 1
        ));
    }
    Ok(list)
}

/// The filters of a table row's selector (`config=ris, scene=a`), as inside `[...]`.
pub fn parse_filters(text: &str) -> Result<Vec<Filter>, String> {
    let mut p = Parser {
        s: format!("{text}]").chars().collect(),
        i: 0,
    };
    let filters = p.filters()?;
    p.skip_space();
    if p.i < p.s.len() {
        return p.fail("unexpected text after the filters");
    }
    Ok(filters)
}

struct Parser {
    s: Vec<char>,
    i: usize,
}

impl Parser {
    fn skip_space(&mut self) {
        while self.s.get(self.i).is_some_and(|c| c.is_whitespace()) {
            self.i += 1;
        }
    }
    fn peek(&mut self) -> Option<char> {
        self.skip_space();
        self.s.get(self.i).copied()
    }
    fn eat(&mut self, c: char) -> bool {
        if self.peek() == Some(c) {
            self.i += 1;
            true
        } else {
            false
        }
    }
    fn eat_str(&mut self, t: &str) -> bool {
        self.skip_space();
        let n = t.chars().count();
        if self.s[self.i..].iter().take(n).copied().eq(t.chars()) {
            self.i += n;
            true
        } else {
            false
        }
    }
    fn rest(&self) -> String {
        self.s[self.i..].iter().collect()
    }
    fn fail<T>(&self, what: &str) -> Result<T, String> {
        let text: String = self.s.iter().collect();
        Err(format!("formula `{text}`: {what} at `{}`", self.rest()))
    }

    fn expr(&mut self) -> Result<Expr, String> {
        let left = self.sum()?;
        for op in ["<=", ">=", "==", "!=", "<", ">"] {
            if self.eat_str(op) {
                return Ok(Expr::Cmp(op, Box::new(left), Box::new(self.sum()?)));
            }
        }
        Ok(left)
    }
    fn sum(&mut self) -> Result<Expr, String> {
        let mut e = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek() {
            self.i += 1;
            e = Expr::Bin(op, Box::new(e), Box::new(self.product()?));
        }
        Ok(e)
    }
    fn product(&mut self) -> Result<Expr, String> {
        let mut e = self.unary()?;
        while let Some(op @ ('*' | '/')) = self.peek() {
            self.i += 1;
            e = Expr::Bin(op, Box::new(e), Box::new(self.unary()?));
        }
        Ok(e)
    }
    fn unary(&mut self) -> Result<Expr, String> {
        if self.eat('-') {
            return Ok(Expr::Neg(Box::new(self.unary()?)));
        }
        let base = self.atom()?;
        if self.eat('^') {
            return Ok(Expr::Bin('^', Box::new(base), Box::new(self.unary()?)));
        }
        Ok(base)
    }
    fn atom(&mut self) -> Result<Expr, String> {
        if self.eat('(') {
            let e = self.expr()?;
            if !self.eat(')') {
                return self.fail("expected `)`");
            }
            return Ok(e);
        }
        let file = self.file_prefix();
        match self.peek() {
            Some(c) if file.is_none() && (c.is_ascii_digit() || c == '.') => self.number(),
            Some(c) if c.is_ascii_alphabetic() || c == '_' => {
                let name = self.word(|c| c.is_ascii_alphanumeric() || "_.".contains(c));
                if file.is_none() && self.eat('(') {
                    let mut args = Vec::new();
                    if !self.eat(')') {
                        args.push(self.expr()?);
                        while self.eat(',') {
                            args.push(self.expr()?);
                        }
                        if !self.eat(')') {
                            return self.fail("expected `)` after the arguments");
                        }
                    }
                    return Ok(Expr::Call(name, args));
                }
                let filters = if self.eat('[') {
                    Some(self.filters()?)
                } else {
                    None
                };
                Ok(Expr::Ref(Ref {
                    file,
                    column: name,
                    filters,
                }))
            }
            _ => self.fail("expected a number, a column or `(`"),
        }
    }
    /// `path.csv:` or `path.json:` before a column.
    fn file_prefix(&mut self) -> Option<String> {
        self.skip_space();
        let start = self.i;
        let word = self.word(|c| c.is_ascii_alphanumeric() || "_./-".contains(c));
        if (word.ends_with(".csv") || word.ends_with(".json")) && self.s.get(self.i) == Some(&':') {
            self.i += 1;
            return Some(word);
        }
        self.i = start;
        None
    }
    fn word(&mut self, ok: impl Fn(char) -> bool) -> String {
        let start = self.i;
        while self.s.get(self.i).is_some_and(|&c| ok(c)) {
            self.i += 1;
        }
        self.s[start..self.i].iter().collect()
    }
    fn number(&mut self) -> Result<Expr, String> {
        let mut text = self.word(|c| c.is_ascii_digit() || c == '.');
        if matches!(self.s.get(self.i), Some('e' | 'E')) {
            let mark = self.i;
            self.i += 1;
            let sign = if matches!(self.s.get(self.i), Some('-' | '+')) {
                self.i += 1;
                self.s[self.i - 1].to_string()
            } else {
                String::new()
            };
            let digits = self.word(|c| c.is_ascii_digit());
            if digits.is_empty() {
                self.i = mark;
            } else {
                text = format!("{text}e{sign}{digits}");
            }
        }
        match text.parse() {
            Ok(v) => Ok(Expr::Num(v)),
            Err(_) => self.fail("not a number"),
        }
    }
    fn filters(&mut self) -> Result<Vec<Filter>, String> {
        let mut out = Vec::new();
        loop {
            self.skip_space();
            let key = self.word(|c| c.is_ascii_alphanumeric() || "_.".contains(c));
            if key.is_empty() {
                return self.fail("expected a column name in the filter");
            }
            let negate = if self.eat_str("!=") {
                true
            } else if self.eat('=') {
                false
            } else {
                return self.fail("expected `=` or `!=` in the filter");
            };
            let mut values = vec![self.value()?];
            while self.eat('|') {
                values.push(self.value()?);
            }
            out.push(Filter {
                key,
                negate,
                values,
            });
            if self.eat(']') {
                return Ok(out);
            }
            if !self.eat(',') {
                return self.fail("expected `,` or `]` in the filter");
            }
        }
    }
    fn value(&mut self) -> Result<String, String> {
        if self.eat('\'') {
            let v = self.word(|c| c != '\'');
            if !self.eat('\'') {
                return self.fail("unclosed `'`");
            }
            return Ok(v);
        }
        self.skip_space();
        Ok(self.word(|c| !",]|".contains(c)).trim().to_string())
    }
}

/// Where a formula is evaluated: its file's folder, the file itself, and (in a table) the
/// row its bare column names mean.
pub struct Scope<'a> {
    pub tables: &'a mut Tables,
    pub file: PathBuf,
    pub row: Option<(Rc<Table>, usize)>,
}

type Values = Result<Vec<f64>, EvalError>;

fn other<T>(s: String) -> Result<T, EvalError> {
    Err(EvalError::Other(s))
}

impl Scope<'_> {
    fn dir(&self) -> &Path {
        self.file.parent().unwrap_or(Path::new("."))
    }

    pub fn eval(&mut self, e: &Expr) -> Values {
        match e {
            Expr::Num(v) => Ok(vec![*v]),
            Expr::Ref(r) => self.reference(r),
            Expr::Neg(a) => Ok(self.eval(a)?.into_iter().map(|v| -v).collect()),
            Expr::Bin(op, a, b) => {
                let f = |x: f64, y: f64| match op {
                    '+' => x + y,
                    '-' => x - y,
                    '*' => x * y,
                    '/' => x / y,
                    _ => x.powf(y),
                };
                zip(self.eval(a)?, self.eval(b)?, f)
            }
            Expr::Cmp(op, a, b) => {
                let f = |x: f64, y: f64| {
                    let t = match *op {
                        "<" => x < y,
                        ">" => x > y,
                        "<=" => x <= y,
                        ">=" => x >= y,
                        "==" => x == y,
                        _ => x != y,
                    };
                    if t { 1.0 } else { 0.0 }
                };
                zip(self.eval(a)?, self.eval(b)?, f)
            }
            // `first(a, b, ...)`: the first argument that has a value (its cells not empty,
            // its filters matching), for a figure read from a confirmation run where
            // there is one and from the first run elsewhere.
            Expr::Call(name, args) if name == "first" => {
                let mut why = Vec::new();
                for a in args {
                    match self.eval(a) {
                        Err(e @ (EvalError::Missing(_) | EvalError::NoRow(_))) => {
                            why.push(e.to_string())
                        }
                        v => return v,
                    }
                }
                Err(EvalError::Missing(format!("first(): no argument has a value ({})", why.join("; "))))
            }
            Expr::Call(name, args) => {
                let mut all = Vec::new();
                for a in args {
                    match self.eval(a) {
                        // No row is nothing to count or add.
                        Err(EvalError::NoRow(_)) if name == "count" || name == "sum" => {}
                        v => all.extend(v?),
                    }
                }
                call(name, all)
            }
        }
    }

    fn reference(&mut self, r: &Ref) -> Values {
        let table = match &r.file {
            Some(f) => {
                let path = self.dir().join(f);
                self.tables.get(&path).or_else(other)?
            }
            None => match &self.row {
                Some((t, _)) => t.clone(),
                None => self.tables.get(&self.file.clone()).or_else(other)?,
            },
        };
        let column = table.column(&r.column).or_else(other)?;
        let rows: Vec<usize> = match (&r.filters, &self.row) {
            // A bare column in a table row is that row's cell (of the row's own file).
            (None, Some((t, row))) if r.file.is_none() || Rc::ptr_eq(t, &table) => vec![*row],
            (None, _) => (0..table.rows.len()).collect(),
            (Some(filters), _) => self.matching(&table, filters)?,
        };
        if rows.is_empty() {
            return Err(EvalError::NoRow(format!(
                "{}: no row where {}",
                table.path.display(),
                describe(r.filters.as_deref().unwrap_or(&[]))
            )));
        }
        rows.iter()
            .map(|&i| {
                let cell = table.rows[i][column].trim();
                number(cell).ok_or_else(|| {
                    let what = format!(
                        "{} line {}, column `{}`: {}",
                        table.path.display(),
                        i + 2,
                        r.column,
                        if cell.is_empty() {
                            "empty".to_string()
                        } else {
                            format!("`{cell}` is not a number")
                        }
                    );
                    if cell.is_empty() {
                        EvalError::Missing(what)
                    } else {
                        EvalError::Text {
                            cell: cell.to_string(),
                            what,
                        }
                    }
                })
            })
            .collect()
    }

    pub fn matching(&self, table: &Table, filters: &[Filter]) -> Result<Vec<usize>, EvalError> {
        let mut wanted = Vec::new();
        for f in filters {
            let column = table.column(&f.key).or_else(other)?;
            let mut values = Vec::new();
            for v in &f.values {
                values.push(match v.strip_prefix('$') {
                    Some(name) => {
                        let Some((t, row)) = &self.row else {
                            return other(format!("`{v}` means a table row's cell: only in a table"));
                        };
                        t.rows[*row][t.column(name).or_else(other)?].clone()
                    }
                    None => v.clone(),
                });
            }
            wanted.push((column, f.negate, values));
        }
        Ok((0..table.rows.len())
            .filter(|&i| {
                wanted.iter().all(|(c, negate, values)| {
                    values.iter().any(|v| glob(v, table.rows[i][*c].trim())) != *negate
                })
            })
            .collect())
    }
}

fn describe(filters: &[Filter]) -> String {
    filters
        .iter()
        .map(|f| {
            format!(
                "{}{}{}",
                f.key,
                if f.negate { "!=" } else { "=" },
                f.values.join("|")
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A cell as a number: decimals, `inf`, `NaN`, and `true`/`false` as 1/0.
pub fn number(cell: &str) -> Option<f64> {
    match cell {
        "true" => Some(1.0),
        "false" => Some(0.0),
        "" => None,
        c => c.parse().ok(),
    }
}

/// `pattern` with `*` for any run of characters.
fn glob(pattern: &str, text: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == text;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !text.starts_with(first) || !text[first.len()..].ends_with(last) {
        return false;
    }
    let mut rest = &text[first.len()..text.len() - last.len()];
    for p in &parts[1..parts.len() - 1] {
        match rest.find(p) {
            Some(i) => rest = &rest[i + p.len()..],
            None => return false,
        }
    }
    true
}

fn zip(a: Vec<f64>, b: Vec<f64>, f: impl Fn(f64, f64) -> f64) -> Values {
    match (a.len(), b.len()) {
        (1, _) => Ok(b.iter().map(|&y| f(a[0], y)).collect()),
        (_, 1) => Ok(a.iter().map(|&x| f(x, b[0])).collect()),
        (n, m) if n == m => Ok(a.iter().zip(&b).map(|(&x, &y)| f(x, y)).collect()),
        (n, m) => other(format!(
            "lists of {n} and {m} values do not pair up element by element"
        )),
    }
}

fn call(name: &str, v: Vec<f64>) -> Values {
    let one = |x: f64| Ok(vec![x]);
    if v.is_empty() && name != "count" && name != "sum" {
        return other(format!("{name}() of nothing"));
    }
    match name {
        "min" => one(v.iter().copied().fold(f64::INFINITY, f64::min)),
        "max" => one(v.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        "sum" => one(v.iter().sum()),
        "count" => one(v.len() as f64),
        "mean" => one(v.iter().sum::<f64>() / v.len() as f64),
        "median" => {
            let mut s = v.clone();
            s.sort_by(f64::total_cmp);
            let n = s.len();
            one(if n % 2 == 1 {
                s[n / 2]
            } else {
                (s[n / 2 - 1] + s[n / 2]) / 2.0
            })
        }
        "sqrt" => Ok(v.iter().map(|x| x.sqrt()).collect()),
        "abs" => Ok(v.iter().map(|x| x.abs()).collect()),
        "ln" => Ok(v.iter().map(|x| x.ln()).collect()),
        "exp" => Ok(v.iter().map(|x| x.exp()).collect()),
        _ => other(format!(
            "no function `{name}` (min, max, mean, median, sum, count, first, sqrt, abs, ln, exp)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval_in(csv: &str, formula: &str) -> Result<Vec<Vec<f64>>, String> {
        let dir = std::env::temp_dir().join(format!("figures-expr-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join(format!("t{}.csv", formula.len()));
        std::fs::write(&file, csv).unwrap();
        let mut tables = Tables::default();
        let mut scope = Scope {
            tables: &mut tables,
            file,
            row: None,
        };
        parse(formula)?
            .iter()
            .map(|e| scope.eval(e).map_err(|e| e.to_string()))
            .collect()
    }

    const CSV: &str = "config,scene,ms,rmse\nris,a,10,0.2\nrestir,a,30,0.05\nris,b,12,\n\
                       x[1],b,5,0.1\n";

    #[test]
    fn figures_formulas_select_rows_and_do_arithmetic() {
        let v = eval_in(CSV, "(rmse[config=restir]/rmse[config=ris, scene=a])^2").unwrap();
        assert!((v[0][0] - 0.0625).abs() < 1e-12);
        let v = eval_in(CSV, "min(ms[scene=a]), max(ms), count(ms[config!=ris])").unwrap();
        assert_eq!(v, vec![vec![10.0], vec![30.0], vec![2.0]]);
        let v = eval_in(CSV, "sum(ms[config=r*] > 11)").unwrap();
        assert_eq!(v, vec![vec![2.0]]);
        let v = eval_in(CSV, "ms[config='x[1]']").unwrap();
        assert_eq!(v, vec![vec![5.0]]);
        let v = eval_in(CSV, "first(rmse[config=ris, scene=b], ms[config=ris, scene=b]), count(ms[config=nee])").unwrap();
        assert_eq!(v, vec![vec![12.0], vec![0.0]]);
    }

    #[test]
    fn figures_formulas_name_what_is_missing() {
        let e = eval_in(CSV, "rmse[config=ris, scene=b]").unwrap_err();
        assert!(e.contains("line 4, column `rmse`: empty"), "{e}");
        let e = eval_in(CSV, "rmse[config=nee]").unwrap_err();
        assert!(e.contains("no row where config=nee"), "{e}");
        let e = eval_in(CSV, "time").unwrap_err();
        assert!(e.contains("no column `time`") && e.contains("config, scene, ms, rmse"), "{e}");
        assert!(parse("ms[config=ris").is_err());
        assert!(parse("ms + ").is_err());
    }

    #[test]
    fn figures_globs_match_runs_of_characters() {
        assert!(glob("con*-static", "concourse-384x256-static"));
        assert!(!glob("con*-static", "concourse-384x256-pan"));
        assert!(glob("*", ""));
        assert!(glob("a*b*c", "aXbYc"));
    }
}
