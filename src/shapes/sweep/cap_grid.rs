//! The cap test's answer where no segment passes: a grid over the
//! contour's box whose cells the contour does not enter are marked inside
//! or outside once, when the contour is made, so that a ray reaching a cap
//! there needs no root (the port's; the thesis prints no cap test,
//! DEVIATIONS D32).
//!
//! A cell the contour does not enter lies wholly on one side of it, so the
//! answer at its centre, from [`point_in_contour`], is the answer at every
//! point of it. Which cells the contour enters is found from the segments'
//! Bézier control polygons, which hold their curves on [0, 1] (the convex
//! hull property), halved (de Casteljau) until a piece's box is about a
//! cell, and padded: a cell counts as entered when a padded piece's box
//! overlaps it, so a point in a cell left clean is farther from the curve
//! than the pad, far beyond the rounding of the cell's index.

use super::contour::point_in_contour;
use crate::types::Coeff;

/// Cells along each side of the grid.
const CELLS: usize = 64;

/// Halvings of a segment at most (a piece of a segment is 2⁻¹⁶ of it).
const MAX_DEPTH: u32 = 16;

/// What a cell of the grid knows.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cell {
    /// The contour may enter it: ask [`point_in_contour`].
    Near,
    Inside,
    Outside,
}

/// See the module doc. Built by [`CapGrid::new`] from the contour's
/// segments; answers [`CapGrid::answer`].
#[derive(Clone, PartialEq)]
pub(crate) struct CapGrid {
    x0: f64,
    y0: f64,
    /// Cells per unit of U and of V.
    per_x: f64,
    per_y: f64,
    cells: Vec<Cell>,
}

/// A summary: the cells are too many to print with every scene.
impl std::fmt::Debug for CapGrid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let count = |c: Cell| self.cells.iter().filter(|&&k| k == c).count();
        write!(
            f,
            "CapGrid {{ {CELLS}×{CELLS} from ({}, {}): {} near, {} inside, {} outside }}",
            self.x0,
            self.y0,
            count(Cell::Near),
            count(Cell::Inside),
            count(Cell::Outside)
        )
    }
}

/// The Bézier control points of segment (u, v) on [0, 1], from its
/// power coefficients: d, d + c/3, d + (2c + b)/3, d + c + b + a.
fn control_points(u: &Coeff, v: &Coeff) -> [[f64; 2]; 4] {
    let p = |c: &Coeff| {
        [
            c.d,
            c.d + c.c / 3.0,
            c.d + (2.0 * c.c + c.b) / 3.0,
            c.d + c.c + c.b + c.a,
        ]
    };
    let (pu, pv) = (p(u), p(v));
    std::array::from_fn(|k| [pu[k], pv[k]])
}

/// The box of four points: (min x, max x, min y, max y).
fn points_box(p: &[[f64; 2]; 4]) -> (f64, f64, f64, f64) {
    p.iter().fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
        |(a, b, c, d), q| (a.min(q[0]), b.max(q[0]), c.min(q[1]), d.max(q[1])),
    )
}

/// The two halves of a cubic Bézier's control polygon (de Casteljau at ½).
fn halve(p: &[[f64; 2]; 4]) -> ([[f64; 2]; 4], [[f64; 2]; 4]) {
    let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let (p01, p12, p23) = (mid(p[0], p[1]), mid(p[1], p[2]), mid(p[2], p[3]));
    let (p012, p123) = (mid(p01, p12), mid(p12, p23));
    let m = mid(p012, p123);
    ([p[0], p01, p012, m], [m, p123, p23, p[3]])
}

