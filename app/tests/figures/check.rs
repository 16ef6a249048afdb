//! Checks a page's figures against their data and says, for each that disagrees, which
//! page, line, file and formula (docs/src/figures.md).

use std::ops::Range;
use std::path::Path;
use std::rc::Rc;

use crate::data::Tables;
use crate::expr::{self, EvalError, Scope};
use crate::pages::{BoundTable, Page, Rows};
use crate::text::{self, Printed};

/// What checking one page found.
#[derive(Default)]
pub struct Report {
    /// `page:line: what`, one per disagreement.
    pub findings: Vec<String>,
    /// The corrections `FIGURES_WRITE=1` makes: a printed number and its data's value,
    /// printed alike.
    pub edits: Vec<(Range<usize>, String)>,
    pub figures: usize,
    pub tables: usize,
}

/// Where a link may point instead of data and still print a ratio or a time: a quote from
/// elsewhere, or the book's list of figures without data.
fn is_quote_or_declared(target: &str) -> bool {
    target.starts_with("http://")
        || target.starts_with("https://")
        || target.ends_with("figures.md#without-data")
}

pub fn check_page(page: &Page, tables: &mut Tables, root: &Path) -> Report {
    let mut report = Report::default();
    let mut bound: Vec<Range<usize>> = Vec::new();
    let (figures, others) = page.links();
    for link in &figures {
        bound.push(link.span.clone());
        report.figures += 1;
        let line = page.line_of(link.text.start);
        let fail = |what: String| format!("{}:{line}: {what}", page.name);
        if !link.file.is_file() {
            report.findings.push(fail(format!(
                "links `{}`, which does not exist",
                shown_path(&link.file, root)
            )));
            continue;
        }
        if let Some(missing) = command_missing(&link.file, root) {
            report.findings.push(fail(missing));
        }
        let printed = printed_in(page, link.text.clone());
        let mut scope = Scope {
            tables,
            file: link.file.clone(),
            row: None,
        };
        let values = evaluate(&mut scope, &link.formula).map_err(|e| e.to_string());
        compare(
            &mut report,
            &printed,
            values,
            &fail,
            &link.formula,
            &link.file,
            root,
        );
    }
    for link in &others {
        if is_quote_or_declared(&link.target) {
            bound.push(link.span.clone());
        }
    }
    let (bound_tables, broken) = page.bound_tables();
    for t in &bound_tables {
        report.tables += 1;
        check_table(page, t, tables, root, &mut report, &mut bound);
    }
    for (what, cells) in broken {
        report.findings.push(what);
        bound.extend(cells);
    }
    for span in page.unbound_figures(&bound) {
        report.findings.push(format!(
            "{}:{}: `{}…` is not bound to data (docs/src/figures.md)",
            page.name,
            page.line_of(span.start),
            context(&page.text, span)
        ));
    }
    report
}

fn check_table(
    page: &Page,
    t: &BoundTable,
    tables: &mut Tables,
    root: &Path,
    report: &mut Report,
    bound: &mut Vec<Range<usize>>,
) {
    let at = page.line_of(t.at);
    if let Rows::Listed(rows) = &t.rows
        && rows.len() != t.body.len()
    {
        report.findings.push(format!(
            "{}:{at}: `rows:` lists {} rows, the table has {}",
            page.name,
            rows.len(),
            t.body.len()
        ));
        return;
    }
    for (i, cells) in t.body.iter().enumerate() {
        let line = page.line_of(cells[0].start);
        let fail = |what: String| format!("{}:{line}: {what}", page.name);
        let selector = match &t.rows {
            Rows::Listed(rows) => rows[i].clone(),
            Rows::Keyed(column) => {
                let key = page.text[cells[0].clone()].replace(['`', '*'], "");
                format!("{column}='{}'", key.trim())
            }
        };
        let (file, row) = match select_row(tables, &t.file, &selector) {
            Ok(found) => found,
            Err(e) => {
                report.findings.push(fail(format!("row `{selector}`: {e}")));
                continue;
            }
        };
        if i == 0
            && let Some(missing) = command_missing(&file.path, root)
        {
            report.findings.push(fail(missing));
        }
        for (cell, formula) in cells.iter().zip(&t.columns) {
            let Some(formula) = formula else {
                continue;
            };
            bound.push(cell.clone());
            let printed = printed_in(page, cell.clone());
            let mut scope = Scope {
                tables,
                file: file.path.clone(),
                row: Some((file.clone(), row)),
            };
            let shown = page.text[cell.clone()].replace(['`', '*'], "");
            let values = match evaluate(&mut scope, formula) {
                // A cell that prints no number agrees with an empty data cell or a filter that
                // matches no row (a baseline's own interval), and one that prints a text
                // cell's text (`never`) with it.
                Err(EvalError::Missing(_) | EvalError::NoRow(_)) if printed.is_empty() => continue,
                Err(EvalError::Text { cell, .. }) if printed.is_empty() => {
                    if shown.trim() != cell {
                        let at = shown_path(&file.path, root);
                        report.findings.push(fail(format!(
                            "prints `{}`, the data say `{cell}` ({at}: `{formula}`)",
                            shown.trim()
                        )));
                    }
                    continue;
                }
                v => v.map_err(|e| e.to_string()),
            };
            compare(report, &printed, values, &fail, formula, &file.path, root);
        }
    }
}

