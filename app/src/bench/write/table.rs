//! A CSV table as every bench file writes it: cells escaped where they hold a comma, a
//! quote or a line break, numbers as Rust prints them, none as an empty cell.

use std::path::Path;

use anyhow::Context;

/// A CSV table under construction.
pub struct Table {
    text: String,
}

impl Table {
    pub fn new(header: &[&str]) -> Table {
        let mut t = Table {
            text: String::new(),
        };
        t.row(header.iter().map(|s| s.to_string()));
        t
    }

    pub fn row(&mut self, cells: impl IntoIterator<Item = String>) {
        let cells: Vec<String> = cells.into_iter().map(|c| escape(&c)).collect();
        self.text.push_str(&cells.join(","));
        self.text.push('\n');
    }

    pub fn write(&self, path: &Path) -> anyhow::Result<()> {
        std::fs::write(path, &self.text)
            .with_context(|| format!("{}: cannot write", path.display()))
    }
}

fn escape(cell: &str) -> String {
    if cell.contains([',', '"', '\n']) {
        format!("\"{}\"", cell.replace('"', "\"\""))
    } else {
        cell.to_string()
    }
}

/// A number, or empty when there is none.
pub fn num(x: Option<f64>) -> String {
    x.map(|v| format!("{v}")).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_csv_cells_are_escaped() {
        let mut t = Table::new(&["a", "b"]);
        t.row(["x,y".to_string(), "say \"hi\"".to_string()]);
        assert_eq!(t.text, "a,b\n\"x,y\",\"say \"\"hi\"\"\"\n");
        assert_eq!(num(None), "");
        assert_eq!(num(Some(0.5)), "0.5");
    }
}
