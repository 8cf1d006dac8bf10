//! The contour being edited: its control points, curve and sweep kind,
//! the edits that change it, whether it makes a closed curve the renderer
//! can sweep, and the undo history. No window here: the script, the tests
//! and the window all edit through [`Contour::apply`].

use crate::types::{CurveKind, PrimitiveClass, MAXSEGMENTS};

/// The finest step a moved or added point keeps: a millionth of a unit.
/// A point the editor writes is rounded to it, so that what is saved reads
/// back as the very number the editor shows and renders (six decimals in
/// the deck; a point that is not touched keeps its deck value exactly).
pub const STEP: f64 = 1e-6;

/// Steps a unit: `k / PER_UNIT` is the double nearest the decimal k·10⁻⁶,
/// as the deck reader parses it (a division by an exact 10⁶ rounds once).
const PER_UNIT: f64 = 1e6;

/// The length a sweep gets when it becomes a translation or conic sweep
/// and had none (a rotation sweep has no `length`).
pub(crate) const DEFAULT_LENGTH: f64 = 1.0;

/// The scale a sweep gets when it becomes a conic sweep and had none.
pub(crate) const DEFAULT_SCALE: f64 = 0.5;

/// The largest magnitude of a coordinate ([`crate::deck::MAX_MAGNITUDE`]).
const MAX_COORD: f64 = crate::deck::MAX_MAGNITUDE;

/// `x` rounded to [`STEP`]: the number the deck reader makes of it
/// written with six decimals.
pub fn snap(x: f64) -> f64 {
    (x * PER_UNIT).round() / PER_UNIT
}

/// A control point (U, V) and its identity: the deck's points are 0..n in
/// the record's order as opened, and each point the editor adds gets the
/// next number, never given again (not even after an undo). The save
/// finds by it which of the record's point lines a point is, to rewrite
/// its numbers in place; a point the record lacks gets a line of its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlPoint {
    pub u: f64,
    pub v: f64,
    pub id: u64,
}

/// A sweep's contour as the editor holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    pub class: PrimitiveClass,
    pub curve: CurveKind,
    pub points: Vec<ControlPoint>,
    /// `length` of a translation or conic sweep; kept (unwritten) while
    /// the sweep is a rotation, so that switching back restores it.
    pub length: f64,
    /// `scale` of a conic sweep; kept likewise while it is not one.
    pub scale: f64,
    /// The identity the next added point gets.
    pub next_id: u64,
}

/// One edit, as a script line says it (points counted from 0 here).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Edit {
    /// Move point `k` by (du, dv).
    Move { k: usize, du: f64, dv: f64 },
    /// Put the new point (u, v) at place `k` (0..=n): it becomes point `k`.
    Insert { k: usize, u: f64, v: f64 },
    /// Delete point `k`.
    Delete { k: usize },
    /// Draw the contour as this curve.
    Curve(CurveKind),
    /// Sweep the contour this way.
    Sweep(PrimitiveClass),
}

/// Why a contour cannot be saved (or swept).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal(pub String);

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// The deck's word for a curve.
pub(crate) fn curve_word(curve: CurveKind) -> &'static str {
    match curve {
        CurveKind::Bspline => "bspline",
        CurveKind::Bezier => "bezier",
    }
}

/// The deck's word for a sweep kind.
pub(crate) fn class_word(class: PrimitiveClass) -> &'static str {
    match class {
        PrimitiveClass::Translation => "translation",
        PrimitiveClass::Conic => "conic",
        PrimitiveClass::Rotation => "rotation",
        _ => "not a sweep",
    }
}

impl Contour {
    /// The contour of a deck's sweep: its points numbered as read.
    pub fn of_deck(class: PrimitiveClass, curve: CurveKind, points: &[[f64; 2]], length: f64, scale: f64) -> Contour {
        Contour {
            class,
            curve,
            points: points
                .iter()
                .enumerate()
                .map(|(i, &[u, v])| ControlPoint { u, v, id: i as u64 })
                .collect(),
            length: if class == PrimitiveClass::Rotation {
                DEFAULT_LENGTH
            } else {
                length
            },
            scale: if class == PrimitiveClass::Conic {
                scale
            } else {
                DEFAULT_SCALE
            },
            next_id: points.len() as u64,
        }
    }

    /// The points as (U, V) pairs.
    pub fn uv(&self) -> Vec<[f64; 2]> {
        self.points.iter().map(|p| [p.u, p.v]).collect()
    }

