//! Bicubic Bezier patches (§6.2's "parametric surface"): the port's
//! extension. P(u, v) = Σ B_r(v) B_c(u) P[4r + c], u and v in [0, 1], the
//! Bernstein cubics B; a patch is a sheet without inside, seen from both
//! sides (the shading turns the normal toward the ray).
//!
//! The intersection is Bezier clipping (Nishita, Sederberg & Kakimoto
//! 1990, "Ray tracing trimmed rational surface patches", SIGGRAPH '90).
//! The ray is the meeting line of two planes through it; the control
//! points' signed distances to them, (x, y), make a planar Bezier patch
//! D(u, v) whose zeros are the ray's hits, and each control point's ray
//! parameter t rides along (the patch in the ray's frame). Then, over and
//! over: the distances of the net to a line through the origin across the
//! net's v direction, by columns, are the Bernstein coefficients of a
//! function of (u, v) that D = 0 makes 0, so its zeros lie where the
//! convex hull of the points (c/3, distance) meets the axis: the u range
//! outside that is cut away (de Casteljau); then v alike. A piece that
//! shrinks by less than a fifth is halved; a piece whose ranges are
//! narrower than [`CONVERGED`] gives its centre to Newton's method on D,
//! and the hit is checked on the patch.
//!
//! Why no root is missed: a range is cut only where the convex hull of
//! Bernstein coefficients keeps from 0 a function that vanishes at every
//! root (the convex hull property of the Bernstein basis), and a halving
//! keeps both halves; so every root in the patch stays in some piece
//! until that piece converges, and a piece whose least t lies beyond the
//! nearest hit so far is dropped only because it cannot hold a nearer one
//! (its t lies in the hull of its net's t). What can still fail, counted
//! in docs/STABILITY.md: a grazing ray (a double root, where the clips
//! shrink slowly and the halvings multiply) may run out of
//! [`MAX_STEPS`] or of the [`STACK`] of pieces and leave a hole; and at a
//! point where the patch has no tangent plane (a collapsed edge) Newton's
//! step is not taken and the normal is taken nearby.
//!
//! The normal is exact: Pᵤ × Pᵥ at the hit's (u, v), in the local frame.
//! Everything per ray is in fixed arrays.

use super::sweep::{box_size, ray_meets_box, RESIDUAL_TOL};
use super::Near;
use crate::types::{BoundingBox, DVec3, LocalHit, PatchShape, Ray};

/// A piece converges when both its parameter ranges are narrower than
/// this; Newton's method then finishes the root.
pub const CONVERGED: f64 = 1e-7;

/// The most clipping steps one ray takes on one patch.
pub const MAX_STEPS: usize = 200;

/// The most pieces waiting at once.
pub const STACK: usize = 24;

/// A clip that keeps more than this share of a range halves the piece.
const SLOW: f64 = 0.8;

/// The control hull's box, in the local frame (it holds the patch).
pub fn patch_box(shape: &PatchShape) -> BoundingBox {
    shape.points.iter().fold(BoundingBox::EMPTY, |b, &p| b.holding(p))
}

/// The radius of a sphere about the local origin holding the patch: its
/// farthest control point.
pub fn patch_reach(shape: &PatchShape) -> f64 {
    shape.points.iter().fold(0.0f64, |m, p| m.max(p.length()))
}

/// The Bernstein cubics at x, and their derivatives.
fn bernstein3(x: f64) -> ([f64; 4], [f64; 4]) {
    let y = 1.0 - x;
    (
        [y * y * y, 3.0 * x * y * y, 3.0 * x * x * y, x * x * x],
        [
            -3.0 * y * y,
            3.0 * y * (y - 2.0 * x),
            3.0 * x * (2.0 * y - x),
            3.0 * x * x,
        ],
    )
}

/// P(u, v), Pᵤ and Pᵥ of a net of 16 points of any kind of coordinates.
fn eval<T>(net: &[T; 16], u: f64, v: f64) -> (T, T, T)
where
    T: Copy + Default + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T>,
{
    let ((bu, du), (bv, dv)) = (bernstein3(u), bernstein3(v));
    let (mut p, mut pu, mut pv) = (T::default(), T::default(), T::default());
    for r in 0..4 {
        for c in 0..4 {
            let q = net[4 * r + c];
            p = p + q * (bv[r] * bu[c]);
            pu = pu + q * (bv[r] * du[c]);
            pv = pv + q * (dv[r] * bu[c]);
        }
    }
    (p, pu, pv)
}