impl CapGrid {
    /// The grid of the closed contour (u, v); `None` when its box is
    /// degenerate or not finite (the cap test then always asks
    /// [`point_in_contour`]).
    pub fn new(u: &[Coeff], v: &[Coeff]) -> Option<CapGrid> {
        let n = u.len().min(v.len());
        if n == 0 {
            return None;
        }
        let polygons: Vec<[[f64; 2]; 4]> = (0..n).map(|i| control_points(&u[i], &v[i])).collect();
        if !polygons.iter().flatten().flatten().all(|c| c.is_finite()) {
            return None;
        }
        let (mut xmin, mut xmax, mut ymin, mut ymax) =
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for p in &polygons {
            let (a, b, c, d) = points_box(p);
            (xmin, xmax, ymin, ymax) = (xmin.min(a), xmax.max(b), ymin.min(c), ymax.max(d));
        }
        let size = [xmin, xmax, ymin, ymax].iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if !(size.is_finite() && xmax > xmin && ymax > ymin) {
            return None;
        }
        // Far above the rounding of the control points and of a cell's
        // index, far below a cell.
        let pad = 1e-9 * size;
        let (x0, y0) = (xmin - pad, ymin - pad);
        let per_x = CELLS as f64 / (xmax - xmin + 2.0 * pad);
        let per_y = CELLS as f64 / (ymax - ymin + 2.0 * pad);
        let mut grid = CapGrid {
            x0,
            y0,
            per_x,
            per_y,
            cells: vec![Cell::Outside; CELLS * CELLS],
        };
        let (cell_w, cell_h) = (1.0 / per_x, 1.0 / per_y);
        let mut stack: Vec<([[f64; 2]; 4], u32)> = polygons.iter().map(|&p| (p, 0)).collect();
        while let Some((p, depth)) = stack.pop() {
            let (a, b, c, d) = points_box(&p);
            // Pieces of half a cell: each marks one to four cells.
            if depth < MAX_DEPTH && (b - a > 0.5 * cell_w || d - c > 0.5 * cell_h) {
                let (l, r) = halve(&p);
                stack.push((l, depth + 1));
                stack.push((r, depth + 1));
                continue;
            }
            let (i0, i1) = (grid.column(a - pad), grid.column(b + pad));
            let (j0, j1) = (grid.row(c - pad), grid.row(d + pad));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    grid.cells[j * CELLS + i] = Cell::Near;
                }
            }
        }
        // Every other cell as its centre. A run of such cells along a row
        // lies on one side of the contour (a segment between two centres
        // of the run crosses only cells it does not enter), so its first
        // cell's answer is every one's: a few point tests a row, not 64.
        for j in 0..CELLS {
            let mut run: Option<Cell> = None;
            for i in 0..CELLS {
                let cell = &mut grid.cells[j * CELLS + i];
                if *cell == Cell::Near {
                    run = None;
                    continue;
                }
                *cell = *run.get_or_insert_with(|| {
                    let x = x0 + (i as f64 + 0.5) * cell_w;
                    let y = y0 + (j as f64 + 0.5) * cell_h;
                    if point_in_contour(u, v, x, y) {
                        Cell::Inside
                    } else {
                        Cell::Outside
                    }
                });
            }
        }
        Some(grid)
    }

    /// The column of U = x, clamped into the grid.
    fn column(&self, x: f64) -> usize {
        (((x - self.x0) * self.per_x).max(0.0) as usize).min(CELLS - 1)
    }

    /// The row of V = y, clamped into the grid.
    fn row(&self, y: f64) -> usize {
        (((y - self.y0) * self.per_y).max(0.0) as usize).min(CELLS - 1)
    }

    /// Is (x, y) inside the contour, where the grid knows: `None` in a cell
    /// the contour may enter (and for NaN). Outside the grid, no: the grid
    /// holds the control polygons, and so the curve, with the pad to spare.
    pub fn answer(&self, x: f64, y: f64) -> Option<bool> {
        let (fx, fy) = ((x - self.x0) * self.per_x, (y - self.y0) * self.per_y);
        if fx.is_nan() || fy.is_nan() {
            return None;
        }
        if !(fx >= 0.0 && fx < CELLS as f64 && fy >= 0.0 && fy < CELLS as f64) {
            return Some(false);
        }
        match self.cells[fy as usize * CELLS + fx as usize] {
            Cell::Near => None,
            Cell::Inside => Some(true),
            Cell::Outside => Some(false),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::hashed_uniform;
    use crate::shapes::sweep::SweepCache;
    use crate::shapes::sweep::{star_points, translation_sweep};
    use crate::types::{CurveKind, PrimitiveClass, SweepShape};

    /// The grid the cache of `sw` as an object of `class` keeps.
    fn grid_of(class: PrimitiveClass, sw: &SweepShape) -> Option<CapGrid> {
        SweepCache::new(class, sw).and_then(|c| c.cap_grid)
    }

    /// A contour through `points` (closed uniform B-spline or Bézier).
    fn contour(points: Vec<[f64; 2]>, curve: CurveKind) -> SweepShape {
        translation_sweep(points, curve, 1.0)
    }

    /// fig5_6's wavy star (16 points at radii 1.4 and 0.7), either way
    /// round; a Bézier square with a pinched side.
    fn contours() -> Vec<SweepShape> {
        let star = star_points(16, 1.4, 0.7);
        let clockwise: Vec<[f64; 2]> = star.iter().rev().copied().collect();
        let square = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [3.0, 1.0],
            [3.0, 2.0],
            [3.0, 3.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [0.0, 3.0],
            [0.0, 2.0],
            [0.0, 1.0],
        ];
        vec![
            contour(star, CurveKind::Bspline),
            contour(clockwise, CurveKind::Bspline),
            contour(square, CurveKind::Bezier),
        ]
    }

    /// A cell the contour does not enter is marked as `point_in_contour`
    /// answers at its own centre, though only the first of each run along
    /// a row is asked.
    #[test]
    fn each_clean_cell_is_its_centres_answer() {
        for sw in contours() {
            let grid = grid_of(PrimitiveClass::Translation, &sw).unwrap();
            let (w, h) = (1.0 / grid.per_x, 1.0 / grid.per_y);
            let mut asked = 0;
            for j in 0..CELLS {
                for i in 0..CELLS {
                    let cell = grid.cells[j * CELLS + i];
                    if cell == Cell::Near {
                        continue;
                    }
                    let (x, y) = (grid.x0 + (i as f64 + 0.5) * w, grid.y0 + (j as f64 + 0.5) * h);
                    let inside = point_in_contour(&sw.u, &sw.v, x, y);
                    assert_eq!(cell == Cell::Inside, inside, "cell ({i}, {j})");
                    asked += 1;
                }
            }
            assert!(asked > CELLS * CELLS / 2, "{asked}");
        }
    }

    /// Where the grid answers, it answers as `point_in_contour`: at points
    /// spread over (and around) the contour's box, and at points a hair
    /// off the curve on either side, where only a grid that marked its
    /// cells wrongly would answer. And it answers most of the box.
    #[test]
    fn the_grid_answers_as_point_in_contour() {
        for (c, sw) in contours().iter().enumerate() {
            let grid = grid_of(PrimitiveClass::Translation, sw).expect("a grid is made with the segments");
            let (xmin, xmax, ymin, ymax) = sw.u.iter().zip(&sw.v).fold(
                (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
                |(a, b, p, q), (cu, cv)| (a.min(cu.min), b.max(cu.max), p.min(cv.min), q.max(cv.max)),
            );
            let (mut known, mut asked) = (0, 0);
            for k in 0..20_000u64 {
                let r = |j: u64| hashed_uniform(4 * k + j + 1_000_000 * c as u64);
                let (x, y) = if k % 2 == 0 {
                    // Over the box and a tenth beyond it.
                    let (w, h) = (xmax - xmin, ymax - ymin);
                    (xmin - 0.1 * w + 1.2 * w * r(0), ymin - 0.1 * h + 1.2 * h * r(1))
                } else {
                    // A hair off the curve, across it.
                    let i = (r(0) * sw.u.len() as f64) as usize % sw.u.len();
                    let s = r(1);
                    let (cu, cv) = (&sw.u[i], &sw.v[i]);
                    let (du, dv) = (cu.slope(s), cv.slope(s));
                    let off = [1e-7, 1e-4, 1e-2][k as usize % 3] * if r(2) < 0.5 { -1.0 } else { 1.0 };
                    let len = (du * du + dv * dv).sqrt().max(1e-300);
                    (cu.value(s) + off * dv / len, cv.value(s) - off * du / len)
                };
                let want = point_in_contour(&sw.u, &sw.v, x, y);
                if let Some(got) = grid.answer(x, y) {
                    assert_eq!(got, want, "contour {c}: ({x}, {y})");
                    known += (k % 2 == 0) as usize;
                }
                asked += (k % 2 == 0) as usize;
            }
            assert!(known * 10 > asked * 8, "contour {c}: the grid knows {known} of {asked}");
        }
    }

    /// NaN is not answered (the cap test asks `point_in_contour`), in
    /// either coordinate; the grid's far edges and corner, where the cell
    /// index reaches the count, are beyond it: outside.
    #[test]
    fn nan_is_not_answered_and_the_far_edges_are_outside() {
        let sw = contours().remove(0);
        let grid = grid_of(PrimitiveClass::Translation, &sw).expect("a grid");
        assert_eq!(grid.answer(f64::NAN, 0.0), None);
        assert_eq!(grid.answer(0.0, f64::NAN), None);
        assert_eq!(grid.answer(0.0, 0.0), Some(true));
        let far_x = grid.x0 + CELLS as f64 / grid.per_x;
        let far_y = grid.y0 + CELLS as f64 / grid.per_y;
        assert_eq!((far_x - grid.x0) * grid.per_x, CELLS as f64);
        assert_eq!((far_y - grid.y0) * grid.per_y, CELLS as f64);
        for (x, y) in [(far_x, 0.0), (0.0, far_y), (far_x, far_y)] {
            assert_eq!(grid.answer(x, y), Some(false), "({x}, {y})");
        }
    }

    /// No grid where the contour has no area to lay one over, or is not
    /// finite (every cap test is then solved), nor for a rotation sweep.
    #[test]
    fn no_grid_for_a_flat_or_broken_contour() {
        let flat = contour((0..8).map(|k| [k as f64, 2.0]).collect(), CurveKind::Bspline);
        assert!(grid_of(PrimitiveClass::Translation, &flat).is_none());
        let mut broken = contours().remove(0);
        broken.v[3].c = f64::NAN;
        assert!(CapGrid::new(&broken.u, &broken.v).is_none());
        assert!(CapGrid::new(&[], &[]).is_none());
        // A rotation sweep's contour closes no cap: no grid is made for it.
        let mut goblet = contours().remove(0);
        crate::shapes::sweep::prepare::fill_segments(PrimitiveClass::Rotation, &mut goblet);
        assert!(grid_of(PrimitiveClass::Rotation, &goblet).is_none());
        assert!(
            grid_of(PrimitiveClass::Translation, &goblet).is_some(),
            "the class decides"
        );
    }
}
