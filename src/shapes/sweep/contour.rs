//! The contour's own geometry: its tangent, orientation and signed area,
//! and the cap test [`point_in_contour`].

use super::{asc, may_have_root, norm2, one_crossing, unit_crossings, CapGrid, Crossings};
use crate::robust::{bernstein_unit_of, real_roots, RealRoots};
use crate::types::{Coeff, SweepShape};

/// The contour's curve direction at s of segment (u, v): the derivative;
/// where it vanishes (a cusp from repeated control points), the limit
/// direction from the second or third derivative.
pub(super) fn tangent(u: &Coeff, v: &Coeff, s: f64, size: f64) -> (f64, f64) {
    let tiny = 1e-9 * size;
    let t1 = (u.slope(s), v.slope(s));
    if norm2(t1.0, t1.1) > tiny {
        return t1;
    }
    // x′(s) ≈ x″(s0)(s − s0): forward from the start, backward at the end.
    let sign = if s > 0.5 { -1.0 } else { 1.0 };
    let t2 = (sign * u.curvature(s), sign * v.curvature(s));
    if norm2(t2.0, t2.1) > tiny {
        return t2;
    }
    (u.a, v.a)
}

/// The contour's signed area, ½∮(U dV − V dU): positive when it runs
/// counter-clockwise in the (U, V) plane, where (V′, −U′) points out.
pub fn signed_area(u: &[Coeff], v: &[Coeff]) -> f64 {
    let mut sum = 0.0;
    for (cu, cv) in u.iter().zip(v) {
        let (pu, pv) = (asc(cu), asc(cv));
        for j in 0..4 {
            for k in 1..4 {
                let w = k as f64 / (j + k) as f64;
                sum += (pu[j] * pv[k] - pv[j] * pu[k]) * w;
            }
        }
    }
    0.5 * sum
}

