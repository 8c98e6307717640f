//! The exchange structure of ISO 10303-21 (a STEP file): the header and data sections as
//! entity instances `#id = NAME(...)` (simple) or `#id = (A(...) B(...))` (complex), with their
//! parameters as written. Reals are read as the exact rationals their decimals denote;
//! nothing is interpreted here beyond the syntax.

use crate::number::{parse_exact, Rational};
use std::collections::BTreeMap;

/// One parameter of an entity instance.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Param {
    /// An integer (no decimal point).
    Integer(i64),
    /// A real, exact.
    Real(Rational),
    /// A string, its quotes removed and `''` read as `'` (other escapes kept as written).
    Str(String),
    /// An enumeration or logical value, without its dots (`T`, `F`, `U`, `PCURVE_S1`).
    Enum(String),
    /// A reference to an instance, `#id`.
    Ref(u64),
    /// `$`: not given.
    Unset,
    /// `*`: derived.
    Derived,
    /// A list `( ... )`.
    List(Vec<Param>),
    /// A typed parameter `NAME( ... )`, such as `LENGTH_MEASURE(1.)`.
    Typed(String, Vec<Param>),
    /// A binary `"..."` (kept as written).
    Binary(String),
}

/// One part of an instance: an entity name and its parameters.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Record {
    /// The entity name, upper case as written.
    pub(crate) name: String,
    /// Its parameters.
    pub(crate) params: Vec<Param>,
}

/// An entity instance of the data section.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Instance {
    /// The line its `#id` is on (1-based).
    pub(crate) line: usize,
    /// Its records: one for a simple instance, several (in the file's order) for a complex one.
    pub(crate) records: Vec<Record>,
    /// Whether it was written as a complex instance `( ... )`.
    pub(crate) complex: bool,
}

impl Instance {
    /// The record named `name`, if the instance has one.
    pub(crate) fn record(&self, name: &str) -> Option<&Record> {
        self.records.iter().find(|r| r.name == name)
    }

    /// A name for messages: the simple entity's name, or the complex one's names joined by `+`.
    pub(crate) fn kind(&self) -> String {
        self.records
            .iter()
            .map(|r| r.name.as_str())
            .collect::<Vec<_>>()
            .join("+")
    }
}

/// A syntax error: the line and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SyntaxError {
    pub(crate) line: usize,
    pub(crate) message: String,
}

/// The data of a STEP file.
#[derive(Debug, Default)]
pub(crate) struct Exchange {
    /// The header's `FILE_SCHEMA` names.
    pub(crate) schemas: Vec<String>,
    /// The instances of the data section(s), by id.
    pub(crate) instances: BTreeMap<u64, Instance>,
}

/// How deep lists may nest (a corrupt file could otherwise recurse without end).
const MAX_NESTING: usize = 64;

/// The most instances read from one file.
const MAX_INSTANCES: usize = 20_000_000;

struct Lexer<'a> {
    s: &'a [u8],
    i: usize,
    line: usize,
}

impl<'a> Lexer<'a> {
    fn err<T>(&self, message: impl Into<String>) -> Result<T, SyntaxError> {
        Err(SyntaxError {
            line: self.line,
            message: message.into(),
        })
    }

