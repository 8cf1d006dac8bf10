//! The deck's lexer. Reconstructed: Pascal's lexical rules (Jensen & Wirth,
//! *Pascal User Manual and Report*, ch. 1) as DECK.md restates them.
//!
//! The deck is cut into words (maximal runs of characters that are neither
//! white space nor the start of a comment), line ends and the end of the
//! file. What a word means (keyword, name, number, file) is decided by the
//! parser, which knows what it expects there.
//!
//! The lexer streams: it hands the parser one token at a time, so reading
//! a deck costs its bytes and the scene it builds, not a list of tokens
//! (the port's extension; a 100 MB deck of blank lines took 4.2 GB when it
//! was tokenised first). It reads bytes, not text: outside comments a deck
//! is ASCII, inside them any bytes may stand (a 1989 deck may carry Big5 or
//! Latin-1 there).

use std::ops::Deref;
use std::rc::Rc;
use std::sync::Arc;

use crate::scene::Pos;

/// The largest deck the reader takes, in bytes (64 MiB): far beyond any
/// scene, and small enough that a deck read from an endless file (a device,
/// a pipe) ends with an error instead of taking all memory.
pub const MAX_DECK_BYTES: usize = 64 << 20;

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    /// A run of ASCII characters other than white space and comment openers.
    Word(String),
    /// A line end outside a comment: it ends a record.
    Eol,
    /// The end of the deck.
    Eof,
    /// A lexical error (an unterminated comment, a byte that is not ASCII
    /// outside a comment); nothing follows it.
    Bad(String),
}

/// A token and where it starts (1-based line and column, columns counting
/// characters).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Token {
    pub tok: Tok,
    pub pos: Pos,
}

/// White space outside comments: space, tab, carriage return, vertical tab,
/// form feed (the line end is a token of its own).
fn is_blank(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | 0x0b | 0x0c)
}

/// A line and a column in the lexer's file: a [`Pos`] without the file,
/// kept while scanning and made a `Pos` only for a token.
type Place = (u32, u32);

/// A deck's bytes: borrowed (the deck [`super::initialize`] is given) or
/// shared (a file an `include` record reads, which the reader owns), so that
/// one lexer serves both and cloning a cursor never copies a file.
#[derive(Clone, Debug)]
pub(super) enum Bytes<'a> {
    Borrowed(&'a [u8]),
    Shared(Rc<[u8]>),
}

impl Deref for Bytes<'_> {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        match self {
            Bytes::Borrowed(b) => b,
            Bytes::Shared(b) => b,
        }
    }
}

/// A cursor over a deck's bytes that keeps the line and column of where it
/// stands. A column is a character: one UTF-8 character, or one byte that is
/// not part of a UTF-8 character (a Latin-1 or Big5 byte in a comment).
#[derive(Clone, Debug)]
pub(super) struct Cursor<'a> {
    src: Bytes<'a>,
    /// The file's name, which every [`Pos`] it gives carries.
    file: Arc<str>,
    at: usize,
    line: u32,
    column: u32,
}

impl<'a> Cursor<'a> {
    pub fn new(src: &'a [u8], file: Arc<str>) -> Self {
        Cursor::over(Bytes::Borrowed(src), file)
    }

    /// The cursor at the start of `src`, borrowed or shared.
    pub fn over(src: Bytes<'a>, file: Arc<str>) -> Self {
        Cursor {
            src,
            file,
            at: 0,
            line: 1,
            column: 1,
        }
    }

    /// Where the cursor stands.
    pub fn pos(&self) -> Pos {
        self.pos_of(self.place())
    }

    /// Where the cursor stands, without the file.
    fn place(&self) -> Place {
        (self.line, self.column)
    }

    /// The position of `place` in the cursor's file.
    fn pos_of(&self, (line, column): Place) -> Pos {
        Pos {
            file: self.file.clone(),
            line,
            column,
        }
    }

