//! `contour --script EDITS`: edits one a line, as the window makes them.
//!
//! ```text
//! move K DU DV        move point K by (DU, DV)
//! insert K U V        a new point (U, V) that becomes point K (1..n+1)
//! delete K            delete point K
//! curve bspline|bezier
//! sweep translation|conic|rotation
//! ```
//! Points are counted from 1, as the window numbers them. Blank lines and
//! lines starting with `#` are skipped; words are case-insensitive.

use super::model::Edit;
use crate::types::{CurveKind, PrimitiveClass};

/// The most bytes a script may have: a deck's limit
/// ([`crate::deck::MAX_DECK_BYTES`], 64 MiB), far past any script of edits.
pub const MAX_SCRIPT_BYTES: usize = crate::deck::MAX_DECK_BYTES;

/// Reads a script's text from `reader`, named `file` in errors: no more
/// than [`MAX_SCRIPT_BYTES`] and one byte, so a source without end
/// (`--script /dev/zero`, `yes | contour … --script -`) ends with an error
/// at the byte past the limit (`FILE:LINE: …`) rather than taking all
/// memory.
pub fn read(reader: impl std::io::Read, file: &str) -> Result<String, String> {
    read_within(reader, file, MAX_SCRIPT_BYTES)
}

/// [`read`] with another limit.
fn read_within(reader: impl std::io::Read, file: &str, limit: usize) -> Result<String, String> {
    use std::io::Read;
    let mut bytes = Vec::new();
    reader
        .take(limit as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("{file}: {e}"))?;
    if bytes.len() > limit {
        let line = 1 + bytes[..limit].iter().filter(|&&b| b == b'\n').count();
        return Err(format!(
            "{file}:{line}: the script is larger than {} MiB, the most the editor reads",
            limit >> 20
        ));
    }
    String::from_utf8(bytes).map_err(|e| format!("{file}: the script is not UTF-8 text ({e})"))
}

/// An edit of the script and the line it stands on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScriptLine {
    pub line: usize,
    pub edit: Edit,
}

/// The edits of a script, or the first error as `FILE:LINE: message`.
pub fn parse(text: &str, file: &str) -> Result<Vec<ScriptLine>, String> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let words: Vec<&str> = raw.split_whitespace().collect();
        if words.is_empty() || words[0].starts_with('#') {
            continue;
        }
        let edit = edit(&words).map_err(|e| format!("{file}:{line}: {e}"))?;
        out.push(ScriptLine { line, edit });
    }
    Ok(out)
}

/// The edit of one line's words.
fn edit(words: &[&str]) -> Result<Edit, String> {
    let verb = words[0].to_ascii_lowercase();
    let want = |n: usize, form: &str| match words.len() == n {
        true => Ok(()),
        false => Err(format!(
            "'{verb}' takes {} (\"{form}\"), found {}",
            n - 1,
            words.len() - 1
        )),
    };
    let point = |w: &str| match w.parse::<usize>() {
        Ok(k) if k >= 1 => Ok(k - 1),
        _ => Err(format!("'{w}' is not a point number (1, 2, …)")),
    };
    let number = |w: &str, what: &str| match w.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{w}' is not a number for {what}")),
    };
    match verb.as_str() {
        "move" => {
            want(4, "move K DU DV")?;
            Ok(Edit::Move {
                k: point(words[1])?,
                du: number(words[2], "DU")?,
                dv: number(words[3], "DV")?,
            })
        }
        "insert" => {
            want(4, "insert K U V")?;
            Ok(Edit::Insert {
                k: point(words[1])?,
                u: number(words[2], "U")?,
                v: number(words[3], "V")?,
            })
        }
        "delete" => {
            want(2, "delete K")?;
            Ok(Edit::Delete { k: point(words[1])? })
        }
        "curve" => {
            want(2, "curve bspline|bezier")?;
            match words[1].to_ascii_lowercase().as_str() {
                "bspline" => Ok(Edit::Curve(CurveKind::Bspline)),
                "bezier" => Ok(Edit::Curve(CurveKind::Bezier)),
                w => Err(format!("'{w}' is not a curve: bspline or bezier")),
            }
        }
        "sweep" => {
            want(2, "sweep translation|conic|rotation")?;
            match words[1].to_ascii_lowercase().as_str() {
                "translation" => Ok(Edit::Sweep(PrimitiveClass::Translation)),
                "conic" => Ok(Edit::Sweep(PrimitiveClass::Conic)),
                "rotation" => Ok(Edit::Sweep(PrimitiveClass::Rotation)),
                w => Err(format!("'{w}' is not a sweep kind: translation, conic or rotation")),
            }
        }
        _ => Err(format!(
            "'{}' is no edit: move, insert, delete, curve or sweep",
            words[0]
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A source without end is read no further than the limit and one
    /// byte; the error names the line of the byte past it.
    #[test]
    fn a_script_is_read_to_its_limit_and_no_further() {
        let endless = std::io::repeat(b'\n');
        let e = read_within(endless, "s", 10).unwrap_err();
        assert_eq!(e, "s:11: the script is larger than 0 MiB, the most the editor reads");
        let e = read(std::io::repeat(0), "<stdin>").unwrap_err();
        assert!(e.starts_with("<stdin>:1: the script is larger than 64 MiB"), "{e}");
        assert_eq!(read_within(&b"move 1 0 0\n"[..], "s", 11).unwrap(), "move 1 0 0\n");
        assert!(read_within(&b"\xff"[..], "s", 11)
            .unwrap_err()
            .starts_with("s: the script is not UTF-8"));
    }

    #[test]
    fn every_edit_reads_with_points_from_one() {
        let s = parse(
            "# a comment\n\nmove 2 0.5 -1\ninsert 1 0 0\nDELETE 3\ncurve Bezier\nsweep conic\n",
            "e",
        )
        .unwrap();
        let edits: Vec<(usize, Edit)> = s.iter().map(|l| (l.line, l.edit)).collect();
        assert_eq!(
            edits,
            vec![
                (
                    3,
                    Edit::Move {
                        k: 1,
                        du: 0.5,
                        dv: -1.0
                    }
                ),
                (4, Edit::Insert { k: 0, u: 0.0, v: 0.0 }),
                (5, Edit::Delete { k: 2 }),
                (6, Edit::Curve(CurveKind::Bezier)),
                (7, Edit::Sweep(PrimitiveClass::Conic)),
            ]
        );
    }

    #[test]
    fn a_bad_line_is_named_with_its_number() {
        for (text, want) in [
            ("move 0 1 1", "e:1: '0' is not a point number (1, 2, …)"),
            ("\nmove 1 1", "e:2: 'move' takes 3 (\"move K DU DV\"), found 2"),
            ("insert 1 a 0", "e:1: 'a' is not a number for U"),
            ("curve nurbs", "e:1: 'nurbs' is not a curve: bspline or bezier"),
            (
                "sweep lathe",
                "e:1: 'lathe' is not a sweep kind: translation, conic or rotation",
            ),
            ("drag 1", "e:1: 'drag' is no edit: move, insert, delete, curve or sweep"),
            ("move 1 inf 0", "e:1: 'inf' is not a number for DU"),
        ] {
            assert_eq!(parse(text, "e").unwrap_err(), want, "{text}");
        }
    }
}
