//! A line-aware scanner of whitespace- or comma-separated numbers, shared by the text readers.

use super::{Place, ReadError};
use crate::number::{parse_exact, Rational};

/// Tokens with the 1-based line each came from.
pub(super) struct Tokens<'a> {
    name: &'a str,
    tokens: Vec<(usize, &'a str)>,
    pos: usize,
    last_line: usize,
}

impl<'a> Tokens<'a> {
    /// Splits the text at whitespace and at `extra` separators.
    pub(super) fn new(name: &'a str, text: &'a str, extra: &[char]) -> Tokens<'a> {
        let mut tokens = Vec::new();
        for (i, line) in text.lines().enumerate() {
            for t in line.split(|c: char| c.is_whitespace() || extra.contains(&c)) {
                if !t.is_empty() {
                    tokens.push((i + 1, t));
                }
            }
        }
        let last_line = text.lines().count().max(1);
        Tokens {
            name,
            tokens,
            pos: 0,
            last_line,
        }
    }

    /// Whether every token has been read.
    pub(super) fn at_end(&self) -> bool {
        self.pos >= self.tokens.len()
    }

    /// The line of the next token (or the last line, at the end).
    pub(super) fn line(&self) -> usize {
        self.tokens.get(self.pos).map_or(self.last_line, |t| t.0)
    }

    pub(super) fn error(&self, line: usize, message: impl Into<String>) -> ReadError {
        ReadError::new(self.name, Place::Line(line), message)
    }

    fn next(&mut self, what: &str) -> Result<(usize, &'a str), ReadError> {
        let t = self.tokens.get(self.pos).copied().ok_or_else(|| {
            self.error(
                self.last_line,
                format!("the file ends where {what} was expected (truncated?)"),
            )
        })?;
        self.pos += 1;
        Ok(t)
    }

    /// The next token as a count (a nonnegative integer at most `max`).
    pub(super) fn count(&mut self, what: &str, max: usize) -> Result<usize, ReadError> {
        let (line, t) = self.next(what)?;
        let n: usize = t.parse().map_err(|_| {
            self.error(
                line,
                format!("{what}: expected a whole number, found {t:?}"),
            )
        })?;
        if n > max {
            return Err(self.error(line, format!("{what}: {n} is more than the {max} allowed")));
        }
        Ok(n)
    }

    /// The next token as an exact number.
    pub(super) fn number(&mut self, what: &str) -> Result<Rational, ReadError> {
        let (line, t) = self.next(what)?;
        parse_exact(t).map_err(|e| self.error(line, format!("{what}: {e}")))
    }

    /// Fails if any token is left.
    pub(super) fn finish(&self, after: &str) -> Result<(), ReadError> {
        match self.tokens.get(self.pos) {
            None => Ok(()),
            Some((line, t)) => Err(self.error(*line, format!("unexpected {t:?} after {after}"))),
        }
    }
}