/// +1 or −1: which way (V′, −U′) must turn to point out of the contour.
pub fn orientation(u: &[Coeff], v: &[Coeff]) -> f64 {
    if signed_area(u, v) < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Are the segments `u`, `v` the driver takes from `sw` all of its
/// segments, those its kept orientation and its cache's cap grid were
/// made with?
fn all_segments(sw: &SweepShape, u: &[Coeff], v: &[Coeff]) -> bool {
    u.len() == sw.u.len() && v.len() == sw.v.len()
}

/// [`orientation`] of the segments `u`, `v` the driver takes from `sw`:
/// the one filled with them (`sw.orientation`) when they are all of its
/// segments, else computed.
pub(super) fn orientation_of(sw: &SweepShape, u: &[Coeff], v: &[Coeff]) -> f64 {
    if sw.orientation != 0.0 && all_segments(sw, u, v) {
        sw.orientation
    } else {
        orientation(u, v)
    }
}

/// [`point_in_contour`] of the segments `u`, `v` the driver takes from
/// `sw`: answered by `grid`, made with all of `sw`'s segments
/// ([`SweepCache`](super::SweepCache)), where it knows and `u`, `v` are
/// all of them, else solved.
pub(super) fn inside_contour(
    grid: Option<&CapGrid>,
    sw: &SweepShape,
    u: &[Coeff],
    v: &[Coeff],
    x: f64,
    y: f64,
) -> bool {
    let whole = all_segments(sw, u, v);
    match grid.filter(|_| whole).and_then(|g| g.answer(x, y)) {
        Some(inside) => inside,
        None => point_in_contour(u, v, x, y),
    }
}

/// Is (x, y) inside the contour? Even–odd rule along the ray from (x, y)
/// toward +U: the sign of V(s) − y is followed round the whole contour
/// (at each joint, at the roots of V(s) = y inside each segment, and
/// between), and each change of sign right of x counts a crossing. A root
/// where V only touches y changes nothing, and a crossing through a joint
/// counts once, since each joint's sign is computed once.
///
/// Reconstructed (the thesis prints no cap test). Its cubics are solved by
/// the port's robust solver whatever `Options::solver` says (the one root
/// of a cubic whose Bernstein count is one by `one_crossing`, the rest by
/// [`real_roots`]): one missed crossing turns a whole cap inside out along
/// a line.
pub fn point_in_contour(u: &[Coeff], v: &[Coeff], x: f64, y: f64) -> bool {
    let n = u.len().min(v.len());
    let mut inside = false;
    let above = |g: f64| g >= 0.0;
    for i in 0..n {
        let (cu, cv) = (&u[i], &v[i]);
        if cu.max < x {
            continue; // every change on this segment is left of x
        }
        if y < cv.min || y > cv.max {
            continue; // V stays on one side of y (the convex hull): no change of sign
        }
        let next = (i + 1) % n;
        let g0 = v[i].d - y;
        let g1 = v[next].d - y;
        if cu.min > x {
            // Every change on this segment is right of x (its joints and its
            // roots alike), so they count as one when the signs at its two
            // joints differ: the count below, without its roots.
            if above(g0) != above(g1) {
                inside = !inside;
            }
            continue;
        }
        let mut p = [0.0; 7];
        p[..4].copy_from_slice(&asc(cv));
        p[0] -= y;
        let b = bernstein_unit_of::<3>(&p);
        let r = match unit_crossings(3, &b) {
            Crossings::None => continue, // V − y keeps one strict sign over the segment
            Crossings::One => {
                let mut one = RealRoots::NONE;
                (one.count, one.x[0], one.multiplicity[0]) = (1, one_crossing(3, &p, &b, 0.0), 1);
                one
            }
            Crossings::Unknown if !may_have_root(3, &p, 0.0, 1.0) => continue, // (D18)
            Crossings::Unknown => real_roots(3, &p, 0.0, 1.0),
        };
        // The sign sequence: joint, (midpoint, root)*, midpoint, joint.
        let mut prev_sign = above(g0);
        let mut prev_at = Some(cu.d);
        let mut prev_s = 0.0;
        let roots = if r.identically_zero { &[][..] } else { r.roots() };
        let mut flip = |sign: bool, at: Option<f64>, s_mid: f64, prev_sign: &mut bool, prev_at: &mut Option<f64>| {
            if sign != *prev_sign {
                let loc = at.or(*prev_at).unwrap_or_else(|| cu.value(s_mid));
                if loc > x {
                    inside = !inside;
                }
            }
            *prev_sign = sign;
            *prev_at = at;
        };
        for &s in roots.iter().filter(|&&s| s > 0.0 && s < 1.0) {
            let mid = 0.5 * (prev_s + s);
            flip(above(cv.value(mid) - y), None, mid, &mut prev_sign, &mut prev_at);
            flip(true, Some(cu.value(s)), s, &mut prev_sign, &mut prev_at);
            prev_s = s;
        }
        let mid = 0.5 * (prev_s + 1.0);
        flip(above(cv.value(mid) - y), None, mid, &mut prev_sign, &mut prev_at);
        flip(above(g1), Some(u[next].d), 1.0, &mut prev_sign, &mut prev_at);
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::sweep::{star_points, translation_sweep};
    use crate::types::{CurveKind, SweepShape};

    fn square(points: &[[f64; 2]], curve: CurveKind) -> SweepShape {
        translation_sweep(points.to_vec(), curve, 2.0)
    }

    /// The grid answers for the whole contour it was made with only: given
    /// fewer segments of either coordinate (as a record whose `segment` is
    /// less than its lists), `inside_contour` solves that open contour as
    /// `point_in_contour` does.
    #[test]
    fn inside_contour_asks_the_grid_for_the_whole_contour_only() {
        let pts = star_points(12, 2.0, 1.0);
        let sw = square(&pts, CurveKind::Bspline);
        let grid = CapGrid::new(&sw.u, &sw.v);
        assert!(grid.is_some());
        let grid = grid.as_ref();
        let n = sw.u.len();
        let (mut differ, mut asked) = (0, 0);
        for k in 0..4000u64 {
            let x = -2.0 + 4.0 * crate::hash::hashed_uniform(2 * k);
            let y = -2.0 + 4.0 * crate::hash::hashed_uniform(2 * k + 1);
            let whole = point_in_contour(&sw.u, &sw.v, x, y);
            assert_eq!(inside_contour(grid, &sw, &sw.u, &sw.v, x, y), whole);
            for (u, v) in [
                (&sw.u[..n - 1], &sw.v[..n - 1]),
                (&sw.u[..], &sw.v[..n - 1]),
                (&sw.u[..n - 1], &sw.v[..]),
            ] {
                let open = point_in_contour(u, v, x, y);
                assert_eq!(inside_contour(grid, &sw, u, v, x, y), open, "({x}, {y})");
                differ += (open != whole) as usize;
                asked += 1;
            }
        }
        assert!(differ > 100, "the open contours differ at {differ} of {asked}");
    }

    #[test]
    fn point_in_contour_square_bezier() {
        // A square with straight Bezier sides, counter-clockwise.
        let pts = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [3.0, 1.0],
            [3.0, 2.0],
            [3.0, 3.0],
            [2.0, 3.0],
            [1.0, 3.0],
            [0.0, 3.0],
            [0.0, 2.0],
            [0.0, 1.0],
        ];
        let sw = square(&pts, CurveKind::Bezier);
        assert!(signed_area(&sw.u, &sw.v) > 0.0);
        assert!((signed_area(&sw.u, &sw.v) - 9.0).abs() < 1e-12);
        assert!(point_in_contour(&sw.u, &sw.v, 1.5, 1.5));
        assert!(!point_in_contour(&sw.u, &sw.v, 4.0, 1.5));
        assert!(!point_in_contour(&sw.u, &sw.v, -1.0, 1.5));
        // Through the corner's height (a joint) and along an edge.
        assert!(point_in_contour(&sw.u, &sw.v, 1.5, 0.0 + 1e-12));
        assert!(!point_in_contour(&sw.u, &sw.v, -1.0, 0.0));
        assert!(!point_in_contour(&sw.u, &sw.v, -1.0, 3.0));
        assert!(!point_in_contour(&sw.u, &sw.v, 1.5, 3.5));
    }
}