    /// The bytes from the cursor on.
    fn rest(&self) -> &[u8] {
        &self.src[self.at..]
    }

    /// Advances over one character, keeping line and column.
    fn step(&mut self) {
        let rest = self.rest();
        let Some(&b) = rest.first() else { return };
        let len = match b {
            0xc2..=0xdf => 2,
            0xe0..=0xef => 3,
            0xf0..=0xf4 => 4,
            _ => 1,
        };
        let len = match rest.get(..len).map(std::str::from_utf8) {
            Some(Ok(_)) => len,
            _ => 1,
        };
        self.at += len;
        if b == b'\n' {
            self.line = self.line.saturating_add(1);
            self.column = 1;
        } else {
            self.column = self.column.saturating_add(1);
        }
    }

    /// Advances over `n` characters (fewer at the end).
    fn skip(&mut self, n: usize) {
        for _ in 0..n {
            self.step();
        }
    }

    /// Advances to byte `offset` (or the end) and returns where that is.
    pub fn pos_at(mut self, offset: usize) -> Pos {
        while self.at < offset.min(self.src.len()) {
            self.step();
        }
        self.pos()
    }
}

/// Cuts a deck into tokens, one at a time. After [`Tok::Eof`] or
/// [`Tok::Bad`] it hands out the same token again.
///
/// Comments are `{ … }` and `(* … *)`; they do not nest, `{` is closed only
/// by `}` and `(*` only by `*)`. A comment separates words like a space, and
/// the line ends inside it do not end a record. The end of the deck is placed
/// on the last line: at the final line end if the deck ends with one.
pub(super) struct Lexer<'a> {
    cur: Cursor<'a>,
    /// Where the last line end stood.
    last_eol: Option<Place>,
    /// The token that ends the deck, once met.
    last: Option<Token>,
    /// The last comment that held its own opener, for the errors.
    opener_inside: Option<OpenerInside<'a>>,
}

/// A comment that held its own opener, `{ a { b } c }`: valid Pascal (the
/// inner `{` is text), but when a stray closer follows, its writer took
/// comments to nest and the words after the comment's end were meant to be
/// inside it.
#[derive(Clone, Debug)]
struct OpenerInside<'a> {
    open: &'static str,
    close: &'static str,
    start: Pos,
    inner: Pos,
    end: Pos,
    /// Just past the comment's closer.
    after: Cursor<'a>,
}

impl OpenerInside<'_> {
    /// The first closer of the comment's kind outside any comment after it,
    /// if one comes before the next opener of its kind.
    fn stray_closer(&self) -> Option<Pos> {
        let (other_open, other_close) = if self.open == "{" { ("(*", "*)") } else { ("{", "}") };
        let mut c = self.after.clone();
        loop {
            let rest = c.rest();
            if rest.is_empty() || rest.starts_with(self.open.as_bytes()) {
                return None;
            }
            if rest.starts_with(self.close.as_bytes()) {
                return Some(c.pos());
            }
            if rest.starts_with(other_open.as_bytes()) {
                c.skip(other_open.len());
                while !c.rest().is_empty() && !c.rest().starts_with(other_close.as_bytes()) {
                    c.step();
                }
                c.skip(other_close.len());
            } else {
                c.step();
            }
        }
    }
}

impl<'a> Lexer<'a> {
    /// The lexer of `src`, whose tokens' positions name `file`.
    pub fn new(src: Bytes<'a>, file: Arc<str>) -> Self {
        Lexer {
            cur: Cursor::over(src, file),
            last_eol: None,
            last: None,
            opener_inside: None,
        }
    }

    /// The byte offset the lexer stands at: just past the token it handed
    /// out last (for [`super::words`]).
    pub fn offset(&self) -> usize {
        self.cur.at
    }

