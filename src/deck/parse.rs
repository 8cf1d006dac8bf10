//! The parser's cursor over the deck's tokens: what every record reader
//! needs (keywords, names, numbers, choices, fields, record ends), each
//! raising a [`DeckError`] at the offending token.

use super::lex::{is_integer, is_number, Bytes, Lexer, Tok, Token};
use super::DeckError;
use crate::scene::Pos;
use crate::types::STRINGLENGTH;

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
    lexer: Lexer<'a>,
    /// The next token.
    next: Token,
    /// The record's keyword as DECK.md spells it, or `deck` between records.
    pub record: &'static str,
    /// The record's name, once it has been read and found meaningful.
    pub name: Option<String>,
}

/// The largest magnitude of any real number in a deck: coordinates, sizes,
/// distances, angles (the port's extension; the thesis's scenes are a few
/// units across). Products and squares of such numbers stay far from
/// overflow, so the renderer computes every ray of a deck in range.
pub const MAX_MAGNITUDE: f64 = 1e7;

/// The smallest size (a radius, edge, length, height, distance, screen,
/// paint scale, refractive index): sizes lie in `MIN_SIZE..=MAX_MAGNITUDE`,
/// so their squares and ratios stay far from underflow.
pub const MIN_SIZE: f64 = 1e-7;

/// The nearest of `names` to `word` (case-insensitive edit distance, a
/// swap of two neighbours counting as one edit), if it is near enough to be
/// a slip: at most a third of its letters (one for a short name) and not
/// the whole word.
pub(super) fn nearest<'n>(word: &str, names: &[&'n str]) -> Option<&'n str> {
    let longest = names.iter().map(|n| n.chars().count()).max().unwrap_or(0);
    if word.chars().count() > 2 * longest + 1 {
        return None;
    }
    let w: Vec<char> = word.to_lowercase().chars().collect();
    let mut best: Option<(usize, &'n str)> = None;
    for &name in names {
        let n: Vec<char> = name.to_lowercase().chars().collect();
        let most = (n.len() / 3).max(1);
        // The distance is at least the difference of the lengths: a word
        // far longer than the name is no slip (and costs nothing to skip).
        if w.len() > n.len() + most {
            continue;
        }
        let d = edit_distance(&w, &n);
        let slip = d <= most && d < n.len().max(w.len());
        if slip && best.is_none_or(|(b, _)| d < b) {
            best = Some((d, name));
        }
    }
    best.map(|(_, name)| name)
}

/// ` — did you mean 'NAME'?` for the nearest of `names`, or nothing.
pub(super) fn did_you_mean(word: &str, names: &[&str]) -> String {
    nearest(word, names)
        .map(|n| format!(" — did you mean '{n}'?"))
        .unwrap_or_default()
}

/// The optimal string alignment distance: insertions, deletions,
/// substitutions and swaps of two neighbours, each one edit.
fn edit_distance(a: &[char], b: &[char]) -> usize {
    let w = b.len() + 1;
    let mut d = vec![0usize; (a.len() + 1) * w];
    for i in 0..=a.len() {
        for j in 0..=b.len() {
            d[i * w + j] = if i == 0 || j == 0 {
                i + j
            } else {
                let cost = usize::from(a[i - 1] != b[j - 1]);
                let mut v = (d[(i - 1) * w + j] + 1)
                    .min(d[i * w + j - 1] + 1)
                    .min(d[(i - 1) * w + j - 1] + cost);
                if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                    v = v.min(d[(i - 2) * w + j - 2] + 1);
                }
                v
            };
        }
    }
    d[a.len() * w + b.len()]
}

/// The most characters of a word an error echoes.
const SHOWN_CHARS: usize = 40;

/// The most characters of a path an error echoes: its last ones.
const SHOWN_PATH_CHARS: usize = 160;

/// A word as an error echoes it: quoted, control characters escaped (`\0`,
/// `\t`, `\x1B`), cut after [`SHOWN_CHARS`] characters with its length.
pub(super) fn shown(word: &str) -> String {
    quoted(word, SHOWN_CHARS)
}

/// A path as an error echoes it: as [`shown`], but past
/// [`SHOWN_PATH_CHARS`] its start is cut, not its end (the end is what
/// tells where it points).
pub(super) fn shown_path(path: &std::path::Path) -> String {
    let path = path.to_string_lossy();
    let n = path.chars().count();
    if n <= SHOWN_PATH_CHARS {
        return quoted(&path, SHOWN_PATH_CHARS);
    }
    // Its end is kept: a message stays under the fuzzer's 400 characters
    // with a file name as written beside it.
    let tail: String = path.chars().skip(n - SHOWN_PATH_CHARS).collect();
    format!("'…{} ({n} characters)", &quoted(&tail, SHOWN_PATH_CHARS)[1..])
}

