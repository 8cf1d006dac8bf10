//! The parser's cursor over the deck's tokens: what every record reader
//! needs (keywords, names, numbers, choices, fields, record ends), each
//! raising a [`DeckError`] at the offending token.

use super::lex::{is_integer, is_number, tokenize, Tok, Token};
use super::DeckError;
use crate::types::{Pos, STRINGLENGTH};

/// A number read from the deck, with its text as written (echoed by range
/// errors).
#[derive(Clone, Debug)]
pub(super) struct Num {
    pub value: f64,
    pub pos: Pos,
    pub text: String,
}

/// The cursor. `record` and `name` say which record is being read, for the
/// errors.
pub(super) struct Parser<'a> {
    toks: Vec<Token>,
    i: usize,
    file: &'a str,
    /// The record's keyword as DECK.md spells it, or `deck` between records.
    pub record: &'static str,
    /// The record's name, once it has been read and found meaningful.
    pub name: Option<String>,
}

/// How a token is shown in "found …".
fn found(tok: &Tok) -> String {
    match tok {
        Tok::Word(w) => format!("'{w}'"),
        Tok::Eol => "end of line".to_string(),
        Tok::Eof | Tok::Bad(_) => "end of file".to_string(),
    }
}

impl<'a> Parser<'a> {
    pub fn new(source: &str, file: &'a str) -> Self {
        Parser {
            toks: tokenize(source),
            i: 0,
            file,
            record: "deck",
            name: None,
        }
    }

    /// Starts a new record: no name yet.
    pub fn begin(&mut self, record: &'static str) {
        self.record = record;
        self.name = None;
    }

    /// An error at `pos` in the current record.
    pub fn error_at(&self, pos: Pos, message: impl Into<String>) -> DeckError {
        DeckError {
            file: self.file.to_string(),
            line: pos.line,
            column: pos.column,
            record: self.record.to_string(),
            name: self.name.clone(),
            message: message.into(),
        }
    }

    /// The next token; a lexical error surfaces here, in the current record.
    pub fn peek(&self) -> Result<&Token, DeckError> {
        // `tokenize` always ends the list with Eof or Bad, and `advance`
        // never passes them, so the index is in range.
        let t = &self.toks[self.i.min(self.toks.len() - 1)];
        match &t.tok {
            Tok::Bad(msg) => Err(self.error_at(t.pos, msg.clone())),
            _ => Ok(t),
        }
    }

    /// Where the next token stands (also for a lexical error).
    pub fn pos(&self) -> Pos {
        self.toks[self.i.min(self.toks.len() - 1)].pos
    }

    fn advance(&mut self) {
        if matches!(self.toks.get(self.i).map(|t| &t.tok), Some(Tok::Word(_) | Tok::Eol)) {
            self.i += 1;
        }
    }

    /// An error at the next token: "expected WHAT, found TOKEN".
    pub fn expected(&self, what: &str) -> DeckError {
        match self.peek() {
            Ok(t) => self.error_at(t.pos, format!("expected {what}, found {}", found(&t.tok))),
            Err(e) => e,
        }
    }

    /// The next word, if the next token is one (not consumed).
    pub fn peek_word(&self) -> Result<Option<(String, Pos)>, DeckError> {
        let t = self.peek()?;
        Ok(match &t.tok {
            Tok::Word(w) => Some((w.clone(), t.pos)),
            _ => None,
        })
    }

    /// Whether the record's line ends here.
    pub fn at_eol(&self) -> Result<bool, DeckError> {
        Ok(matches!(self.peek()?.tok, Tok::Eol | Tok::Eof))
    }

    /// Whether the deck ends here.
    pub fn at_eof(&self) -> Result<bool, DeckError> {
        Ok(matches!(self.peek()?.tok, Tok::Eof))
    }

    /// Skips empty lines (and lines holding only comments).
    pub fn skip_blank_lines(&mut self) -> Result<(), DeckError> {
        while matches!(self.peek()?.tok, Tok::Eol) {
            self.advance();
        }
        Ok(())
    }

    /// The end of a record's line: the line end (consumed) or the end of
    /// the deck.
    pub fn end_of_line(&mut self) -> Result<(), DeckError> {
        match self.peek()?.tok {
            Tok::Eol => {
                self.advance();
                Ok(())
            }
            Tok::Eof => Ok(()),
            _ => Err(self.expected("end of line")),
        }
    }

    /// A word, whatever it is.
    pub fn word(&mut self, what: &str) -> Result<(String, Pos), DeckError> {
        match self.peek_word()? {
            Some(w) => {
                self.advance();
                Ok(w)
            }
            None => Err(self.expected(what)),
        }
    }

    /// The keyword `kw` (any case).
    pub fn keyword(&mut self, kw: &str) -> Result<Pos, DeckError> {
        match self.peek_word()? {
            Some((w, pos)) if w.eq_ignore_ascii_case(kw) => {
                self.advance();
                Ok(pos)
            }
            _ => Err(self.expected(&format!("'{kw}'"))),
        }
    }

