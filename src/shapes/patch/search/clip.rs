//! Bezier clipping (Nishita, Sederberg & Kakimoto 1990) of a piece the
//! contraction bound cannot settle (see the module doc of
//! [`crate::shapes::patch`]), the step of the [`super`] search: a
//! part's ranges cut to where the convex hull of its Bernstein
//! coefficients meets 0, halved where that is slow, Newton's method
//! finishing a part that has converged.

use glam::DVec2;

use super::{Net, Search};
use crate::shapes::patch::{cut, Dir, Piece, CONVERGED, MAX_STEPS};
use crate::shapes::sweep::RESIDUAL_TOL;
use crate::types::DVec3;

/// A clip that keeps more than this share of a range halves the part.
const SLOW: f64 = 0.8;

/// The deepest a part is halved.
const MAX_HALVINGS: u32 = 40;

impl Search<'_> {
    /// Bezier clipping of `part` of the piece whose net in the ray's frame
    /// is `net` (see the module doc); true when the search is done.
    pub(super) fn clip(&mut self, mut part: Part, net: &Net, piece: &Piece, halvings: u32) -> bool {
        loop {
            self.steps += 1;
            if self.steps > MAX_STEPS {
                return true;
            }
            let (t_lo, t_hi) = part.t_range();
            if t_hi <= self.ask.tmin || self.past(t_lo) {
                return false;
            }
            let narrow = part.u.1 - part.u.0 < CONVERGED && part.v.1 - part.v.0 < CONVERGED;
            if narrow || part.span() <= RESIDUAL_TOL * self.cache.size {
                if let Some(hit) = self.finish(net, piece, &part) {
                    if !self.past(hit.0) {
                        self.best = Some(hit);
                        return self.ask.first;
                    }
                }
                return false;
            }
            let Some((a, b)) = part.clip(Dir::U) else { return false };
            part = part.cut(Dir::U, a, b);
            let Some((c, e)) = part.clip(Dir::V) else { return false };
            part = part.cut(Dir::V, c, e);
            if b - a <= SLOW && e - c <= SLOW {
                continue;
            }
            if halvings == MAX_HALVINGS {
                return false;
            }
            // Slow: halve along the wider range, the nearer half first.
            let dir = if part.u.1 - part.u.0 >= part.v.1 - part.v.0 {
                Dir::U
            } else {
                Dir::V
            };
            let (h0, h1) = (part.cut(dir, 0.0, 0.5), part.cut(dir, 0.5, 1.0));
            let (near, far) = if h1.t_range().0 < h0.t_range().0 {
                (h1, h0)
            } else {
                (h0, h1)
            };
            if self.clip(near, net, piece, halvings + 1) {
                return true;
            }
            part = far;
        }
    }
}

/// A part of a piece in the ray's frame: its net (x, y, t) and its ranges
/// of the piece's own u and v.
#[derive(Clone, Copy)]
pub(super) struct Part {
    pub(super) net: [DVec3; 16],
    pub(super) u: (f64, f64),
    pub(super) v: (f64, f64),
}

impl Part {
    /// The part cut to [a, b] of its own range in `dir`.
    pub(super) fn cut(&self, dir: Dir, a: f64, b: f64) -> Part {
        let range = |(lo, hi): (f64, f64)| (lo + a * (hi - lo), lo + b * (hi - lo));
        let (u, v) = match dir {
            Dir::U => (range(self.u), self.v),
            Dir::V => (self.u, range(self.v)),
        };
        Part {
            net: cut(&self.net, dir, a, b),
            u,
            v,
        }
    }

    /// The largest distance of the net's points from the ray, twice over
    /// (the part lies within it of the ray): where a collapsed edge keeps
    /// a range from narrowing, the part has still met the ray.
    fn span(&self) -> f64 {
        self.net.iter().fold(0.0f64, |m, p| m.max(p.x.abs().max(p.y.abs()))) * 2.0
    }

    /// The least and greatest ray parameter of the net, which hold the
    /// part's (convex hull).
    pub(super) fn t_range(&self) -> (f64, f64) {
        self.net.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        })
    }

    /// The part of the part's own range in `dir` where a zero of D can
    /// be (see the module doc), or `None` where none can.
    pub(super) fn clip(&self, dir: Dir) -> Option<(f64, f64)> {
        let q = |r: usize, c: usize| self.net[4 * r + c].truncate();
        // The net's direction across `dir`: the line is drawn along it.
        let (across, along) = (
            (q(3, 0) - q(0, 0)) + (q(3, 3) - q(0, 3)),
            (q(0, 3) - q(0, 0)) + (q(3, 3) - q(3, 0)),
        );
        let (line, other) = match dir {
            Dir::U => (across, along),
            Dir::V => (along, across),
        };
        // The distance to the line: along its normal; a net without that
        // direction is measured along the other.
        let n = if line != DVec2::ZERO { line.perp() } else { other };
        let (mut lo, mut hi) = ([f64::INFINITY; 4], [f64::NEG_INFINITY; 4]);
        for r in 0..4 {
            for c in 0..4 {
                let k = if dir == Dir::U { c } else { r };
                let e = n.dot(q(r, c));
                lo[k] = lo[k].min(e);
                hi[k] = hi[k].max(e);
            }
        }
        hull_on_axis(&lo, &hi)
    }
}

/// Where the convex hull of the points (k/3, lo[k]) and (k/3, hi[k])
/// meets the axis: between the least and greatest crossing of a segment
/// joining two of them of opposite signs (the hull's edges that cross are
/// among those, and every such segment lies in the hull), widened by a
/// rounding margin; `None` if all lie on one side. A NaN answers the
/// whole range.
fn hull_on_axis(lo: &[f64; 4], hi: &[f64; 4]) -> Option<(f64, f64)> {
    if lo.iter().chain(hi).any(|e| e.is_nan()) {
        return Some((0.0, 1.0));
    }
    if lo.iter().all(|&e| e > 0.0) || hi.iter().all(|&e| e < 0.0) {
        return None;
    }
    let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut at = |x: f64| {
        a = a.min(x);
        b = b.max(x);
    };
    for i in 0..4 {
        let xi = i as f64 / 3.0;
        if lo[i] <= 0.0 && hi[i] >= 0.0 {
            at(xi);
        }
        for j in i + 1..4 {
            let xj = j as f64 / 3.0;
            for yi in [lo[i], hi[i]] {
                for yj in [lo[j], hi[j]] {
                    if (yi < 0.0) != (yj < 0.0) {
                        at(xi + (xj - xi) * yi / (yi - yj));
                    }
                }
            }
        }
    }
    let pad = 1e-9;
    (a <= b).then(|| ((a - pad).max(0.0), (b + pad).min(1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_meets_the_axis() {
        // All above, all below: none.
        assert_eq!(hull_on_axis(&[1.0; 4], &[2.0; 4]), None);
        assert_eq!(hull_on_axis(&[-2.0; 4], &[-1.0; 4]), None);
        // A line from −1 at 0 to 2 at 1 crosses at 1/3.
        let lo = [-1.0, 0.0, 1.0, 2.0];
        let (a, b) = hull_on_axis(&lo, &lo).unwrap();
        assert!((a - 1.0 / 3.0).abs() < 1e-8 && (b - 1.0 / 3.0).abs() < 1e-8, "{a} {b}");
    }
}