/// `word` quoted, control characters escaped, cut after `most` characters.
fn quoted(word: &str, most: usize) -> String {
    let mut out = String::from("'");
    for c in word.chars().take(most) {
        match c {
            '\0' => out.push_str("\\0"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c.is_control() => out.push_str(&format!("\\x{:02X}", u32::from(c))),
            c => out.push(c),
        }
    }
    out.push('\'');
    let n = word.chars().count();
    if n > most {
        out = format!("{}…' ({n} characters)", &out[..out.len() - 1]);
    }
    out
}

/// How a token is shown in "found …".
fn found(tok: &Tok) -> String {
    match tok {
        Tok::Word(w) => shown(w),
        Tok::Eol => "end of line".to_string(),
        Tok::Eof | Tok::Bad(_) => "end of file".to_string(),
    }
}

impl<'a> Parser<'a> {
    /// The cursor over `source`, a deck named `file` in errors.
    pub fn new(source: &'a [u8], file: &str) -> Self {
        Parser::over(Bytes::Borrowed(source), file)
    }

    /// The cursor over `source`, borrowed or shared (an included file).
    pub fn over(source: Bytes<'a>, file: &str) -> Self {
        let mut lexer = Lexer::new(source, file.into());
        let next = lexer.next_token();
        Parser {
            lexer,
            next,
            record: "deck",
            name: None,
        }
    }

    /// Starts a new record: no name yet.
    pub fn begin(&mut self, record: &'static str) {
        self.record = record;
        self.name = None;
    }

    /// An error at `pos` (in the file `pos` names) in the current record;
    /// one that a nested comment before it explains is reported as that
    /// comment ([`Lexer::nested_comment`]).
    pub fn error_at(&self, pos: Pos, message: impl Into<String>) -> DeckError {
        let (pos, message) = self.lexer.nested_comment(pos.clone()).unwrap_or((pos, message.into()));
        DeckError::at(pos, self.record, self.name.clone(), message)
    }

    /// The next token; a lexical error surfaces here, in the current record.
    pub fn peek(&self) -> Result<&Token, DeckError> {
        let t = &self.next;
        match &t.tok {
            Tok::Bad(msg) => Err(self.error_at(t.pos.clone(), msg.clone())),
            _ => Ok(t),
        }
    }

    /// Where the next token stands (also for a lexical error).
    pub fn pos(&self) -> Pos {
        self.next.pos.clone()
    }

    /// Moves to the token after the next; the end of the deck and a lexical
    /// error stay.
    fn advance(&mut self) {
        if matches!(self.next.tok, Tok::Word(_) | Tok::Eol) {
            self.next = self.lexer.next_token();
        }
    }

    /// An error at the next token: "expected WHAT, found TOKEN".
    pub fn expected(&self, what: &str) -> DeckError {
        match self.peek() {
            Ok(t) => self.error_at(t.pos.clone(), format!("expected {what}, found {}", found(&t.tok))),
            Err(e) => e,
        }
    }

    /// [`Parser::expected`], followed by the nearest of `names` to the word
    /// found, if one is near.
    pub fn expected_near(&self, what: &str, names: &[&str]) -> DeckError {
        let mut e = self.expected(what);
        if let Ok(Some((w, _))) = self.peek_word() {
            e.message.push_str(&did_you_mean(&w, names));
        }
        e
    }

    /// The next word, if the next token is one (not consumed).
    pub fn peek_word(&self) -> Result<Option<(String, Pos)>, DeckError> {
        let t = self.peek()?;
        Ok(match &t.tok {
            Tok::Word(w) => Some((w.clone(), t.pos.clone())),
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

    /// ` — the field 'F' is given twice` when the next word is a field F of
    /// the record where its optional fields stand: the required fields are
    /// read by then (an optional one given twice is caught by
    /// [`Parser::field`] itself).
    fn given_twice(&self) -> Result<Option<String>, DeckError> {
        let word = self.peek_word()?.map(|(w, _)| w).unwrap_or_default();
        Ok(self
            .record_fields()
            .iter()
            .find(|f| word.eq_ignore_ascii_case(f))
            .map(|f| format!(" — the field '{f}' is given twice")))
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

    /// The keyword `kw` (any case). Another word gets "expected 'KW',
    /// found 'WORD'", and then where the field WORD belongs if it is one of
    /// the record's, or the nearest field if it looks like a slip.
    pub fn keyword(&mut self, kw: &'static str) -> Result<Pos, DeckError> {
        self.keyword_of(&[kw]).map(|(_, pos)| pos)
    }

    /// One of the keywords `kws` (any case), for a record of two forms
    /// (`motion NAME to …`, `motion NAME path …`): which, and where. Another
    /// word is an error as in [`Parser::keyword`] for the first of them
    /// ("expected 'to' or 'path', found …"), the nearest of them all and
    /// the record's fields suggested.
    pub fn keyword_of(&mut self, kws: &[&'static str]) -> Result<(&'static str, Pos), DeckError> {
        let what = kws.iter().map(|k| format!("'{k}'")).collect::<Vec<_>>().join(" or ");
        match self.peek_word()? {
            Some((w, pos)) => {
                if let Some(&kw) = kws.iter().find(|k| w.eq_ignore_ascii_case(k)) {
                    self.advance();
                    return Ok((kw, pos));
                }
                let mut e = self.expected(&what);
                e.message.push_str(&self.field_hint(kws, &w));
                Err(e)
            }
            None => Err(self.expected(&what)),
        }
    }

    /// The current record's fields in DECK.md's order ([`super::FIELDS`]).
    fn record_fields(&self) -> &'static [&'static str] {
        super::FIELDS
            .iter()
            .find(|(record, _)| *record == self.record)
            .map_or(&[], |(_, fields)| fields)
    }

    /// What follows "expected 'KW', found 'WORD'" in the current record
    /// (KW the first of `kws`): a field of the record out of its place
    /// (DECK.md's order, required fields first) is told which comes first,
    /// or that it was given already; another word gets the nearest of `kws`
    /// and the record's fields, `kws` first.
    fn field_hint(&self, kws: &[&str], word: &str) -> String {
        let kw = kws[0];
        let fields = self.record_fields();
        let place = |name: &str| fields.iter().position(|f| f.eq_ignore_ascii_case(name));
        match (place(kw), place(word)) {
            (Some(k), Some(f)) if f > k => format!(" — '{kw}' comes before '{}'", fields[f]),
            // The fields before `kw` are required ones, read already.
            (Some(_), Some(f)) => format!(" — the field '{}' is given twice", fields[f]),
            (None, Some(_)) => String::new(),
            (_, None) => {
                let names: Vec<&str> = kws
                    .iter()
                    .copied()
                    .chain(
                        fields
                            .iter()
                            .copied()
                            .filter(|f| !kws.iter().any(|k| f.eq_ignore_ascii_case(k))),
                    )
                    .collect();
                did_you_mean(word, &names)
            }
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
        Err(self.expected_near(&format!("{what} ({})", names.join(", ")), &names))
    }

    /// A name: 1–10 characters of `[A-Za-z0-9_]`, not a number. `what`
    /// says whose name ("an object name").
    pub fn name(&mut self, what: &str) -> Result<(String, Pos), DeckError> {
        let Some((w, pos)) = self.peek_word()? else {
            return Err(self.expected(what));
        };
        if is_number(&w) {
            return Err(self.error_at(pos, format!("expected {what}, found the number {}", shown(&w))));
        }
        if !w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(self.error_at(
                pos,
                format!("expected {what} (letters, digits and '_'), found {}", shown(&w)),
            ));
        }
        if w.len() > STRINGLENGTH {
            return Err(self.error_at(
                pos,
                format!("the name {} is longer than {STRINGLENGTH} characters", shown(&w)),
            ));
        }
        self.advance();
        Ok((w, pos))
    }

    /// A number that meets `ok`; `what` places it in the message ("after
    /// 'radius'", "for X"). A number past the deck's range, ±[`MAX_MAGNITUDE`]
    /// (or too large for a 64-bit real), is refused as outside `outer`, one
    /// in range that fails `ok` as outside `range`. The ranges are written
    /// only for an error (formatting them for every number was a tenth of
    /// reading a deck of many objects).
    fn number_in(
        &mut self,
        what: &str,
        outer: impl FnOnce() -> String,
        range: impl FnOnce() -> String,
        ok: impl Fn(f64) -> bool,
    ) -> Result<Num, DeckError> {
        if let Some((w, pos)) = self.peek_word()? {
            if is_number(&w) {
                // Rust parses every text of the number grammar; one too
                // large for a real gives infinity.
                let value = w.parse::<f64>().unwrap_or(f64::INFINITY);
                if value.abs() <= MAX_MAGNITUDE && ok(value) {
                    self.advance();
                    return Ok(Num { value, pos, text: w });
                }
                let range = if value.abs() <= MAX_MAGNITUDE { range() } else { outer() };
                return Err(self.error_at(pos, format!("expected a number {range} {what}, found {}", shown(&w))));
            }
        }
        Err(self.expected(&format!("a number {what}")))
    }

    /// A number in the deck's range, −[`MAX_MAGNITUDE`]..=[`MAX_MAGNITUDE`].
    pub fn number(&mut self, what: &str) -> Result<Num, DeckError> {
        self.number_in(what, deck_range, deck_range, |_| true)
    }

    /// A number in the deck's range that must also meet `ok`, described by
    /// `range` ("> 0", "in 0..1").
    pub fn number_where(&mut self, what: &str, range: &str, ok: impl Fn(f64) -> bool) -> Result<Num, DeckError> {
        self.number_in(what, deck_range, || range.to_string(), ok)
    }

    /// A size: a number in [`MIN_SIZE`]..=[`MAX_MAGNITUDE`].
    pub fn size(&mut self, what: &str) -> Result<Num, DeckError> {
        self.number_in(what, size_range, size_range, |v| v >= MIN_SIZE)
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
                    _ => Err(self.error_at(
                        pos,
                        format!("expected an integer in {lo}..{hi} {what}, found {}", shown(&w)),
                    )),
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
        let unseen: Vec<&str> = allowed.iter().copied().filter(|f| !seen.contains(f)).collect();
        let what = if list.is_empty() {
            "end of line".to_string()
        } else {
            format!("end of line or {}", list.join(", "))
        };
        if let Some(twice) = self.given_twice()? {
            let mut e = self.expected(&what);
            e.message.push_str(&twice);
            Err(e)
        } else if list.is_empty() {
            Err(self.expected(&what))
        } else {
            Err(self.expected_near(&what, &unseen))
        }
    }
}

/// The deck's range of numbers, as an error writes it.
fn deck_range() -> String {
    format!("in -{MAX_MAGNITUDE:e}..{MAX_MAGNITUDE:e}")
}

/// The range of sizes, as an error writes it.
fn size_range() -> String {
    format!("in {MIN_SIZE:e}..{MAX_MAGNITUDE:e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance(a: &str, b: &str) -> usize {
        let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
        edit_distance(&a, &b)
    }

    #[test]
    fn edit_distance_counts_each_slip_once() {
        assert_eq!(distance("surface", "surface"), 0);
        assert_eq!(distance("surfce", "surface"), 1);
        assert_eq!(distance("surfaces", "surface"), 1);
        assert_eq!(distance("surfoce", "surface"), 1);
        assert_eq!(distance("lenght", "length"), 1);
        assert_eq!(distance("", "abc"), 3);
        assert_eq!(distance("abc", ""), 3);
        assert_eq!(distance("kitten", "sitting"), 3);
    }

    #[test]
    fn nearest_takes_the_closest_slip_only() {
        let names = ["sphere", "surface", "sweep"];
        assert_eq!(nearest("SURFCE", &names), Some("surface"));
        // "swep" is one edit from "sweep" and three from the others.
        assert_eq!(nearest("swep", &names), Some("sweep"));
        // Two edits in a five-letter name are more than a slip.
        assert_eq!(nearest("swxxp", &names), None);
        // Ties go to the first name.
        assert_eq!(nearest("b", &["a", "bb", "ba"]), Some("bb"));
        // A one-letter word that is not the name is no slip of it.
        assert_eq!(nearest("q", &["x"]), None);
        assert_eq!(nearest(&"s".repeat(100), &names), None);
        assert_eq!(did_you_mean("swep", &names), " — did you mean 'sweep'?");
        assert_eq!(did_you_mean("zzz", &names), "");
    }

    #[test]
    fn shown_path_keeps_the_end_of_a_long_path() {
        let short = std::path::Path::new("a/b.deck");
        assert_eq!(shown_path(short), "'a/b.deck'");
        let long = format!("{}/end.ras", "d".repeat(300));
        let shown = shown_path(std::path::Path::new(&long));
        assert!(shown.starts_with("'…d"), "{shown}");
        assert!(shown.ends_with("/end.ras' (308 characters)"), "{shown}");
        assert_eq!(
            shown.chars().count(),
            1 + 1 + SHOWN_PATH_CHARS + 1 + " (308 characters)".len()
        );
    }

    #[test]
    fn shown_cuts_after_forty_characters() {
        let forty = "a".repeat(SHOWN_CHARS);
        assert_eq!(shown(&forty), format!("'{forty}'"));
        assert_eq!(shown(&format!("{forty}b")), format!("'{forty}…' (41 characters)"));
        assert_eq!(shown("\0\t\r\x1b\x7f"), "'\\0\\t\\r\\x1B\\x7F'");
    }
}
