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

mod eval;
mod parse;
#[cfg(test)]
mod tests;

pub use eval::Scope;
pub use parse::{parse, parse_filters};

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
    Text {
        cell: String,
        what: String,
    },
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
