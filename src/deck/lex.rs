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

use crate::types::Pos;

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

/// A cursor over a deck's bytes that keeps the line and column of where it
/// stands. A column is a character: one UTF-8 character, or one byte that is
/// not part of a UTF-8 character (a Latin-1 or Big5 byte in a comment).
#[derive(Clone, Debug)]
pub(super) struct Cursor<'a> {
    src: &'a [u8],
    at: usize,
    line: u32,
    column: u32,
}

impl<'a> Cursor<'a> {
    pub fn new(src: &'a [u8]) -> Self {
        Cursor {
            src,
            at: 0,
            line: 1,
            column: 1,
        }
    }

    /// Where the cursor stands.
    pub fn pos(&self) -> Pos {
        Pos {
            line: self.line,
            column: self.column,
        }
    }

    /// The bytes from the cursor on.
    fn rest(&self) -> &'a [u8] {
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
    last_eol: Option<Pos>,
    /// The token that ends the deck, once met.
    last: Option<Token>,
}

impl<'a> Lexer<'a> {
    pub fn new(src: &'a [u8]) -> Self {
        Lexer {
            cur: Cursor::new(src),
            last_eol: None,
            last: None,
        }
    }

    /// A lexical error at `pos`: the lexer stops there.
    fn bad(&mut self, pos: Pos, message: String) -> Token {
        let t = Token {
            tok: Tok::Bad(message),
            pos,
        };
        self.last = Some(t.clone());
        t
    }

    /// The error for a byte that is not ASCII outside a comment.
    fn not_ascii(&mut self, b: u8) -> Token {
        let pos = self.cur.pos();
        self.bad(
            pos,
            format!("the byte 0x{b:02X} is not ASCII: outside comments a deck is ASCII (comments may hold any bytes)"),
        )
    }

    /// The next token.
    pub fn next_token(&mut self) -> Token {
        if let Some(t) = &self.last {
            return t.clone();
        }
        loop {
            let here = self.cur.pos();
            let rest = self.cur.rest();
            let Some(&b) = rest.first() else { break };
            if b == b'\n' {
                self.last_eol = Some(here);
                self.cur.step();
                return Token {
                    tok: Tok::Eol,
                    pos: here,
                };
            } else if is_blank(b) {
                self.cur.step();
            } else if b == b'{' || rest.starts_with(b"(*") {
                let (open, close): (&str, &[u8]) = if b == b'{' { ("{", b"}") } else { ("(*", b"*)") };
                for _ in 0..open.len() {
                    self.cur.step();
                }
                loop {
                    let rest = self.cur.rest();
                    if rest.is_empty() {
                        let close = String::from_utf8_lossy(close).into_owned();
                        return self.bad(here, format!("unterminated comment: '{open}' has no '{close}'"));
                    }
                    if rest.starts_with(close) {
                        for _ in 0..close.len() {
                            self.cur.step();
                        }
                        break;
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
                    pos: here,
                };
            }
        }
        let end = match self.last_eol {
            Some(eol) if self.cur.src.ends_with(b"\n") => eol,
            _ => self.cur.pos(),
        };
        let t = Token {
            tok: Tok::Eof,
            pos: end,
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

    /// Every token of a deck, up to the end of the deck or an error.
    fn tokenize(source: &str) -> Vec<Token> {
        let mut lexer = Lexer::new(source.as_bytes());
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

    #[test]
    fn unterminated_comment_is_reported_at_its_start() {
        let toks = tokenize("a\n  (* open\n\n");
        let last = toks.last().cloned();
        assert_eq!(
            last,
            Some(Token {
                tok: Tok::Bad("unterminated comment: '(*' has no '*)'".into()),
                pos: Pos { line: 2, column: 3 },
            })
        );
    }

    #[test]
    fn end_of_file_stands_on_the_last_line() {
        assert_eq!(tokenize("").last().map(|t| t.pos), Some(Pos { line: 1, column: 1 }));
        assert_eq!(tokenize("ab\n").last().map(|t| t.pos), Some(Pos { line: 1, column: 3 }));
        assert_eq!(
            tokenize("ab\ncd").last().map(|t| t.pos),
            Some(Pos { line: 2, column: 3 })
        );
    }

    #[test]
    fn columns_count_characters_and_stray_bytes_in_comments() {
        let toks = tokenize("{é ü} x");
        assert_eq!(toks[0].pos, Pos { line: 1, column: 7 });
        // Big5 (two bytes a character, not UTF-8) and Latin-1 in comments:
        // each byte that is not UTF-8 is one column.
        let deck = b"{ \xa4\xa4\xa4\xe5 caf\xe9 } x\n(* \xff *) y";
        let mut lexer = Lexer::new(deck);
        assert_eq!(lexer.next_token().pos, Pos { line: 1, column: 15 });
        assert_eq!(lexer.next_token().tok, Tok::Eol);
        let y = lexer.next_token();
        assert_eq!((y.tok, y.pos), (Tok::Word("y".into()), Pos { line: 2, column: 9 }));
    }

    #[test]
    fn a_byte_that_is_not_ascii_outside_comments_is_an_error_at_it() {
        for (deck, column) in [(&b"ab c\xe9d"[..], 5), (b"  \xa4\xa4", 3), ("x é".as_bytes(), 3)] {
            let mut lexer = Lexer::new(deck);
            let mut t = lexer.next_token();
            while let Tok::Word(_) = t.tok {
                t = lexer.next_token();
            }
            assert!(matches!(&t.tok, Tok::Bad(m) if m.contains("not ASCII")), "{t:?}");
            assert_eq!(t.pos, Pos { line: 1, column });
            assert_eq!(lexer.next_token(), t, "the lexer stops at the error");
        }
    }

    #[test]
    fn pos_at_counts_like_the_lexer() {
        let deck = b"ab\n{\xc3\xa9}\xff";
        assert_eq!(Cursor::new(deck).pos_at(0), Pos { line: 1, column: 1 });
        assert_eq!(Cursor::new(deck).pos_at(3), Pos { line: 2, column: 1 });
        // After `{é}` (4 bytes, 3 characters).
        assert_eq!(Cursor::new(deck).pos_at(7), Pos { line: 2, column: 4 });
        assert_eq!(Cursor::new(deck).pos_at(99), Pos { line: 2, column: 5 });
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
