//! Reading back the CSV files the bench writes (write/table.rs): RFC 4180, so a cell
//! quoted for its comma, quote or line break comes back whole. A configuration's name can
//! hold a comma (a preset's file name, `--set` values inside brackets), and a line split on
//! commas would shift every later column of its row.

/// The records of `text`, each a list of cells; a doubled quote inside quotes is a quote.
pub fn records(text: &str) -> Vec<Vec<String>> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bench_csv_records_keep_quoted_commas_quotes_and_line_breaks() {
        let text = "config,ms\n\"ris[a=1,b=2]\",3\n\"say \"\"hi\"\"\",\"two\nlines\"\n1,\n";
        let r = records(text);
        assert_eq!(r.len(), 5 - 1);
        assert_eq!(r[1], vec!["ris[a=1,b=2]", "3"]);
        assert_eq!(r[2], vec!["say \"hi\"", "two\nlines"]);
        assert_eq!(r[3], vec!["1", ""]);
        // No final line break: the last record still counts.
        assert_eq!(records("a,b\n1,2"), vec![vec!["a", "b"], vec!["1", "2"]]);
    }
}