    /// The number of cubic segments the points give: n for a B-spline,
    /// n div 3 for a Bezier (its last n mod 3 points left over).
    pub fn segments(&self) -> usize {
        let n = self.points.len();
        match self.curve {
            CurveKind::Bspline if n >= 4 => n,
            CurveKind::Bezier => n / 3,
            _ => 0,
        }
    }

    /// Applies one edit, or says why it cannot be made (a point that is
    /// not there, a place past the end); the contour is then unchanged.
    pub fn apply(&mut self, edit: Edit) -> Result<(), Refusal> {
        let n = self.points.len();
        let no_point = |k: usize| {
            Refusal(match n {
                0 => format!("there is no point {}: the contour has none", k + 1),
                _ => format!("there is no point {}: the points are 1..{n}", k + 1),
            })
        };
        match edit {
            Edit::Move { k, du, dv } => {
                let p = self.points.get_mut(k).ok_or_else(|| no_point(k))?;
                let (u, v) = (snap(p.u + du), snap(p.v + dv));
                check_coordinates(u, v)?;
                (p.u, p.v) = (u, v);
            }
            Edit::Insert { k, u, v } => {
                if k > n {
                    return Err(Refusal(format!(
                        "cannot insert point {}: a new point goes at 1..{}",
                        k + 1,
                        n + 1
                    )));
                }
                let (u, v) = (snap(u), snap(v));
                check_coordinates(u, v)?;
                self.points.insert(k, ControlPoint { u, v, id: self.next_id });
                self.next_id += 1;
            }
            Edit::Delete { k } => {
                if k >= n {
                    return Err(no_point(k));
                }
                self.points.remove(k);
            }
            Edit::Curve(curve) => self.curve = curve,
            Edit::Sweep(class) => self.class = class,
        }
        Ok(())
    }

    /// `Ok(segments)` if the contour is a closed curve the renderer sweeps,
    /// else the reason, as the deck reader would give it: too few points
    /// for the curve, a Bezier whose points are not 3k, more than 60
    /// segments, a rotation contour with U < 0, or points that enclose no
    /// area (all on one line).
    pub fn check(&self) -> Result<usize, Refusal> {
        let n = self.points.len();
        let refuse = |s: String| Err(Refusal(s));
        match self.curve {
            CurveKind::Bspline if n < 4 => {
                return refuse(format!(
                    "too few points: a bspline contour needs at least 4, this one has {n}"
                ))
            }
            CurveKind::Bezier if !n.is_multiple_of(3) => {
                let (add, delete) = (3 - n % 3, n % 3);
                return refuse(format!(
                    "no closed curve: a bezier contour is 3k points (k segments), and {n} is not a multiple of 3 (add {add} or delete {delete})"
                ));
            }
            CurveKind::Bezier if n < 6 => {
                return refuse(format!(
                    "too few points: a bezier contour needs at least 6 (2 segments), this one has {n}"
                ))
            }
            _ => {}
        }
        let segments = self.segments();
        if segments > MAXSEGMENTS {
            return refuse(format!(
                "more than {MAXSEGMENTS} segments: {n} points make {segments} {} segments",
                curve_word(self.curve)
            ));
        }
        if self.class == PrimitiveClass::Rotation {
            if let Some(k) = self.points.iter().position(|p| p.u < 0.0) {
                return refuse(format!(
                    "point {} has U = {} < 0: a rotation contour's U is a radius",
                    k + 1,
                    self.points[k].u
                ));
            }
        }
        if self.encloses_nothing() {
            return refuse("no closed curve: the points lie on one line, so the contour encloses nothing".into());
        }
        Ok(segments)
    }

    /// Whether every point lies on one line (or on one place), so that no
    /// curve through them encloses an area: the cross products of the
    /// points from the first are all below rounding.
    fn encloses_nothing(&self) -> bool {
        let Some(first) = self.points.first() else {
            return true;
        };
        let size = self
            .points
            .iter()
            .map(|p| (p.u - first.u).abs().max((p.v - first.v).abs()))
            .fold(0.0, f64::max);
        let far = self
            .points
            .iter()
            .max_by(|a, b| {
                let d = |p: &&ControlPoint| (p.u - first.u).hypot(p.v - first.v);
                d(a).total_cmp(&d(b))
            })
            .copied()
            .unwrap_or(*first);
        let (du, dv) = (far.u - first.u, far.v - first.v);
        let tolerance = 1e-9 * size * size;
        size == 0.0
            || self
                .points
                .iter()
                .all(|p| (du * (p.v - first.v) - dv * (p.u - first.u)).abs() <= tolerance)
    }
}