    /// Skips white space and comments.
    fn skip(&mut self) -> Result<(), SyntaxError> {
        loop {
            match self.s.get(self.i) {
                Some(b'\n') => {
                    self.line += 1;
                    self.i += 1;
                }
                Some(c) if c.is_ascii_whitespace() => self.i += 1,
                Some(b'/') if self.s.get(self.i + 1) == Some(&b'*') => {
                    let start = self.line;
                    self.i += 2;
                    loop {
                        match self.s.get(self.i) {
                            None => {
                                return Err(SyntaxError {
                                    line: start,
                                    message: "a comment /* is never closed".into(),
                                })
                            }
                            Some(b'*') if self.s.get(self.i + 1) == Some(&b'/') => {
                                self.i += 2;
                                break;
                            }
                            Some(b'\n') => {
                                self.line += 1;
                                self.i += 1;
                            }
                            Some(_) => self.i += 1,
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    fn peek(&mut self) -> Result<Option<u8>, SyntaxError> {
        self.skip()?;
        Ok(self.s.get(self.i).copied())
    }

    fn expect(&mut self, c: u8) -> Result<(), SyntaxError> {
        match self.peek()? {
            Some(x) if x == c => {
                self.i += 1;
                Ok(())
            }
            Some(x) => self.err(format!("expected '{}' but found '{}'", c as char, shown(x))),
            None => self.err(format!("expected '{}' but the file ends", c as char)),
        }
    }

    /// A keyword (entity or section name): letters, digits, `_`, `-`, an optional leading `!`.
    fn keyword(&mut self) -> Result<String, SyntaxError> {
        self.skip()?;
        let start = self.i;
        if self.s.get(self.i) == Some(&b'!') {
            self.i += 1;
        }
        while let Some(c) = self.s.get(self.i) {
            if c.is_ascii_alphanumeric() || *c == b'_' || *c == b'-' {
                self.i += 1;
            } else {
                break;
            }
        }
        if self.i == start {
            return match self.s.get(self.i) {
                Some(&c) => self.err(format!("expected a keyword but found '{}'", shown(c))),
                None => self.err("expected a keyword but the file ends"),
            };
        }
        Ok(String::from_utf8_lossy(&self.s[start..self.i]).to_ascii_uppercase())
    }

    /// An instance id after `#`.
    fn id(&mut self) -> Result<u64, SyntaxError> {
        self.expect(b'#')?;
        let start = self.i;
        while self.s.get(self.i).is_some_and(u8::is_ascii_digit) {
            self.i += 1;
        }
        let digits = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
        match digits.parse::<u64>() {
            Ok(n) => Ok(n),
            Err(_) if digits.is_empty() => self.err("'#' is not followed by an instance number"),
            Err(_) => self.err(format!(
                "the instance number #{} is too large",
                crate::io::shortened(digits)
            )),
        }
    }

    fn string(&mut self) -> Result<String, SyntaxError> {
        let start_line = self.line;
        self.i += 1;
        let mut out = Vec::new();
        loop {
            match self.s.get(self.i) {
                None => {
                    return Err(SyntaxError {
                        line: start_line,
                        message: "a string is never closed (a missing ')".into(),
                    })
                }
                Some(b'\'') if self.s.get(self.i + 1) == Some(&b'\'') => {
                    out.push(b'\'');
                    self.i += 2;
                }
                Some(b'\'') => {
                    self.i += 1;
                    return Ok(String::from_utf8_lossy(&out).into_owned());
                }
                // The directive `\S\c` holds one character `c`, which may be a quote; `\\` is
                // a backslash. Both are kept as written.
                Some(b'\\') if self.s.get(self.i + 1) == Some(&b'\\') => {
                    out.extend_from_slice(b"\\\\");
                    self.i += 2;
                }
                Some(b'\\')
                    if self.s.get(self.i + 1) == Some(&b'S')
                        && self.s.get(self.i + 2) == Some(&b'\\')
                        && self.s.get(self.i + 3).is_some_and(|&c| c != b'\n') =>
                {
                    out.extend_from_slice(&self.s[self.i..self.i + 4]);
                    self.i += 4;
                }
                Some(&c) => {
                    if c == b'\n' {
                        self.line += 1;
                    }
                    out.push(c);
                    self.i += 1;
                }
            }
        }
    }

    fn number(&mut self) -> Result<Param, SyntaxError> {
        let start = self.i;
        if matches!(self.s.get(self.i), Some(b'+' | b'-')) {
            self.i += 1;
        }
        let mut real = false;
        while let Some(&c) = self.s.get(self.i) {
            match c {
                b'0'..=b'9' => self.i += 1,
                b'.' | b'E' | b'e' => {
                    real = true;
                    self.i += 1;
                    if matches!(c, b'E' | b'e') && matches!(self.s.get(self.i), Some(b'+' | b'-')) {
                        self.i += 1;
                    }
                }
                _ => break,
            }
        }
        let text = std::str::from_utf8(&self.s[start..self.i]).unwrap_or("");
        if !real {
            if let Ok(n) = text.parse::<i64>() {
                return Ok(Param::Integer(n));
            }
        }
        match parse_exact(text) {
            Ok(x) => Ok(Param::Real(x)),
            Err(e) => self.err(format!(
                "'{}' is not a number: {e}",
                crate::io::shortened(text)
            )),
        }
    }

    /// One parameter.
    fn param(&mut self, depth: usize) -> Result<Param, SyntaxError> {
        if depth > MAX_NESTING {
            return self.err(format!("lists nest deeper than {MAX_NESTING}"));
        }
        let Some(c) = self.peek()? else {
            return self.err("expected a parameter but the file ends");
        };
        match c {
            b'#' => self.id().map(Param::Ref),
            b'\'' => self.string().map(Param::Str),
            b'"' => {
                self.i += 1;
                let start = self.i;
                while self.s.get(self.i).is_some_and(|&b| b != b'"') {
                    self.i += 1;
                }
                if self.i >= self.s.len() {
                    return self.err("a binary \" is never closed");
                }
                let b = String::from_utf8_lossy(&self.s[start..self.i]).into_owned();
                self.i += 1;
                Ok(Param::Binary(b))
            }
            b'.' if self.s.get(self.i + 1).is_some_and(u8::is_ascii_alphabetic) => {
                self.i += 1;
                let start = self.i;
                while self
                    .s
                    .get(self.i)
                    .is_some_and(|&b| b.is_ascii_alphanumeric() || b == b'_')
                {
                    self.i += 1;
                }
                let e = String::from_utf8_lossy(&self.s[start..self.i]).to_ascii_uppercase();
                if self.s.get(self.i) != Some(&b'.') {
                    return self.err(format!("the enumeration .{e} is not closed by '.'"));
                }
                self.i += 1;
                Ok(Param::Enum(e))
            }
            b'$' => {
                self.i += 1;
                Ok(Param::Unset)
            }
            b'*' => {
                self.i += 1;
                Ok(Param::Derived)
            }
            b'(' => self.list(depth + 1).map(Param::List),
            b'+' | b'-' | b'.' | b'0'..=b'9' => self.number(),
            c if c.is_ascii_alphabetic() || c == b'!' => {
                let name = self.keyword()?;
                let args = self.list(depth + 1)?;
                Ok(Param::Typed(name, args))
            }
            c => self.err(format!("'{}' cannot start a parameter", shown(c))),
        }
    }

    /// A parenthesised list of parameters.
    fn list(&mut self, depth: usize) -> Result<Vec<Param>, SyntaxError> {
        self.expect(b'(')?;
        let mut out = Vec::new();
        if self.peek()? == Some(b')') {
            self.i += 1;
            return Ok(out);
        }
        loop {
            out.push(self.param(depth)?);
            match self.peek()? {
                Some(b',') => self.i += 1,
                Some(b')') => {
                    self.i += 1;
                    return Ok(out);
                }
                Some(c) => {
                    return self.err(format!(
                        "expected ',' or ')' after a parameter but found '{}'",
                        shown(c)
                    ))
                }
                None => return self.err("a parameter list is never closed (a missing ')')"),
            }
        }
    }

    fn record(&mut self) -> Result<Record, SyntaxError> {
        let name = self.keyword()?;
        let params = self.list(0)?;
        Ok(Record { name, params })
    }
}

/// A byte as it may be shown in a message.
fn shown(c: u8) -> String {
    if c.is_ascii_graphic() {
        (c as char).to_string()
    } else {
        format!("\\x{c:02x}")
    }
}

/// Reads the exchange structure.
pub(crate) fn parse(bytes: &[u8]) -> Result<Exchange, SyntaxError> {
    let mut lx = Lexer {
        s: bytes,
        i: 0,
        line: 1,
    };
    let magic = lx.keyword()?;
    if magic != "ISO-10303-21" {
        return lx.err(format!(
            "a STEP file starts with ISO-10303-21; this one starts with {}",
            crate::io::shortened(&magic)
        ));
    }
    lx.expect(b';')?;
    let mut ex = Exchange::default();
    let mut data_sections = 0;
    loop {
        if lx.peek()?.is_none() {
            return lx.err(if data_sections == 0 {
                "the file ends before its DATA section (truncated?)"
            } else {
                "the file ends without END-ISO-10303-21; (truncated?)"
            });
        }
        let section = lx.keyword()?;
        match section.as_str() {
            "HEADER" => {
                lx.expect(b';')?;
                loop {
                    let k = lx.keyword()?;
                    if k == "ENDSEC" {
                        lx.expect(b';')?;
                        break;
                    }
                    let params = lx.list(0)?;
                    lx.expect(b';')?;
                    if k == "FILE_SCHEMA" {
                        if let Some(Param::List(l)) = params.first() {
                            ex.schemas.extend(l.iter().filter_map(|p| match p {
                                Param::Str(s) => Some(s.clone()),
                                _ => None,
                            }));
                        }
                    }
                }
            }
            "DATA" => {
                data_sections += 1;
                if lx.peek()? == Some(b'(') {
                    // A named data section (edition 3): its parameters are not used.
                    lx.list(0)?;
                }
                lx.expect(b';')?;
                loop {
                    match lx.peek()? {
                        Some(b'#') => {}
                        None => {
                            return lx.err("the file ends inside its DATA section (truncated?)")
                        }
                        _ => {
                            let k = lx.keyword()?;
                            if k != "ENDSEC" {
                                return lx.err(format!(
                                    "expected an instance '#n = ...;' or ENDSEC in the data section but found {}",
                                    crate::io::shortened(&k)
                                ));
                            }
                            lx.expect(b';')?;
                            break;
                        }
                    }
                    let line = lx.line;
                    let id = lx.id()?;
                    lx.expect(b'=')?;
                    let (records, complex) = if lx.peek()? == Some(b'(') {
                        lx.i += 1;
                        let mut records = Vec::new();
                        while lx.peek()? != Some(b')') {
                            if lx.peek()?.is_none() {
                                return lx.err(format!("instance #{id} is never closed"));
                            }
                            records.push(lx.record()?);
                        }
                        lx.i += 1;
                        if records.is_empty() {
                            return lx.err(format!("instance #{id} is an empty complex instance"));
                        }
                        (records, true)
                    } else {
                        (vec![lx.record()?], false)
                    };
                    lx.expect(b';')?;
                    if ex.instances.len() >= MAX_INSTANCES {
                        return lx.err(format!("more than {MAX_INSTANCES} instances"));
                    }
                    let inst = Instance {
                        line,
                        records,
                        complex,
                    };
                    if let Some(first) = ex.instances.insert(id, inst) {
                        return Err(SyntaxError {
                            line,
                            message: format!(
                                "instance #{id} is defined twice (first on line {})",
                                first.line
                            ),
                        });
                    }
                }
            }
            "END-ISO-10303-21" => {
                lx.expect(b';')?;
                break;
            }
            other => {
                return lx.err(format!(
                    "expected HEADER, DATA or END-ISO-10303-21 but found {}",
                    crate::io::shortened(other)
                ))
            }
        }
    }
    if data_sections == 0 {
        return lx.err("the file has no DATA section");
    }
    Ok(ex)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(data: &str) -> String {
        format!("ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n")
    }

    #[test]
    fn simple_and_complex_instances_with_exact_numbers() {
        let t = file(
            "#1 = CARTESIAN_POINT('a''b\\S\\'c',(1.96709821454E+003,-0.,.5));\n/* note */ #2=( A(1,$,*) B(.T.,(#1,#3),LENGTH_MEASURE(2.5E-1)) );\n#3 = X(\"0F\");",
        );
        let ex = parse(t.as_bytes()).unwrap();
        assert_eq!(ex.schemas, vec!["AUTOMOTIVE_DESIGN".to_string()]);
        let p = &ex.instances[&1];
        assert_eq!(p.line, 6);
        assert_eq!(p.records[0].params[0], Param::Str("a'b\\S\\'c".into()));
        let Param::List(c) = &p.records[0].params[1] else {
            panic!("a list")
        };
        assert_eq!(
            c[0],
            Param::Real(Rational::from((196709821454i64, 100000000)))
        );
        assert_eq!(c[1], Param::Real(Rational::from(0)));
        assert_eq!(c[2], Param::Real(Rational::from((1, 2))));
        let q = &ex.instances[&2];
        assert!(q.complex);
        assert_eq!(q.kind(), "A+B");
        assert_eq!(
            q.record("A").unwrap().params,
            vec![Param::Integer(1), Param::Unset, Param::Derived]
        );
        assert_eq!(
            q.record("B").unwrap().params[2],
            Param::Typed(
                "LENGTH_MEASURE".into(),
                vec![Param::Real(Rational::from((1, 4)))]
            )
        );
        assert_eq!(
            ex.instances[&3].records[0].params[0],
            Param::Binary("0F".into())
        );
    }

    #[test]
    fn syntax_errors_name_their_line() {
        let cases = [
            ("#1 = A(1,2;", 6, "expected ',' or ')'"),
            ("#1 = A(1);\n#1 = B(2);", 7, "defined twice"),
            ("#1 = A('x);", 6, "never closed"),
            ("#1 = A(1.2.3);", 6, "not a number"),
            ("#1 = A(.T);", 6, "not closed by '.'"),
            ("#x = A(1);", 6, "not followed by an instance number"),
            ("#1 = A(1); FOO;", 6, "expected an instance"),
        ];
        for (data, line, what) in cases {
            let e = parse(file(data).as_bytes()).unwrap_err();
            assert_eq!(e.line, line, "{data}: {e:?}");
            assert!(e.message.contains(what), "{data}: {}", e.message);
        }
        let e = parse(b"ISO-10303-21;\nHEADER;\nENDSEC;\nEND-ISO-10303-21;").unwrap_err();
        assert!(e.message.contains("no DATA"), "{}", e.message);
        let e = parse(b"HELLO;").unwrap_err();
        assert!(
            e.message.contains("starts with ISO-10303-21"),
            "{}",
            e.message
        );
        let deep = format!("#1 = A({}1{});", "(".repeat(100), ")".repeat(100));
        let e = parse(file(&deep).as_bytes()).unwrap_err();
        assert!(e.message.contains("nest deeper"), "{}", e.message);
    }
}
