//! The sweep record in the deck's text, and the save that writes an edited
//! contour back into it: only the words and point lines of that record
//! change; every other byte of the deck, comments included, stays as it
//! was. The words are the deck reader's own ([`crate::deck::words`]).
//!
//! What the save changes, and nothing else:
//! - the sweep kind and the curve: the word, in place;
//! - `length` and `scale`: the value in place; the field removed (with the
//!   blanks before it) when the kind no longer takes it, or appended to
//!   the record's first line when it now needs it;
//! - a point the editor kept: its U and V words in place when they
//!   changed, right-aligned to where the old words ended where the blanks
//!   allow (so that columns stay aligned);
//! - a deleted point: its line, or only its two words when the line holds
//!   a comment too;
//! - an added point: a new line before the next kept point's line (or
//!   before `end`), its columns aligned as the record's first point line.

use std::ops::Range;

use super::model::{class_word, curve_word, Contour};
use crate::deck::words::{lexemes, Lexeme};
use crate::types::PrimitiveClass;

/// A field of the record's first line: its keyword and its value.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Field {
    key: Range<usize>,
    value: Range<usize>,
}

/// A point line of the record: its U and V words and its whole line
/// (with the line end), and whether the line holds nothing else.
#[derive(Clone, Debug, PartialEq, Eq)]
struct PointLine {
    u: Range<usize>,
    v: Range<usize>,
    line: Range<usize>,
    alone: bool,
}

/// Where a sweep record's parts stand in the deck's bytes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SweepRecord {
    /// The line of its `sweep` keyword.
    pub line: u32,
    class: Range<usize>,
    curve: Range<usize>,
    /// Just past the last word of the first line.
    header_end: usize,
    length: Option<Field>,
    scale: Option<Field>,
    points: Vec<PointLine>,
    /// Where the line of `end` starts.
    end_line: usize,
}

/// The lexemes of one record line: its words, up to its line end.
fn split_lines(lx: &[Lexeme]) -> Vec<&[Lexeme]> {
    lx.split(|l| l.word.is_none()).filter(|l| !l.is_empty()).collect()
}

/// Whether a line of words starts with `keyword` (in any case).
fn starts(line: &[Lexeme], keyword: &str) -> bool {
    line.first()
        .and_then(|l| l.word.as_deref())
        .is_some_and(|w| w.eq_ignore_ascii_case(keyword))
}

/// The start of the line holding byte `at`.
fn line_start(source: &[u8], at: usize) -> usize {
    source[..at].iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1)
}