    /// The error for one at `at` that a nested comment explains: `at` lies
    /// after a comment that held its own opener and no later than a stray
    /// closer of its kind. Then the error is reported at the inner opener,
    /// saying so (the original message, "unknown record 'c'", would not).
    pub fn nested_comment(&self, at: Pos) -> Option<(Pos, String)> {
        let n = self.opener_inside.as_ref()?;
        let stray = n.stray_closer()?;
        let key = |p: &Pos| (p.line, p.column);
        if key(&at) < key(&n.end) || key(&at) > key(&stray) {
            return None;
        }
        let place = |p: &Pos| format!("{}:{}", p.line, p.column);
        let (open, close) = (n.open, n.close);
        Some((
            n.inner.clone(),
            format!(
                "a comment inside a comment: '{open} … {close}' comments do not nest (Pascal's), so this \
                 '{open}' is text of the comment opened at {}, the '{close}' at {} ends that comment, \
                 and the '{close}' at {} is outside any comment",
                place(&n.start),
                place(&n.end),
                place(&stray)
            ),
        ))
    }

    /// A lexical error at `pos`: the lexer stops there.
    fn bad(&mut self, place: Place, message: String) -> Token {
        let t = Token {
            tok: Tok::Bad(message),
            pos: self.cur.pos_of(place),
        };
        self.last = Some(t.clone());
        t
    }

    /// The error for a byte that is not ASCII outside a comment.
    fn not_ascii(&mut self, b: u8) -> Token {
        let place = self.cur.place();
        self.bad(
            place,
            format!("the byte 0x{b:02X} is not ASCII: outside comments a deck is ASCII (comments may hold any bytes)"),
        )
    }

    /// The next token.
    pub fn next_token(&mut self) -> Token {
        if let Some(t) = &self.last {
            return t.clone();
        }
        loop {
            let here = self.cur.place();
            let rest = self.cur.rest();
            let Some(&b) = rest.first() else { break };
            if b == b'\n' {
                self.last_eol = Some(here);
                self.cur.step();
                return Token {
                    tok: Tok::Eol,
                    pos: self.cur.pos_of(here),
                };
            } else if is_blank(b) {
                self.cur.step();
            } else if b == b'{' || rest.starts_with(b"(*") {
                let (open, close) = if b == b'{' { ("{", "}") } else { ("(*", "*)") };
                self.cur.skip(open.len());
                let mut inner = None;
                loop {
                    let rest = self.cur.rest();
                    if rest.is_empty() {
                        return self.bad(here, format!("unterminated comment: '{open}' has no '{close}'"));
                    }
                    if rest.starts_with(close.as_bytes()) {
                        let end = self.cur.pos();
                        self.cur.skip(close.len());
                        if let Some(inner) = inner {
                            self.opener_inside = Some(OpenerInside {
                                open,
                                close,
                                start: self.cur.pos_of(here),
                                inner,
                                end,
                                after: self.cur.clone(),
                            });
                        }
                        break;
                    }
                    if inner.is_none() && rest.starts_with(open.as_bytes()) {
                        inner = Some(self.cur.pos());
                    }
                    self.cur.step();
                }
            } else {
                let mut word = String::new();
                loop {
                    let rest = self.cur.rest();
                    let Some(&c) = rest.first() else { break };
                    if c == b'\n' || is_blank(c) || c == b'{' || rest.starts_with(b"(*") {
                        break;
                    }
                    if !c.is_ascii() {
                        return self.not_ascii(c);
                    }
                    word.push(char::from(c));
                    self.cur.step();
                }
                return Token {
                    tok: Tok::Word(word),
                    pos: self.cur.pos_of(here),
                };
            }
        }
        let end = match self.last_eol {
            Some(eol) if self.cur.src.ends_with(b"\n") => eol,
            _ => self.cur.place(),
        };
        let t = Token {
            tok: Tok::Eof,
            pos: self.cur.pos_of(end),
        };
        self.last = Some(t.clone());
        t
    }
}

