//! Formulas evaluated against their data: references to cells, filters, arithmetic and the
//! reducing functions.

use std::path::{Path, PathBuf};
use std::rc::Rc;

use super::{EvalError, Expr, Filter, Ref};
use crate::data::{Table, Tables};

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
                Err(EvalError::Missing(format!(
                    "first(): no argument has a value ({})",
                    why.join("; ")
                )))
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
                            return other(format!(
                                "`{v}` means a table row's cell: only in a table"
                            ));
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
fn number(cell: &str) -> Option<f64> {
    match cell {
        "true" => Some(1.0),
        "false" => Some(0.0),
        "" => None,
        c => c.parse().ok(),
    }
}

/// `pattern` with `*` for any run of characters.
pub(super) fn glob(pattern: &str, text: &str) -> bool {
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