    /// One of the keywords of `options` (any case), as its value.
    pub fn choice<T: Copy>(&mut self, what: &str, options: &[(&str, T)]) -> Result<(T, Pos), DeckError> {
        if let Some((w, pos)) = self.peek_word()? {
            if let Some((_, v)) = options.iter().find(|(k, _)| w.eq_ignore_ascii_case(k)) {
                self.advance();
                return Ok((*v, pos));
            }
        }
        let names: Vec<&str> = options.iter().map(|(k, _)| *k).collect();
        Err(self.expected(&format!("{what} ({})", names.join(", "))))
    }

    /// A name: 1–10 characters of `[A-Za-z0-9_]`, not a number. `what`
    /// says whose name ("an object name").
    pub fn name(&mut self, what: &str) -> Result<(String, Pos), DeckError> {
        let Some((w, pos)) = self.peek_word()? else {
            return Err(self.expected(what));
        };
        if is_number(&w) {
            return Err(self.error_at(pos, format!("expected {what}, found the number '{w}'")));
        }
        if !w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(self.error_at(pos, format!("expected {what} (letters, digits and '_'), found '{w}'")));
        }
        if w.len() > STRINGLENGTH {
            return Err(self.error_at(pos, format!("the name '{w}' is longer than {STRINGLENGTH} characters")));
        }
        self.advance();
        Ok((w, pos))
    }

    /// A number; `what` places it in the message ("after 'radius'",
    /// "for X").
    pub fn number(&mut self, what: &str) -> Result<Num, DeckError> {
        if let Some((w, pos)) = self.peek_word()? {
            if is_number(&w) {
                return match w.parse::<f64>() {
                    Ok(value) if value.is_finite() => {
                        self.advance();
                        Ok(Num { value, pos, text: w })
                    }
                    _ => Err(self.error_at(pos, format!("the number '{w}' is out of range"))),
                };
            }
        }
        Err(self.expected(&format!("a number {what}")))
    }

    /// A number that must meet `ok`, described by `range` ("> 0",
    /// "in 0..1").
    pub fn number_where(&mut self, what: &str, range: &str, ok: impl Fn(f64) -> bool) -> Result<Num, DeckError> {
        let n = self.number(what)?;
        if ok(n.value) {
            Ok(n)
        } else {
            Err(self.error_at(n.pos, format!("expected a number {range} {what}, found '{}'", n.text)))
        }
    }

    /// A number > 0.
    pub fn positive(&mut self, what: &str) -> Result<Num, DeckError> {
        self.number_where(what, "> 0", |v| v > 0.0)
    }

    /// A number in 0..=1.
    pub fn unit(&mut self, what: &str) -> Result<Num, DeckError> {
        self.number_where(what, "in 0..1", |v| (0.0..=1.0).contains(&v))
    }

    /// Three numbers.
    pub fn vec3(&mut self, what: &str) -> Result<glam::DVec3, DeckError> {
        let x = self.number(what)?.value;
        let y = self.number(what)?.value;
        let z = self.number(what)?.value;
        Ok(glam::DVec3::new(x, y, z))
    }

    /// An integer in `lo..=hi`.
    pub fn integer(&mut self, what: &str, lo: i64, hi: i64) -> Result<(i64, Pos), DeckError> {
        if let Some((w, pos)) = self.peek_word()? {
            if is_integer(&w) {
                return match w.parse::<i64>() {
                    Ok(v) if (lo..=hi).contains(&v) => {
                        self.advance();
                        Ok((v, pos))
                    }
                    _ => Err(self.error_at(pos, format!("expected an integer in {lo}..{hi} {what}, found '{w}'"))),
                };
            }
        }
        Err(self.expected(&format!("an integer {what}")))
    }

    /// The next optional field of a record: `None` at the end of the line;
    /// otherwise one of `allowed` (any case), consumed. A field given twice
    /// or a word that is no field of the record is an error.
    pub fn field(
        &mut self,
        allowed: &[&'static str],
        seen: &mut Vec<&'static str>,
    ) -> Result<Option<(&'static str, Pos)>, DeckError> {
        if self.at_eol()? {
            return Ok(None);
        }
        if let Some((w, pos)) = self.peek_word()? {
            if let Some(&f) = allowed.iter().find(|f| w.eq_ignore_ascii_case(f)) {
                if seen.contains(&f) {
                    return Err(self.error_at(pos, format!("the field '{f}' is given twice")));
                }
                seen.push(f);
                self.advance();
                return Ok(Some((f, pos)));
            }
        }
        let list: Vec<String> = allowed
            .iter()
            .filter(|f| !seen.contains(f))
            .map(|f| format!("'{f}'"))
            .collect();
        if list.is_empty() {
            Err(self.expected("end of line"))
        } else {
            Err(self.expected(&format!("end of line or {}", list.join(", "))))
        }
    }
}
