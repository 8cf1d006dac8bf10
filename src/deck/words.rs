//! A deck's words and line ends with the bytes they stand on: for a
//! program that rewrites one record of a deck and must leave every other
//! byte as it is (the contour editor's save, the port's extension). The
//! words are the reader's own (`super::lex`), so a word inside a comment
//! is no word here either.

use std::ops::Range;

use super::lex::{Bytes, Lexer, Tok};
use super::DeckError;

/// A word of the deck outside comments, or a line end that ends a record.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Lexeme {
    /// The word; `None` for a line end.
    pub word: Option<String>,
    /// The 1-based line the lexeme stands on.
    pub line: u32,
    /// Its bytes in the deck: the word's, or the line end's `\n`.
    pub bytes: Range<usize>,
}

/// The lexemes of `source` in order, up to its end, or the deck's error
/// where a comment is left open or a byte outside comments is not ASCII.
pub fn lexemes(source: &[u8], file: &str) -> Result<Vec<Lexeme>, DeckError> {
    let mut lexer = Lexer::new(Bytes::Borrowed(source), file.into());
    let mut out = Vec::new();
    loop {
        let token = lexer.next_token();
        let end = lexer.offset();
        let (word, bytes) = match token.tok {
            Tok::Eof => return Ok(out),
            Tok::Bad(message) => return Err(DeckError::at(token.pos, "deck", None, message)),
            Tok::Eol => (None, end - 1..end),
            // A word is ASCII: one byte a character.
            Tok::Word(w) => {
                let start = end - w.len();
                (Some(w), start..end)
            }
        };
        out.push(Lexeme {
            word,
            line: token.pos.line,
            bytes,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_line_ends_carry_their_bytes_and_comments_are_skipped() {
        let src = b"sweep a { not (* a } word\n  1 -2.5 (* c\n d *) end\n";
        let lx = lexemes(src, "t.deck").unwrap();
        let shown: Vec<(Option<&str>, u32, &[u8])> = lx
            .iter()
            .map(|l| (l.word.as_deref(), l.line, &src[l.bytes.clone()]))
            .collect();
        assert_eq!(
            shown,
            vec![
                (Some("sweep"), 1, &b"sweep"[..]),
                (Some("a"), 1, b"a"),
                (Some("word"), 1, b"word"),
                (None, 1, b"\n"),
                (Some("1"), 2, b"1"),
                (Some("-2.5"), 2, b"-2.5"),
                (Some("end"), 3, b"end"),
                (None, 3, b"\n"),
            ]
        );
    }

    #[test]
    fn a_comment_left_open_is_the_readers_error() {
        let e = lexemes(b"view {", "t.deck").unwrap_err();
        assert_eq!((e.line, e.column), (1, 6));
        assert!(e.message.contains("unterminated comment"), "{e}");
    }
}