/// A coordinate the deck reader would take (|x| ≤ 1e7).
fn check_coordinates(u: f64, v: f64) -> Result<(), Refusal> {
    match u.is_finite() && v.is_finite() && u.abs() <= MAX_COORD && v.abs() <= MAX_COORD {
        true => Ok(()),
        false => Err(Refusal(format!(
            "({u}, {v}) is out of range: a deck's numbers lie in -1e7..1e7"
        ))),
    }
}

/// The contours before each edit (undo) and after each undone one (redo).
#[derive(Clone, Debug, Default)]
pub(crate) struct History {
    past: Vec<Contour>,
    future: Vec<Contour>,
}

impl History {
    /// Remembers `before`, the contour as it was before an edit; a new
    /// edit forgets what was undone.
    pub fn push(&mut self, before: Contour) {
        self.past.push(before);
        self.future.clear();
    }

    /// The contour before the last edit, if any; `current` is kept for redo.
    /// Identities given out stay given ([`ControlPoint::id`]).
    pub fn undo(&mut self, current: &Contour) -> Option<Contour> {
        let mut before = self.past.pop()?;
        before.next_id = before.next_id.max(current.next_id);
        self.future.push(current.clone());
        Some(before)
    }

    /// The contour of the last undone edit, if any.
    pub fn redo(&mut self, current: &Contour) -> Option<Contour> {
        let mut after = self.future.pop()?;
        after.next_id = after.next_id.max(current.next_id);
        self.past.push(current.clone());
        Some(after)
    }