/// Whether `text` is a number as Pascal writes it, or `.5` or `5.`:
/// `[+|-] (digits [. [digits]] | . digits) [(e|E) [+|-] digits]`.
pub(super) fn is_number(text: &str) -> bool {
    let b = text.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let int_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let int_digits = i - int_start;
    let mut frac_digits = 0;
    if i < b.len() && b[i] == b'.' {
        i += 1;
        let frac_start = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        frac_digits = i - frac_start;
    }
    if int_digits == 0 && frac_digits == 0 {
        return false;
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        i += 1;
        if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
            i += 1;
        }
        let exp_start = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        if i == exp_start {
            return false;
        }
    }
    i == b.len()
}

/// Whether `text` is an integer as Pascal writes it: `[+|-] digits`.
pub(super) fn is_integer(text: &str) -> bool {
    let digits = text.strip_prefix(['+', '-']).unwrap_or(text);
    !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lexer of a deck named `t.deck`.
    fn lexer(source: &[u8]) -> Lexer<'_> {
        Lexer::new(Bytes::Borrowed(source), "t.deck".into())
    }

    /// Where a token of `t.deck` stands.
    fn at(line: u32, column: u32) -> Pos {
        Pos {
            file: "t.deck".into(),
            line,
            column,
        }
    }

    /// Every token of a deck, up to the end of the deck or an error.
    fn tokenize(source: &str) -> Vec<Token> {
        let mut lexer = lexer(source.as_bytes());
        let mut toks = Vec::new();
        loop {
            let t = lexer.next_token();
            let done = matches!(t.tok, Tok::Eof | Tok::Bad(_));
            toks.push(t);
            if done {
                return toks;
            }
        }
    }

    fn words(source: &str) -> Vec<Tok> {
        tokenize(source).into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn comments_are_separators_and_keep_positions() {
        let toks = tokenize("a{x\ny}b (* c *)\n  d");
        let got: Vec<(Tok, u32, u32)> = toks.into_iter().map(|t| (t.tok, t.pos.line, t.pos.column)).collect();
        assert_eq!(
            got,
            vec![
                (Tok::Word("a".into()), 1, 1),
                (Tok::Word("b".into()), 2, 3),
                (Tok::Eol, 2, 12),
                (Tok::Word("d".into()), 3, 3),
                (Tok::Eof, 3, 4),
            ]
        );
    }

    #[test]
    fn comments_do_not_nest_and_close_only_their_own_kind() {
        assert_eq!(
            words("{ (* } x *) y"),
            vec![
                Tok::Word("x".into()),
                Tok::Word("*)".into()),
                Tok::Word("y".into()),
                Tok::Eof
            ]
        );
        assert_eq!(words("(* } *) z"), vec![Tok::Word("z".into()), Tok::Eof]);
    }

    /// The nested-comment error for one at `at` in `source`, the source
    /// lexed to its end.
    fn nested_at(source: &str, at: (u32, u32)) -> Option<(u32, u32)> {
        let mut lexer = Lexer::new(Bytes::Borrowed(source.as_bytes()), "t.deck".into());
        while !matches!(lexer.next_token().tok, Tok::Eof | Tok::Bad(_)) {}
        let at = Pos {
            file: "t.deck".into(),
            line: at.0,
            column: at.1,
        };
        lexer.nested_comment(at).map(|(p, _)| (p.line, p.column))
    }

    #[test]
    fn a_nested_comment_explains_the_errors_up_to_its_stray_closer() {
        // `{ a { b }` ends at 1:9; the stray '}' stands at 1:13.
        let deck = "{ a { b } c } d";
        assert_eq!(nested_at(deck, (1, 11)), Some((1, 5)));
        assert_eq!(nested_at(deck, (1, 13)), Some((1, 5)));
        assert_eq!(nested_at(deck, (1, 15)), None, "past the stray closer");
        assert_eq!(nested_at(deck, (1, 1)), None, "before the comment");
        // No stray closer before the next comment of the kind: valid Pascal.
        assert_eq!(nested_at("{ a { b } c { d } }", (1, 11)), None);
        assert_eq!(nested_at("{ a { b } c", (1, 11)), None);
        // A comment of the other kind between is skipped, its closer too.
        assert_eq!(nested_at("(* a (* b *) { *) } c *)", (1, 21)), Some((1, 6)));
        assert_eq!(nested_at("{ a { b } (* } *) c", (1, 19)), None);
        // An opener of the other kind inside is text, not nesting.
        assert_eq!(nested_at("{ a (* b } c *)", (1, 12)), None);
    }

    #[test]
    fn unterminated_comment_is_reported_at_its_start() {
        let toks = tokenize("a\n  (* open\n\n");
        let last = toks.last().cloned();
        assert_eq!(
            last,
            Some(Token {
                tok: Tok::Bad("unterminated comment: '(*' has no '*)'".into()),
                pos: at(2, 3),
            })
        );
    }

    #[test]
    fn end_of_file_stands_on_the_last_line() {
        assert_eq!(tokenize("").into_iter().last().map(|t| t.pos), Some(at(1, 1)));
        assert_eq!(tokenize("ab\n").into_iter().last().map(|t| t.pos), Some(at(1, 3)));
        assert_eq!(tokenize("ab\ncd").into_iter().last().map(|t| t.pos), Some(at(2, 3)));
    }

    #[test]
    fn columns_count_characters_and_stray_bytes_in_comments() {
        let toks = tokenize("{é ü} x");
        assert_eq!(toks[0].pos, at(1, 7));
        // Big5 (two bytes a character, not UTF-8) and Latin-1 in comments:
        // each byte that is not UTF-8 is one column.
        let deck = b"{ \xa4\xa4\xa4\xe5 caf\xe9 } x\n(* \xff *) y";
        let mut lexer = lexer(deck);
        assert_eq!(lexer.next_token().pos, at(1, 15));
        assert_eq!(lexer.next_token().tok, Tok::Eol);
        let y = lexer.next_token();
        assert_eq!((y.tok, y.pos), (Tok::Word("y".into()), at(2, 9)));
    }

    #[test]
    fn a_byte_that_is_not_ascii_outside_comments_is_an_error_at_it() {
        for (deck, column) in [(&b"ab c\xe9d"[..], 5), (b"  \xa4\xa4", 3), ("x é".as_bytes(), 3)] {
            let mut lexer = lexer(deck);
            let mut t = lexer.next_token();
            while let Tok::Word(_) = t.tok {
                t = lexer.next_token();
            }
            assert!(matches!(&t.tok, Tok::Bad(m) if m.contains("not ASCII")), "{t:?}");
            assert_eq!(t.pos, at(1, column));
            assert_eq!(lexer.next_token(), t, "the lexer stops at the error");
        }
    }

    #[test]
    fn pos_at_counts_like_the_lexer() {
        let deck = b"ab\n{\xc3\xa9}\xff";
        assert_eq!(Cursor::new(deck, "t.deck".into()).pos_at(0), at(1, 1));
        assert_eq!(Cursor::new(deck, "t.deck".into()).pos_at(3), at(2, 1));
        // After `{é}` (4 bytes, 3 characters).
        assert_eq!(Cursor::new(deck, "t.deck".into()).pos_at(7), at(2, 4));
        assert_eq!(Cursor::new(deck, "t.deck".into()).pos_at(99), at(2, 5));
    }

    #[test]
    fn number_grammar() {
        for ok in ["2", "-0.5", "+3", "1.5E-3", ".5", "5.", "1e10", "-.25e+2", "007"] {
            assert!(is_number(ok), "{ok}");
        }
        for bad in [
            "", ".", "-", "1e", "1.2.3", "e5", "1,5", "inf", "NaN", "0x10", "5f", "--5",
        ] {
            assert!(!is_number(bad), "{bad}");
        }
        assert!(is_integer("-12") && is_integer("+0"));
        assert!(!is_integer("1.") && !is_integer("1e2") && !is_integer("-"));
    }
}
