//! The data a figure is read from: a CSV file (a header, then rows) or a JSON file (an
//! array of objects, or one object), both seen as a table of text cells. JSON objects are
//! flattened into dotted column names (`figures.frame_luma_rmse.mean`, `size.0`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// One data file as a table of text cells.
pub struct Table {
    pub path: PathBuf,
    pub columns: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    pub fn load(path: &Path) -> Result<Table, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("{}: cannot read ({e})", path.display()))?;
        let name = path.to_string_lossy();
        if name.ends_with(".json") {
            let value: serde_json::Value = serde_json::from_str(&text)
                .map_err(|e| format!("{}: not JSON ({e})", path.display()))?;
            Ok(Table::from_json(path, &value))
        } else if name.ends_with(".csv") {
            Table::from_csv(path, &text)
        } else {
            Err(format!(
                "{}: a figure's data is a .csv or .json file",
                path.display()
            ))
        }
    }

    fn from_csv(path: &Path, text: &str) -> Result<Table, String> {
        let mut records = parse_csv(text).into_iter();
        let columns = records
            .next()
            .ok_or_else(|| format!("{}: empty", path.display()))?;
        let rows: Vec<Vec<String>> = records
            .filter(|r| r.iter().any(|c| !c.is_empty()))
            .collect();
        if let Some((i, r)) = rows
            .iter()
            .enumerate()
            .find(|(_, r)| r.len() != columns.len())
        {
            return Err(format!(
                "{}: row {} has {} cells, the header {}",
                path.display(),
                i + 2,
                r.len(),
                columns.len()
            ));
        }
        Ok(Table {
            path: path.to_path_buf(),
            columns,
            rows,
        })
    }

    fn from_json(path: &Path, value: &serde_json::Value) -> Table {
        let objects: Vec<&serde_json::Value> = match value {
            serde_json::Value::Array(items) => items.iter().collect(),
            other => vec![other],
        };
        let flat: Vec<HashMap<String, String>> = objects
            .iter()
            .map(|o| {
                let mut cells = HashMap::new();
                flatten("", o, &mut cells);
                cells
            })
            .collect();
        let mut columns: Vec<String> = Vec::new();
        for cells in &flat {
            let mut names: Vec<&String> = cells.keys().collect();
            names.sort();
            for n in names {
                if !columns.contains(n) {
                    columns.push(n.clone());
                }
            }
        }
        let rows = flat
            .iter()
            .map(|cells| {
                columns
                    .iter()
                    .map(|c| cells.get(c).cloned().unwrap_or_default())
                    .collect()
            })
            .collect();
        Table {
            path: path.to_path_buf(),
            columns,
            rows,
        }
    }

    pub fn column(&self, name: &str) -> Result<usize, String> {
        self.columns.iter().position(|c| c == name).ok_or_else(|| {
            format!(
                "{} has no column `{name}` (it has: {})",
                self.path.display(),
                self.columns.join(", ")
            )
        })
    }
}

fn flatten(prefix: &str, value: &serde_json::Value, out: &mut HashMap<String, String>) {
    let key = |k: &str| {
        if prefix.is_empty() {
            k.to_string()
        } else {
            format!("{prefix}.{k}")
        }
    };
    match value {
        serde_json::Value::Object(map) => {
            for (k, v) in map {
                flatten(&key(k), v, out);
            }
        }
        serde_json::Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                flatten(&key(&i.to_string()), v, out);
            }
        }
        serde_json::Value::String(s) => _ = out.insert(prefix.to_string(), s.clone()),
        serde_json::Value::Null => _ = out.insert(prefix.to_string(), String::new()),
        other => _ = out.insert(prefix.to_string(), other.to_string()),
    }
}

/// RFC 4180: comma-separated, double quotes around cells that hold commas, quotes or
/// line breaks, a doubled quote for a quote.
fn parse_csv(text: &str) -> Vec<Vec<String>> {
    let (mut records, mut record, mut cell) = (Vec::new(), Vec::new(), String::new());
    let (mut quoted, mut chars) = (false, text.chars().peekable());
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                cell.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => cell.push(c),
            (false, '"') => quoted = true,
            (false, ',') => record.push(std::mem::take(&mut cell)),
            (false, '\r') => {}
            (false, '\n') => {
                record.push(std::mem::take(&mut cell));
                records.push(std::mem::take(&mut record));
            }
            (false, c) => cell.push(c),
        }
    }
    if !cell.is_empty() || !record.is_empty() {
        record.push(cell);
        records.push(record);
    }
    records
}

/// `a/b/../c` as `a/c`, without touching the disk (a page's link can climb out of its
/// folder and back down).
pub fn normalise(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            std::path::Component::ParentDir => _ = out.pop(),
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

/// The loaded files of one check, each read once.
#[derive(Default)]
pub struct Tables {
    loaded: HashMap<PathBuf, Result<std::rc::Rc<Table>, String>>,
}

impl Tables {
    pub fn get(&mut self, path: &Path) -> Result<std::rc::Rc<Table>, String> {
        let path = normalise(path);
        self.loaded
            .entry(path.clone())
            .or_insert_with(|| Table::load(&path).map(std::rc::Rc::new))
            .clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_csv_cells_keep_quoted_commas_and_quotes() {
        let records = parse_csv("a,b\n\"x, y\",\"say \"\"hi\"\"\"\n1,\n");
        assert_eq!(records[1], vec!["x, y", "say \"hi\""]);
        assert_eq!(records[2], vec!["1", ""]);
    }

    #[test]
    fn figures_json_objects_flatten_to_dotted_columns() {
        let value: serde_json::Value =
            serde_json::from_str(r#"[{"a": {"b": 1.5}, "size": [3, 4], "n": null}]"#).unwrap();
        let t = Table::from_json(Path::new("x.json"), &value);
        let cell = |name: &str| t.rows[0][t.column(name).unwrap()].clone();
        assert_eq!(cell("a.b"), "1.5");
        assert_eq!(cell("size.1"), "4");
        assert_eq!(cell("n"), "");
    }
}