    /// How many edits can be undone.
    pub fn depth(&self) -> usize {
        self.past.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(curve: CurveKind) -> Contour {
        Contour::of_deck(
            PrimitiveClass::Translation,
            curve,
            &[[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]],
            0.8,
            1.0,
        )
    }

    #[test]
    fn a_move_is_rounded_to_the_step_and_keeps_the_points_identity() {
        let mut c = square(CurveKind::Bspline);
        c.apply(Edit::Move {
            k: 1,
            du: 0.1,
            dv: 1e-8,
        })
        .unwrap();
        assert_eq!((c.points[1].u, c.points[1].v), (-0.9, 1.0));
        assert_eq!(c.points[1].id, 1);
        assert_eq!(snap(0.1 + 0.2), 0.3);
    }

    #[test]
    fn insert_and_delete_number_the_points_from_the_place() {
        let mut c = square(CurveKind::Bspline);
        c.apply(Edit::Insert { k: 4, u: 0.0, v: -2.0 }).unwrap();
        c.apply(Edit::Insert { k: 0, u: 2.0, v: 0.0 }).unwrap();
        assert_eq!(
            c.points.iter().map(|p| p.id).collect::<Vec<_>>(),
            vec![5, 0, 1, 2, 3, 4]
        );
        c.apply(Edit::Delete { k: 2 }).unwrap();
        assert_eq!(c.uv()[2], [-1.0, -1.0]);
        assert_eq!(c.points.len(), 5);
        let e = c.apply(Edit::Delete { k: 5 }).unwrap_err();
        assert_eq!(e.0, "there is no point 6: the points are 1..5");
        let e = c.apply(Edit::Insert { k: 7, u: 0.0, v: 0.0 }).unwrap_err();
        assert!(e.0.contains("1..6"), "{e}");
        assert!(c.apply(Edit::Move { k: 0, du: 2e7, dv: 0.0 }).is_err());
        assert_eq!(c.points.len(), 5);
    }

    #[test]
    fn an_empty_contour_has_no_point_to_name() {
        let mut c = Contour::of_deck(PrimitiveClass::Translation, CurveKind::Bspline, &[], 1.0, 1.0);
        let e = c.apply(Edit::Delete { k: 0 }).unwrap_err();
        assert_eq!(e.0, "there is no point 1: the contour has none");
        assert_eq!(c.segments(), 0);
    }

    #[test]
    fn the_checks_stop_at_their_bounds() {
        let ring = |n: usize, curve, centre: f64, r: f64| {
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / n as f64;
                    [centre + r * a.cos(), centre + r * a.sin()]
                })
                .collect();
            Contour::of_deck(PrimitiveClass::Translation, curve, &pts, 1.0, 1.0)
        };
        assert_eq!(ring(6, CurveKind::Bezier, 0.0, 1.0).check(), Ok(2));
        assert_eq!(ring(60, CurveKind::Bspline, 0.0, 1.0).check(), Ok(60));
        assert_eq!(ring(180, CurveKind::Bezier, 0.0, 1.0).check(), Ok(60));
        assert!(ring(183, CurveKind::Bezier, 0.0, 1.0).check().is_err());
        let e = ring(5, CurveKind::Bezier, 0.0, 1.0).check().unwrap_err();
        assert!(e.0.ends_with("(add 1 or delete 2)"), "{e}");
        // A square a thousandth wide, far from the origin, is a closed curve.
        assert_eq!(ring(4, CurveKind::Bspline, 1000.0, 0.001).check(), Ok(4));
        // Points on a line away from the origin enclose nothing, and so do
        // points on a line whose cross products are rounding, not area.
        let line = |pts: &[[f64; 2]]| Contour::of_deck(PrimitiveClass::Translation, CurveKind::Bspline, pts, 1.0, 1.0);
        assert!(line(&[[1.0, 1.0], [2.0, 3.0], [3.0, 5.0], [4.0, 7.0]]).check().is_err());
        let rounded: Vec<[f64; 2]> = [0.1, 0.7, 1.3, 2.9]
            .iter()
            .map(|k| [k * 1e5 / 3.0, k * 7e5 / 3.0])
            .collect();
        assert!(line(&rounded).check().is_err());
    }

    #[test]
    fn the_checks_give_the_reason() {
        let mut c = square(CurveKind::Bspline);
        assert_eq!(c.check(), Ok(4));
        c.apply(Edit::Delete { k: 0 }).unwrap();
        assert!(c.check().unwrap_err().0.starts_with("too few points: a bspline"));
        let mut b = square(CurveKind::Bezier);
        let e = b.check().unwrap_err();
        assert!(e.0.contains("(add 2 or delete 1)"), "{e}");
        b.apply(Edit::Delete { k: 0 }).unwrap();
        assert!(b.check().unwrap_err().0.starts_with("too few points: a bezier"));
        let many: Vec<[f64; 2]> = (0..61)
            .map(|k| {
                let a = k as f64 * 0.1;
                [a.cos(), a.sin()]
            })
            .collect();
        let c = Contour::of_deck(PrimitiveClass::Translation, CurveKind::Bspline, &many, 1.0, 1.0);
        assert!(c.check().unwrap_err().0.starts_with("more than 60 segments"));
        let line = Contour::of_deck(
            PrimitiveClass::Translation,
            CurveKind::Bspline,
            &[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]],
            1.0,
            1.0,
        );
        assert!(line.check().unwrap_err().0.contains("encloses nothing"));
        let mut r = square(CurveKind::Bspline);
        r.apply(Edit::Sweep(PrimitiveClass::Rotation)).unwrap();
        assert_eq!(
            r.check().unwrap_err().0,
            "point 2 has U = -1 < 0: a rotation contour's U is a radius"
        );
    }

    #[test]
    fn undo_and_redo_walk_the_history() {
        let mut c = square(CurveKind::Bspline);
        let mut h = History::default();
        let start = c.clone();
        h.push(c.clone());
        c.apply(Edit::Curve(CurveKind::Bezier)).unwrap();
        let after = c.clone();
        c = h.undo(&c).unwrap();
        assert_eq!(c, start);
        assert!(h.undo(&c).is_none());
        c = h.redo(&c).unwrap();
        assert_eq!(c, after);
        assert_eq!(h.depth(), 1);
        h.push(c.clone());
        assert!(h.redo(&c).is_none(), "a new edit forgets the undone ones");
    }

    #[test]
    fn an_undone_insert_gives_its_identity_to_no_later_point() {
        let mut c = square(CurveKind::Bspline);
        let mut h = History::default();
        h.push(c.clone());
        c.apply(Edit::Insert { k: 0, u: 0.0, v: 0.0 }).unwrap();
        assert_eq!(c.points[0].id, 4);
        c = h.undo(&c).unwrap();
        c.apply(Edit::Insert { k: 2, u: 5.0, v: 5.0 }).unwrap();
        assert_eq!(c.points[2].id, 5);
        c = h.redo(&c).unwrap_or(c);
        assert_eq!(c.next_id, 6);
    }
}
