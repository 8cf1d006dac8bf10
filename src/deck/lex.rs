//! The deck's lexer. Reconstructed: Pascal's lexical rules (Jensen & Wirth,
//! *Pascal User Manual and Report*, ch. 1) as DECK.md restates them.
//!
//! The deck is cut into words (maximal runs of characters that are neither
//! white space nor the start of a comment), line ends and the end of the
//! file. What a word means (keyword, name, number, file) is decided by the
//! parser, which knows what it expects there.

use crate::types::Pos;

/// What a token is.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    /// A run of characters other than white space and comment openers.
    Word(String),
    /// A line end outside a comment: it ends a record.
    Eol,
    /// The end of the deck.
    Eof,
    /// A lexical error (an unterminated comment); nothing follows it.
    Bad(String),
}

/// A token and where it starts (1-based line and column, columns counting
/// characters).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Token {
    pub tok: Tok,
    pub pos: Pos,
}

/// Cuts a deck into tokens. The list always ends with [`Tok::Eof`] or
/// [`Tok::Bad`].
///
/// Comments are `{ … }` and `(* … *)`; they do not nest, `{` is closed only
/// by `}` and `(*` only by `*)`. A comment separates words like a space, and
/// the line ends inside it do not end a record. The end of the deck is placed
/// on the last line: at the final line end if the deck ends with one.
pub(super) fn tokenize(source: &str) -> Vec<Token> {
    let mut toks = Vec::new();
    let mut line: u32 = 1;
    let mut column: u32 = 1;
    let mut last_eol: Option<Pos> = None;
    let mut rest = source;

    // Advances over one character, keeping line and column.
    fn step(rest: &mut &str, line: &mut u32, column: &mut u32) -> Option<char> {
        let c = rest.chars().next()?;
        *rest = &rest[c.len_utf8()..];
        if c == '\n' {
            *line = line.saturating_add(1);
            *column = 1;
        } else {
            *column = column.saturating_add(1);
        }
        Some(c)
    }

    while let Some(c) = rest.chars().next() {
        let here = Pos { line, column };
        if c == '\n' {
            toks.push(Token {
                tok: Tok::Eol,
                pos: here,
            });
            last_eol = Some(here);
            step(&mut rest, &mut line, &mut column);
        } else if c.is_whitespace() {
            step(&mut rest, &mut line, &mut column);
        } else if c == '{' || rest.starts_with("(*") {
            let (open, close) = if c == '{' { ("{", "}") } else { ("(*", "*)") };
            for _ in 0..open.len() {
                step(&mut rest, &mut line, &mut column);
            }
            loop {
                if rest.is_empty() {
                    toks.push(Token {
                        tok: Tok::Bad(format!("unterminated comment: '{open}' has no '{close}'")),
                        pos: here,
                    });
                    return toks;
                }
                if rest.starts_with(close) {
                    for _ in 0..close.len() {
                        step(&mut rest, &mut line, &mut column);
                    }
                    break;
                }
                step(&mut rest, &mut line, &mut column);
            }
        } else {
            let mut word = String::new();
            while let Some(c) = rest.chars().next() {
                if c.is_whitespace() || c == '{' || rest.starts_with("(*") {
                    break;
                }
                word.push(c);
                step(&mut rest, &mut line, &mut column);
            }
            toks.push(Token {
                tok: Tok::Word(word),
                pos: here,
            });
        }
    }
    let end = if source.ends_with('\n') {
        last_eol.unwrap_or(Pos { line, column })
    } else {
        Pos { line, column }
    };
    toks.push(Token {
        tok: Tok::Eof,
        pos: end,
    });
    toks
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
    fn columns_count_characters() {
        let toks = tokenize("é ü x");
        assert_eq!(toks[2].pos, Pos { line: 1, column: 5 });
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
