//! The segments of a translation or conic sweep whose boxes may meet a
//! box of the contour's plane (the ray's span, D32 and D69), from bins of
//! the boxes' sides, before the test box by box (the port's, D90).

use crate::types::{Coeff, MAXSEGMENTS};

// A segment's bit fits a u64.
const _: () = assert!(MAXSEGMENTS <= 64);

/// The bins each axis of the contour's box is cut into.
const BINS: usize = 64;

/// The segments' box sides by bins of the contour's plane: for each bin b
/// of x, the segments whose U_min lies in a bin at or below b, and those
/// whose U_max lies in a bin at or above b; the same for y and V. A
/// side's bin is a non-decreasing function of it (a difference, a product
/// by a positive number and a truncation, each rounded monotonically), so
/// a segment whose U_min ≤ x₁ has bin(U_min) ≤ bin(x₁): the bits of a span
/// hold every segment its box-by-box test keeps, and a few more, which
/// that test then puts aside. Made once with a cache's segments.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct SideIndex {
    /// x's and y's least side and bins a unit.
    origin: [f64; 2],
    scale: [f64; 2],
    /// U_min at or below, U_max at or above, V_min at or below, V_max at
    /// or above each bin.
    kept: Box<[[u64; BINS]; 4]>,
    /// The segments it was made with.
    len: usize,
}

impl SideIndex {
    /// The index of segments (u, v); `None` for none, or where the sides
    /// are not finite or the box has no width in x or y.
    pub(super) fn new(u: &[Coeff], v: &[Coeff]) -> Option<SideIndex> {
        let n = u.len().min(v.len()).min(MAXSEGMENTS);
        if n == 0 {
            return None;
        }
        let span = |c: &[Coeff]| {
            let lo = c[..n].iter().fold(f64::INFINITY, |m, c| m.min(c.min).min(c.max));
            let hi = c[..n].iter().fold(f64::NEG_INFINITY, |m, c| m.max(c.min).max(c.max));
            (lo, hi)
        };
        let ((ulo, uhi), (vlo, vhi)) = (span(u), span(v));
        let sides = u[..n].iter().chain(&v[..n]).flat_map(|c| [c.min, c.max]);
        if !(ulo < uhi && vlo < vhi) || sides.into_iter().any(|x| !x.is_finite()) {
            return None;
        }
        let mut index = SideIndex {
            origin: [ulo, vlo],
            scale: [BINS as f64 / (uhi - ulo), BINS as f64 / (vhi - vlo)],
            kept: Box::new([[0; BINS]; 4]),
            len: n,
        };
        for (i, (cu, cv)) in u[..n].iter().zip(&v[..n]).enumerate() {
            let bit = 1u64 << i;
            let bins = [
                index.bin(0, cu.min),
                index.bin(0, cu.max),
                index.bin(1, cv.min),
                index.bin(1, cv.max),
            ];
            for (side, &at) in bins.iter().enumerate() {
                // A least side is kept from its bin up, a greatest one
                // from its bin down.
                let range = if side % 2 == 0 { at..BINS } else { 0..at + 1 };
                for b in range {
                    index.kept[side][b] |= bit;
                }
            }
        }
        Some(index)
    }

    /// The bin of `x` on axis `axis` (0 for x, 1 for y): below the box 0,
    /// beyond it the last, NaN 0.
    #[inline(always)]
    fn bin(&self, axis: usize, x: f64) -> usize {
        // `as` saturates: a negative or NaN quotient is 0, +∞ usize::MAX.
        (((x - self.origin[axis]) * self.scale[axis]) as usize).min(BINS - 1)
    }

    /// Was it made with `n` segments?
    pub(super) fn fits(&self, n: usize) -> bool {
        self.len == n
    }