/// The one row of `selector` (`[file.csv:] key=value, ...`, the file relative to `file`).
fn select_row(
    tables: &mut Tables,
    file: &Path,
    selector: &str,
) -> Result<(Rc<crate::data::Table>, usize), String> {
    let (path, filters) = match [".csv:", ".json:"]
        .iter()
        .find_map(|ext| selector.find(ext).map(|i| i + ext.len()))
    {
        Some(split) => (
            crate::data::normalise(
                &file
                    .parent()
                    .unwrap_or(Path::new("."))
                    .join(selector[..split - 1].trim()),
            ),
            &selector[split..],
        ),
        None => (file.to_path_buf(), selector),
    };
    let table = tables.get(&path)?;
    let filters = expr::parse_filters(filters)?;
    let scope = Scope {
        tables,
        file: path.clone(),
        row: None,
    };
    let rows = scope
        .matching(&table, &filters)
        .map_err(|e| e.to_string())?;
    match rows.as_slice() {
        [row] => Ok((table, *row)),
        rows => Err(format!(
            "{} rows of {} match, not one",
            rows.len(),
            path.display()
        )),
    }
}

fn evaluate(scope: &mut Scope, formula: &str) -> Result<Vec<f64>, EvalError> {
    let list = expr::parse(formula).map_err(EvalError::Other)?;
    let mut values = Vec::new();
    for e in &list {
        match scope.eval(e)?.as_slice() {
            [v] => values.push(*v),
            many => {
                return Err(EvalError::Other(format!(
                    "`{formula}` gives {} values where one is printed: reduce with min, max, ...",
                    many.len()
                )));
            }
        }
    }
    Ok(values)
}

fn compare(
    report: &mut Report,
    printed: &[Printed],
    values: Result<Vec<f64>, String>,
    fail: &dyn Fn(String) -> String,
    formula: &str,
    file: &Path,
    root: &Path,
) {
    let values = match values {
        Ok(v) => v,
        Err(e) => {
            let prefix = format!("{}/", root.display());
            return report.findings.push(fail(e.replace(&prefix, "")));
        }
    };
    if printed.len() != values.len() {
        return report.findings.push(fail(format!(
            "prints {} number(s), `{formula}` gives {}",
            printed.len(),
            values.len()
        )));
    }
    for (p, &v) in printed.iter().zip(&values) {
        if text::agrees(p, v) {
            continue;
        }
        report.findings.push(fail(format!(
            "prints {}, the data give {} ({}: `{formula}`)",
            p.printed,
            significant(v),
            shown_path(file, root)
        )));
        if let Some(fixed) = text::reprint(p, v) {
            report.edits.push((p.span.clone(), fixed));
        }
    }
}

/// The numbers printed in `range`, outside code marks.
fn printed_in(page: &Page, range: Range<usize>) -> Vec<Printed> {
    text::numbers(&page.text[range.clone()])
        .into_iter()
        .filter(|p| !page.in_code(range.start + p.span.start))
        .map(|mut p| {
            p.span = range.start + p.span.start..range.start + p.span.end;
            p
        })
        .collect()
}

/// A figure's data folder, or one above it under `docs/bench/`, holds the command that
/// made it (`run*.sh` or `command.txt`): one click to the data, one command to remake it.
fn command_missing(file: &Path, root: &Path) -> Option<String> {
    let stop = root.join("docs");
    let mut dir = file.parent();
    while let Some(d) = dir {
        if d == stop || !d.starts_with(&stop) {
            break;
        }
        let has = std::fs::read_dir(d)
            .into_iter()
            .flatten()
            .flatten()
            .any(|e| {
                let n = e.file_name().to_string_lossy().to_string();
                n == "command.txt" || (n.starts_with("run") && n.ends_with(".sh"))
            });
        if has {
            return None;
        }
        dir = d.parent();
    }
    Some(format!(
        "`{}` has no command.txt or run*.sh beside it or above it: say how it was made",
        shown_path(file, root)
    ))
}

fn shown_path(file: &Path, root: &Path) -> String {
    file.strip_prefix(root)
        .unwrap_or(file)
        .display()
        .to_string()
}

fn significant(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) {
        format!("{v:.4e}")
    } else {
        format!("{:.6}", v)
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

fn context(text: &str, span: Range<usize>) -> String {
    let end = text[span.end..]
        .char_indices()
        .nth(12)
        .map_or(text.len(), |(i, _)| span.end + i);
    text[span.start..end].replace('\n', " ")
}