/// The point of the patch at (u, v), and its exact unit normal Pᵤ × Pᵥ;
/// where that vanishes (a collapsed edge or corner), the normal a step
/// toward the patch's middle, or `None` if it vanishes there too.
pub fn patch_point(shape: &PatchShape, u: f64, v: f64) -> (DVec3, Option<DVec3>) {
    let (p, pu, pv) = eval(&shape.points, u, v);
    let unit = |n: DVec3| {
        let l = n.length();
        (l > 0.0 && l.is_finite()).then(|| n / l)
    };
    let normal = unit(pu.cross(pv)).or_else(|| {
        let (u1, v1) = (u + 1e-6 * (0.5 - u).signum(), v + 1e-6 * (0.5 - v).signum());
        let (_, pu, pv) = eval(&shape.points, u1, v1);
        unit(pu.cross(pv))
    });
    (p, normal)
}

/// A piece of the patch in the ray's frame: each control point's
/// distances to the two planes and its ray parameter, and the piece's
/// ranges of u and v in the whole patch.
#[derive(Clone, Copy)]
struct Piece {
    net: [DVec3; 16],
    u: (f64, f64),
    v: (f64, f64),
}

/// The part [a, b] (0 ≤ a ≤ b ≤ 1) of a cubic Bezier curve, by de
/// Casteljau: the curve on [0, b], then its part from a/b.
fn part(p: [DVec3; 4], a: f64, b: f64) -> [DVec3; 4] {
    let left = |p: [DVec3; 4], x: f64| {
        let (p01, p12, p23) = (p[0].lerp(p[1], x), p[1].lerp(p[2], x), p[2].lerp(p[3], x));
        let (p012, p123) = (p01.lerp(p12, x), p12.lerp(p23, x));
        [p[0], p01, p012, p012.lerp(p123, x)]
    };
    let right = |p: [DVec3; 4], x: f64| {
        let (p01, p12, p23) = (p[0].lerp(p[1], x), p[1].lerp(p[2], x), p[2].lerp(p[3], x));
        let (p012, p123) = (p01.lerp(p12, x), p12.lerp(p23, x));
        [p012.lerp(p123, x), p123, p23, p[3]]
    };
    let l = if b < 1.0 { left(p, b) } else { p };
    if a <= 0.0 {
        l
    } else if b > 0.0 {
        right(l, (a / b).min(1.0))
    } else {
        [l[0]; 4]
    }
}

/// The two directions a piece is clipped in.
#[derive(Clone, Copy, PartialEq)]
enum Dir {
    U,
    V,
}

impl Piece {
    /// The piece cut to [a, b] of its own range in `dir`.
    fn cut(&self, dir: Dir, a: f64, b: f64) -> Piece {
        let mut out = *self;
        for line in 0..4 {
            let at = |k: usize| match dir {
                Dir::U => 4 * line + k,
                Dir::V => 4 * k + line,
            };
            let q = part(std::array::from_fn(|k| self.net[at(k)]), a, b);
            for (k, p) in q.into_iter().enumerate() {
                out.net[at(k)] = p;
            }
        }
        let range = |(lo, hi): (f64, f64)| (lo + a * (hi - lo), lo + b * (hi - lo));
        match dir {
            Dir::U => out.u = range(self.u),
            Dir::V => out.v = range(self.v),
        }
        out
    }