    /// Segments (bit i for segment i) among which are all those the box
    /// `span` = [x₀, x₁, y₀, y₁] does not put aside, those for which
    /// `(cu.max < x₀) | (cu.min > x₁) | (cv.max < y₀) | (cv.min > y₁)` is
    /// false (every segment where an edge is NaN, which puts none aside).
    #[inline(always)]
    pub(super) fn meeting(&self, span: &[f64; 4]) -> u64 {
        if span.iter().any(|x| x.is_nan()) {
            return u64::MAX >> (64 - self.len); // 1 ≤ len ≤ 60
        }
        self.kept[0][self.bin(0, span[1])]
            & self.kept[1][self.bin(0, span[0])]
            & self.kept[2][self.bin(1, span[3])]
            & self.kept[3][self.bin(1, span[2])]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::hashed_uniform;

    fn boxed(min: f64, max: f64) -> Coeff {
        Coeff {
            min,
            max,
            ..Coeff::default()
        }
    }

    /// The bits of `meeting` hold every segment the box-by-box test keeps,
    /// and few others where the edges are finite, for random boxes and spans, spans whose edges are
    /// the boxes' own sides (the comparisons' boundary, ties and equal
    /// sides among them), and edges of infinity and NaN.
    #[test]
    fn meeting_is_the_box_by_box_test() {
        let r = |j: u64| hashed_uniform(31_000 + j);
        let (mut extra, mut indexed, mut few, mut kept) = (0, 0, 0, 0);
        for case in 0..400u64 {
            let n = 1 + (r(100 * case) * 16.0) as usize;
            // Sides on a coarse lattice, so that some are equal.
            let side = |j: u64| (r(100 * case + j) * 8.0).floor() - 4.0;
            let (mut u, mut v) = (vec![], vec![]);
            for i in 0..n as u64 {
                let (a, b, c, d) = (side(4 * i + 1), side(4 * i + 2), side(4 * i + 3), side(4 * i + 4));
                u.push(boxed(a.min(b), a.max(b)));
                v.push(boxed(c.min(d), c.max(d)));
            }
            let Some(index) = SideIndex::new(&u, &v) else {
                // One segment whose box has no width.
                assert!(n == 1 && (u[0].min == u[0].max || v[0].min == v[0].max));
                continue;
            };
            indexed += 1;
            assert!(index.fits(n) && !index.fits(n + 1));
            let edge = |j: u64| match case % 4 {
                0 => side(90 + j),
                1 => side(90 + j) + 0.5,
                2 => [f64::NEG_INFINITY, f64::INFINITY, f64::NAN, 0.0][(r(100 * case + 90 + j) * 4.0) as usize % 4],
                _ => u[0].max,
            };
            let span = [edge(0), edge(1), edge(2), edge(3)];
            let want = (0..n).fold(0u64, |m, i| {
                let (cu, cv) = (&u[i], &v[i]);
                let aside = (cu.max < span[0]) | (cu.min > span[1]) | (cv.max < span[2]) | (cv.min > span[3]);
                if aside {
                    m
                } else {
                    m | 1 << i
                }
            });
            let got = index.meeting(&span);
            assert_eq!(got & want, want, "case {case}: {span:?}");
            assert_eq!(got >> n, 0, "case {case}: only the segments");
            extra += (got & !want).count_ones();
            if case % 4 < 2 {
                // Finite edges: a few more where an edge shares a bin with
                // a side (or both lie beyond the box, in its last bin).
                (few, kept) = (few + (got & !want).count_ones(), kept + want.count_ones());
            }
        }
        assert!(few * 4 < kept, "{few} more than the {kept} kept");
        assert!(extra > 0 && indexed > 350, "infinite and NaN edges take whole bins");
    }

    /// A translation and a conic sweep over a star of 16 segments, with
    /// the bins and without them (the box-by-box test alone): the same
    /// hits and shadow answers to the bit, both solvers, for rays from
    /// afar and from inside the box.
    #[test]
    fn the_bins_keep_every_hit() {
        use super::super::{star_points, translation_sweep, Sweep, SweepCache};
        use crate::options::{Options, Solver};
        use crate::types::{CurveKind, DVec3, PrimitiveClass, Ray};
        for class in [PrimitiveClass::Translation, PrimitiveClass::Conic] {
            let mut sw = translation_sweep(star_points(16, 1.0, 0.45), CurveKind::Bspline, 1.5);
            if class == PrimitiveClass::Conic {
                sw.scale = 0.4;
            }
            let binned = SweepCache::new(class, &sw).expect("a cache");
            assert!(binned.sides.is_some(), "16 segments are kept in bins");
            let plain = SweepCache {
                sides: None,
                ..binned.clone()
            };
            let [a, b] = [&binned, &plain].map(|c| Sweep {
                class,
                shape: &sw,
                cache: Some(c),
            });
            for solver in [Solver::Laguerre, Solver::Robust] {
                let opts = Options {
                    solver,
                    ..Options::default()
                };
                let mut hits = 0;
                for k in 0..3000u64 {
                    let r = |j: u64| hashed_uniform(77_000 + 8 * k + j);
                    let target = DVec3::new(2.2 * r(0) - 1.1, 2.2 * r(1) - 1.1, 1.5 * r(2));
                    let from = if k % 3 == 0 {
                        DVec3::new(2.0 * r(3) - 1.0, 2.0 * r(4) - 1.0, 1.5 * r(5))
                    } else {
                        let phi = std::f64::consts::TAU * r(3);
                        DVec3::new(5.0 * phi.cos(), 5.0 * phi.sin(), 6.0 * r(4) - 2.25)
                    };
                    let ray = Ray::new(from, (target - from).normalize());
                    let hit = a.intersect(&ray, 1e-9, &opts, &mut 0);
                    assert_eq!(
                        hit,
                        b.intersect(&ray, 1e-9, &opts, &mut 0),
                        "{class:?} {solver:?} ray {k}"
                    );
                    let tmax = hit.map_or(10.0, |h| 0.5 * h.t + 0.5 * h.t * 2.0 * r(6));
                    assert_eq!(
                        a.blocks(&ray, 1e-9, tmax, &opts, &mut 0),
                        b.blocks(&ray, 1e-9, tmax, &opts, &mut 0),
                        "{class:?} {solver:?} shadow ray {k}"
                    );
                    hits += hit.is_some_and(|h| h.normal.z.abs() < 0.999) as usize;
                }
                assert!(hits > 1000, "{class:?} {solver:?}: {hits} side hits");
            }
        }
    }

    /// No index for no segments, a side that is not finite, or a box of
    /// no width.
    #[test]
    fn no_index_without_bins() {
        assert_eq!(SideIndex::new(&[], &[]), None);
        let u = [boxed(0.0, 1.0)];
        assert!(SideIndex::new(&u, &u).is_some());
        assert_eq!(SideIndex::new(&u, &[boxed(f64::NAN, 1.0)]), None);
        assert_eq!(SideIndex::new(&u, &[boxed(0.0, f64::INFINITY)]), None);
        assert_eq!(SideIndex::new(&u, &[boxed(1.0, 1.0)]), None);
    }
}
