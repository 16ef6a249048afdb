//! Formulas read from text into `Expr` (the grammar is the parent module's).

use super::{Expr, Filter, Ref};

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