/// Just past the line end of the line holding byte `at` (or the deck's end).
fn line_end(source: &[u8], at: usize) -> usize {
    source[at..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(source.len(), |i| at + i + 1)
}

impl SweepRecord {
    /// The record `sweep NAME …` of a deck the reader has read without
    /// error: the one on `line` when given (the object's record), else
    /// the last one so named (a key shape, which the scene keeps without
    /// its place). An error names what is missing.
    pub fn find(source: &[u8], file: &str, name: &str, line: Option<u32>) -> Result<SweepRecord, String> {
        let lx = lexemes(source, file).map_err(|e| e.to_string())?;
        let lines = split_lines(&lx);
        let mut found = None;
        let mut i = 0;
        while i < lines.len() {
            let first = lines[i];
            let is_list = ["sweep", "prism", "pattern"].iter().any(|k| starts(first, k));
            let mut last = i;
            if is_list {
                while last + 1 < lines.len() && !starts(lines[last], "end") {
                    last += 1;
                }
            }
            let named = first.get(1).and_then(|l| l.word.as_deref()) == Some(name);
            if starts(first, "sweep") && named && line.is_none_or(|n| n == first[0].line) {
                found = Some((i, last));
            }
            i = last + 1;
        }
        let (first, last) = found.ok_or_else(|| format!("{file}: no record 'sweep {name} …' found"))?;
        SweepRecord::read(source, &lines[first..=last])
            .ok_or_else(|| format!("{file}: the record 'sweep {name}' is not whole"))
    }

    /// The parts of a record from its lines (the first, the points, `end`).
    fn read(source: &[u8], lines: &[&[Lexeme]]) -> Option<SweepRecord> {
        let (head, rest) = lines.split_first()?;
        let (end, points) = rest.split_last()?;
        let word = |l: &Lexeme| l.word.as_deref().unwrap_or("").to_ascii_lowercase();
        let mut length = None;
        let mut scale = None;
        let mut k = 9;
        while k + 1 < head.len() {
            let field = Some(Field {
                key: head[k].bytes.clone(),
                value: head[k + 1].bytes.clone(),
            });
            match word(&head[k]).as_str() {
                "length" => length = field,
                "scale" => scale = field,
                _ => {}
            }
            k += 2;
        }
        let points = points
            .iter()
            .map(|p| {
                let (u, v) = (p.first()?.bytes.clone(), p.get(1)?.bytes.clone());
                let line = line_start(source, u.start)..line_end(source, v.end);
                let others = |b: &u8| !matches!(b, b' ' | b'\t' | b'\r' | b'\n');
                let alone = !source[line.start..u.start].iter().any(others)
                    && !source[u.end..v.start].iter().any(others)
                    && !source[v.end..line.end].iter().any(others);
                Some(PointLine { u, v, line, alone })
            })
            .collect::<Option<Vec<_>>>()?;
        Some(SweepRecord {
            line: head[0].line,
            class: head.get(3)?.bytes.clone(),
            curve: head.get(4)?.bytes.clone(),
            header_end: head.last()?.bytes.end,
            length,
            scale,
            points,
            end_line: line_start(source, end.first()?.bytes.start),
        })
    }

    /// The deck with the record rewritten from `original` (the contour as
    /// the deck has it) to `edited`; every byte outside the changes named
    /// in the module's doc is kept.
    pub fn rewrite(&self, source: &[u8], original: &Contour, edited: &Contour) -> Vec<u8> {
        let mut changes: Vec<(Range<usize>, String)> = Vec::new();
        if edited.class != original.class {
            changes.push((self.class.clone(), class_word(edited.class).into()));
        }
        if edited.curve != original.curve {
            changes.push((self.curve.clone(), curve_word(edited.curve).into()));
        }
        let takes_length = edited.class != PrimitiveClass::Rotation;
        let takes_scale = edited.class == PrimitiveClass::Conic;
        for (field, key, wanted, value) in [
            (&self.length, "length", takes_length, edited.length),
            (&self.scale, "scale", takes_scale, edited.scale),
        ] {
            match (field, wanted) {
                (Some(f), true) => {
                    let old = std::str::from_utf8(&source[f.value.clone()]).unwrap_or("");
                    if old.parse::<f64>().ok() != Some(value) {
                        changes.push((f.value.clone(), number(value)));
                    }
                }
                (Some(f), false) => {
                    changes.push((with_blanks_before(source, f.key.clone()), String::new()));
                    changes.push((with_blanks_before(source, f.value.clone()), String::new()));
                }
                (None, true) => changes.push((self.header_end..self.header_end, format!(" {key} {}", number(value)))),
                (None, false) => {}
            }
        }
        self.point_changes(source, original, edited, &mut changes);
        // Insertions (empty ranges) before the changes that start at the
        // same byte; the sort is stable, so added points keep their order.
        changes.sort_by_key(|(r, _)| (r.start, r.end));
        let mut out = Vec::with_capacity(source.len() + 64);
        let mut at = 0;
        for (range, text) in changes {
            out.extend_from_slice(&source[at..range.start]);
            out.extend_from_slice(text.as_bytes());
            at = range.end;
        }
        out.extend_from_slice(&source[at..]);
        out
    }

    /// The changes of the point lines: each point of `edited` is the
    /// record's point line of the same identity in `original`, or new.
    fn point_changes(
        &self,
        source: &[u8],
        original: &Contour,
        edited: &Contour,
        changes: &mut Vec<(Range<usize>, String)>,
    ) {
        let line_of = |id: u64| {
            let o = original.points.iter().position(|q| q.id == id)?;
            Some((o, self.points.get(o)?))
        };
        let mut kept = vec![false; self.points.len()];
        for (i, p) in edited.points.iter().enumerate() {
            match line_of(p.id) {
                Some((o, line)) => {
                    kept[o] = true;
                    let was = &original.points[o];
                    if was.u != p.u {
                        changes.push(aligned(source, line.u.clone(), number(p.u)));
                    }
                    if was.v != p.v {
                        changes.push(aligned(source, line.v.clone(), number(p.v)));
                    }
                }
                None => {
                    // Before the line of the next point the record has.
                    let next = edited.points[i + 1..]
                        .iter()
                        .find_map(|q| line_of(q.id))
                        .map_or(self.end_line, |(_, l)| l.line.start);
                    changes.push((next..next, self.new_line(p.u, p.v)));
                }
            }
        }
        for (line, _) in self.points.iter().zip(kept).filter(|(_, k)| !k) {
            if line.alone {
                changes.push((line.line.clone(), String::new()));
            } else {
                changes.push((with_blanks_before(source, line.u.clone()), String::new()));
                changes.push((with_blanks_before(source, line.v.clone()), String::new()));
            }
        }
    }

    /// A new point line, its words ending in the columns where the first
    /// point line's words end (without one: four spaces, then one between).
    fn new_line(&self, u: f64, v: f64) -> String {
        let (u, v) = (number(u), number(v));
        let (wu, wv) = match self.points.first() {
            Some(p) => (p.u.end - p.line.start, p.v.end - p.u.end),
            None => (4 + u.len(), 1 + v.len()),
        };
        let gap = if v.len() < wv { wv } else { v.len() + 1 };
        format!("{u:>wu$}{v:>gap$}\n")
    }
}

/// `word` with the blanks (spaces, tabs) before it on its line.
fn with_blanks_before(source: &[u8], word: Range<usize>) -> Range<usize> {
    let blanks = source[..word.start]
        .iter()
        .rev()
        .take_while(|&&b| b == b' ' || b == b'\t')
        .count();
    word.start - blanks..word.end
}

/// The change that puts `text` in place of `word`, ending where it ended
/// when the spaces before it allow: a shorter text is padded, a longer one
/// takes spaces before it, keeping at least one (none at a line's start).
fn aligned(source: &[u8], word: Range<usize>, text: String) -> (Range<usize>, String) {
    let spaces = source[..word.start].iter().rev().take_while(|&&b| b == b' ').count();
    let at_line_start = word.start == spaces || source[word.start - spaces - 1] == b'\n';
    let old = word.len();
    if text.len() <= old {
        let pad = if spaces > 0 { old - text.len() } else { 0 };
        return (word, format!("{}{text}", " ".repeat(pad)));
    }
    let spare = if at_line_start {
        spaces
    } else {
        spaces.saturating_sub(1)
    };
    let take = (text.len() - old).min(spare);
    (word.start - take..word.end, text)
}

/// A number as the save writes it: at most six decimals, no trailing
/// zeros (`0.33`, `-1`, `2.5`), never `-0`.
pub fn number(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    match s {
        "-0" | "" => "0".into(),
        s => s.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::editor::model::Edit;
    use crate::types::CurveKind;

    const DECK: &str = "{ a deck }\nsweep  s  red  translation bspline at 0 0 0 length 0.8 { l }\n    1.0000  1.0000 { first }\n   -1.0000  1.0000\n\n   -1.0000 -1.0000\n    1.0000 -1.0000\nend\nsphere b red at 0 0 0 radius 1\n";

    fn open() -> (SweepRecord, Contour) {
        let rec = SweepRecord::find(DECK.as_bytes(), "t.deck", "s", None).unwrap();
        let c = Contour::of_deck(
            PrimitiveClass::Translation,
            CurveKind::Bspline,
            &[[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]],
            0.8,
            1.0,
        );
        (rec, c)
    }

    fn save(edits: &[Edit]) -> String {
        let (rec, original) = open();
        let mut c = original.clone();
        for &e in edits {
            c.apply(e).unwrap();
        }
        String::from_utf8(rec.rewrite(DECK.as_bytes(), &original, &c)).unwrap()
    }

    #[test]
    fn numbers_are_short() {
        assert_eq!(number(0.33), "0.33");
        assert_eq!(number(-1.0), "-1");
        assert_eq!(number(-0.0000001), "0");
        assert_eq!(number(1.2345678), "1.234568");
    }

    #[test]
    fn no_edit_is_the_same_bytes() {
        assert_eq!(save(&[]), DECK);
    }

    #[test]
    fn a_move_changes_its_words_only_and_keeps_the_columns() {
        let out = save(&[Edit::Move {
            k: 1,
            du: 0.25,
            dv: -3.0,
        }]);
        assert_eq!(out, DECK.replace("   -1.0000  1.0000\n", "     -0.75      -2\n"));
    }

    #[test]
    fn a_longer_number_takes_the_spaces_before_it() {
        let out = save(&[Edit::Move {
            k: 0,
            du: 0.123456,
            dv: 0.0,
        }]);
        assert!(out.contains("\n  1.123456  1.0000 { first }\n"), "{out}");
    }

    #[test]
    fn deletes_and_inserts_keep_comments_and_other_lines() {
        let out = save(&[
            Edit::Delete { k: 0 },
            Edit::Delete { k: 1 },
            Edit::Insert { k: 1, u: 0.5, v: 0.25 },
            Edit::Insert { k: 3, u: 2.0, v: 0.0 },
        ]);
        let want = DECK
            .replace("    1.0000  1.0000 { first }\n", " { first }\n")
            .replace("   -1.0000 -1.0000\n", "       0.5    0.25\n")
            .replace("    1.0000 -1.0000\nend", "    1.0000 -1.0000\n         2       0\nend");
        assert_eq!(out, want);
    }

    #[test]
    fn the_kind_and_curve_change_in_place_and_fields_follow_the_kind() {
        let out = save(&[Edit::Sweep(PrimitiveClass::Conic), Edit::Curve(CurveKind::Bezier)]);
        assert!(
            out.contains("sweep  s  red  conic bezier at 0 0 0 length 0.8 scale 0.5 { l }\n"),
            "{out}"
        );
        let out = save(&[Edit::Sweep(PrimitiveClass::Rotation)]);
        assert!(
            out.contains("sweep  s  red  rotation bspline at 0 0 0 { l }\n"),
            "{out}"
        );
        assert_eq!(out.lines().count(), DECK.lines().count());
    }

    #[test]
    fn the_record_on_the_line_given_or_the_last_so_named() {
        let deck = "sweep s r rotation bspline at 0 0 0\n1 1\n1 2\n2 2\n2 1\nend\ndelete s\nprism p r at 0 0 0 height 1\n0 0\n1 0\n0 1\nend\nsweep s r rotation bspline at 0 0 0\n1 1\n1 2\n2 2\n2 1\nend\n";
        assert_eq!(SweepRecord::find(deck.as_bytes(), "d", "s", None).unwrap().line, 13);
        assert_eq!(SweepRecord::find(deck.as_bytes(), "d", "s", Some(1)).unwrap().line, 1);
        let e = SweepRecord::find(deck.as_bytes(), "d", "p", None).unwrap_err();
        assert_eq!(e, "d: no record 'sweep p …' found");
    }
}