    /// The least and greatest ray parameter of the net, which hold the
    /// piece's (convex hull).
    fn t_range(&self) -> (f64, f64) {
        self.net.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        })
    }

    /// The part of the piece's own range in `dir` where a zero of D can
    /// be (see the module doc), or `None` where none can.
    fn clip(&self, dir: Dir) -> Option<(f64, f64)> {
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
        let n = if line != glam::DVec2::ZERO { line.perp() } else { other };
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

/// What a query asks: the nearest hit, or whether one lies before the
/// caller's `tmax`.
#[derive(Clone, Copy)]
struct Ask {
    tmin: f64,
    /// In the near frame: no hit at or past it matters.
    limit: f64,
    /// Stop at the first hit before `limit`.
    first: bool,
}

/// The nearest hit of a ray with the patch beyond `tmin`, in its local
/// frame (see the module doc); `reach` the radius of a sphere about the
/// local origin holding it ([`patch_reach`], or the object's `radius`).
/// `searched` counts the patches clipped past the first test.
pub fn intersect_patch(shape: &PatchShape, reach: f64, ray: &Ray, tmin: f64, searched: &mut u64) -> Option<LocalHit> {
    query(shape, reach, ray, tmin, f64::INFINITY, false, searched)
}

/// Does the patch stand on the ray at some t with `tmin` < t < `tmax`?
/// The shadow ray's question: the answer of [`intersect_patch`], the
/// search stopped at the first hit before `tmax`.
pub fn patch_blocks(shape: &PatchShape, reach: f64, ray: &Ray, tmin: f64, tmax: f64, searched: &mut u64) -> bool {
    query(shape, reach, ray, tmin, tmax, true, searched).is_some_and(|h| h.t < tmax)
}

fn query(
    shape: &PatchShape,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    first: bool,
    searched: &mut u64,
) -> Option<LocalHit> {
    if !ray.origin.is_finite() || !ray.dir.is_finite() || ray.dir == DVec3::ZERO || tmin.is_nan() {
        return None;
    }
    let near = Near::of(ray, tmin, DVec3::ZERO, reach * reach);
    let (o, d) = (near.ray.origin, near.ray.dir);
    let b = patch_box(shape);
    let (lo, hi) = (DVec3::new(b.xmin, b.ymin, b.zmin), DVec3::new(b.xmax, b.ymax, b.zmax));
    if !ray_meets_box(&near.ray, near.tmin, lo, hi) {
        return None;
    }
    // The ray's frame: two unit normals across it (from the axis it is
    // least along), and its parameter.
    let dn = d.normalize();
    let a = dn.abs();
    let axis = if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let n1 = dn.cross(axis).normalize();
    let n2 = dn.cross(n1);
    let inv = 1.0 / d.length_squared();
    let frame = |p: DVec3| {
        let w = p - o;
        DVec3::new(n1.dot(w), n2.dot(w), d.dot(w) * inv)
    };
    let whole = Piece {
        net: shape.points.map(frame),
        u: (0.0, 1.0),
        v: (0.0, 1.0),
    };
    let size = box_size(&b);
    let ask = Ask {
        tmin: near.tmin,
        limit: tmax - near.shift,
        first,
    };
    if whole.clip(Dir::U).is_none() || whole.clip(Dir::V).is_none() {
        return None;
    }
    *searched += 1;
    let (t, u, v) = search(&whole, ask, size)?;
    let (point, normal) = patch_point(shape, u, v);
    let normal = normal.unwrap_or(-dn);
    near.back(Some(LocalHit { t, point, normal }))
}

/// The clipping of the module doc over the whole patch in the ray's
/// frame: the nearest root beyond `ask.tmin` (or, for `ask.first`, any
/// before `ask.limit`) as (t, u, v).
fn search(whole: &Piece, ask: Ask, size: f64) -> Option<(f64, f64, f64)> {
    let mut stack = [*whole; STACK];
    let mut len = 1;
    let mut best: Option<(f64, f64, f64)> = None;
    let mut steps = 0;
    while len > 0 {
        len -= 1;
        let mut piece = stack[len];
        loop {
            steps += 1;
            if steps > MAX_STEPS {
                return best;
            }
            let bound = best.map_or(ask.limit, |b| b.0.min(ask.limit));
            let (t_lo, t_hi) = piece.t_range();
            if t_hi <= ask.tmin || t_lo >= bound {
                break;
            }
            if piece.u.1 - piece.u.0 < CONVERGED && piece.v.1 - piece.v.0 < CONVERGED {
                if let Some(hit) = finish(whole, &piece, ask, size) {
                    if hit.0 < bound {
                        best = Some(hit);
                        if ask.first {
                            return best;
                        }
                    }
                }
                break;
            }
            let Some((a, b)) = piece.clip(Dir::U) else { break };
            piece = piece.cut(Dir::U, a, b);
            let Some((c, e)) = piece.clip(Dir::V) else { break };
            piece = piece.cut(Dir::V, c, e);
            if b - a <= SLOW && e - c <= SLOW {
                continue;
            }
            // Slow: halve along the wider range, the nearer half first.
            let dir = if piece.u.1 - piece.u.0 >= piece.v.1 - piece.v.0 {
                Dir::U
            } else {
                Dir::V
            };
            let (h0, h1) = (piece.cut(dir, 0.0, 0.5), piece.cut(dir, 0.5, 1.0));
            let (near, far) = if h1.t_range().0 < h0.t_range().0 {
                (h1, h0)
            } else {
                (h0, h1)
            };
            if len == STACK {
                return best;
            }
            stack[len] = far;
            len += 1;
            piece = near;
        }
    }
    best
}

/// A converged piece's root: Newton's method on D from its centre, over
/// the whole patch; the hit (t, u, v) if D vanishes there (within
/// [`RESIDUAL_TOL`] of the patch's size), its (u, v) on the patch and its
/// t beyond `ask.tmin`.
fn finish(whole: &Piece, piece: &Piece, ask: Ask, size: f64) -> Option<(f64, f64, f64)> {
    let (mut u, mut v) = (0.5 * (piece.u.0 + piece.u.1), 0.5 * (piece.v.0 + piece.v.1));
    let (mut p, mut pu, mut pv) = eval(&whole.net, u, v);
    for _ in 0..3 {
        let det = pu.x * pv.y - pu.y * pv.x;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let du = (p.x * pv.y - p.y * pv.x) / det;
        let dv = (pu.x * p.y - pu.y * p.x) / det;
        let (nu, nv) = (u - du, v - dv);
        let (q, qu, qv) = eval(&whole.net, nu, nv);
        if !(q.x.hypot(q.y) < p.x.hypot(p.y)) {
            break;
        }
        (u, v, p, pu, pv) = (nu, nv, q, qu, qv);
    }
    let slack = 1e-9;
    let on = (-slack..=1.0 + slack).contains(&u) && (-slack..=1.0 + slack).contains(&v);
    (on && p.x.hypot(p.y) <= RESIDUAL_TOL * size && p.z > ask.tmin).then_some((
        p.z,
        u.clamp(0.0, 1.0),
        v.clamp(0.0, 1.0),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square patch z = 0 over [−1, 1]², its control points evenly
    /// spaced, bent up by `bend` at the middle rows and columns.
    pub(crate) fn square(bend: f64) -> PatchShape {
        PatchShape {
            points: std::array::from_fn(|k| {
                let (r, c) = (k / 4, k % 4);
                let inner = (1..3).contains(&r) && (1..3).contains(&c);
                DVec3::new(
                    -1.0 + 2.0 * c as f64 / 3.0,
                    -1.0 + 2.0 * r as f64 / 3.0,
                    if inner { bend } else { 0.0 },
                )
            }),
        }
    }

    #[test]
    fn a_flat_square_is_met_where_the_plane_is() {
        let p = square(0.0);
        for (x, y) in [(0.0, 0.0), (0.3, -0.7), (-0.99, 0.99), (0.5, 0.5)] {
            let ray = Ray::new(DVec3::new(x, y, 4.0), DVec3::NEG_Z);
            let h = intersect_patch(&p, patch_reach(&p), &ray, 1e-9, &mut 0).unwrap();
            assert!((h.t - 4.0).abs() < 1e-12, "({x}, {y}): {}", h.t);
            assert!((h.point - DVec3::new(x, y, 0.0)).length() < 1e-12);
            assert!((h.normal.z.abs() - 1.0).abs() < 1e-12);
        }
        let ray = Ray::new(DVec3::new(1.01, 0.0, 4.0), DVec3::NEG_Z);
        assert!(intersect_patch(&p, patch_reach(&p), &ray, 1e-9, &mut 0).is_none());
    }

    /// A bent patch: the hit lies on the surface (its (u, v) found again by
    /// the point), and the normal is Pᵤ × Pᵥ there; a ray through both
    /// folds of a tall bump meets the nearer.
    #[test]
    fn a_bent_patch_is_met_on_its_surface() {
        let p = square(1.5);
        let mut hits = 0;
        for k in 0..400u64 {
            let r = |j: u64| 2.0 * crate::hash::hashed_uniform(4 * k + j) - 1.0;
            let o = DVec3::new(3.0 * r(0), 3.0 * r(1), 3.0);
            let target = DVec3::new(0.9 * r(2), 0.9 * r(3), 0.3);
            let ray = Ray::new(o, (target - o).normalize());
            let Some(h) = intersect_patch(&p, patch_reach(&p), &ray, 1e-9, &mut 0) else {
                continue;
            };
            hits += 1;
            assert!((ray.at(h.t) - h.point).length() < 1e-9, "ray {k}");
            assert!((h.normal.length() - 1.0).abs() < 1e-12);
            // No nearer hit: the patch is a height field over the square
            // (x and y are linear in u and v), and the ray stays above it
            // up to the hit.
            let height = |x: f64, y: f64| eval(&p.points, (x + 1.0) / 2.0, (y + 1.0) / 2.0).0.z;
            let steps = 2000;
            for i in 1..steps {
                let q = ray.at(h.t * i as f64 / steps as f64);
                if q.x.abs() < 1.0 && q.y.abs() < 1.0 {
                    assert!(q.z > height(q.x, q.y) - 1e-9, "ray {k} passed below the sheet");
                }
            }
        }
        assert!(hits > 150, "{hits}");
    }

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

    #[test]
    fn part_of_a_curve_is_the_curve() {
        let p = [
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(2.0, -1.0, 1.0),
            DVec3::new(3.0, 0.0, 0.0),
        ];
        let at = |p: &[DVec3; 4], x: f64| {
            let (b, _) = bernstein3(x);
            (0..4).fold(DVec3::ZERO, |s, k| s + p[k] * b[k])
        };
        for (a, b) in [(0.0, 1.0), (0.2, 0.7), (0.0, 0.4), (0.6, 1.0), (0.5, 0.5)] {
            let q = part(p, a, b);
            for x in [0.0, 0.3, 1.0] {
                assert!(
                    (at(&q, x) - at(&p, a + x * (b - a))).length() < 1e-14,
                    "[{a}, {b}] at {x}"
                );
            }
        }
    }
}
