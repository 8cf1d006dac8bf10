//! Bicubic Bezier patches (§6.2's "parametric surface"): the port's
//! extension. P(u, v) = Σ B_r(v) B_c(u) P[4r + c], u and v in [0, 1], the
//! Bernstein cubics B; a patch is a sheet without inside, seen from both
//! sides (the shading turns the normal toward the ray).
//!
//! Before any ray the patch is cut (de Casteljau) into pieces nearly flat
//! ([`PatchCache`]: a quadtree of at most [`MAX_DEPTH`] levels, a piece
//! cut in four while its control points stand farther than [`FLAT`] of
//! its size from the bilinear sheet of its corners), each with the box of
//! its control points; a ray walks the boxes nearest first.
//!
//! In a piece whose box it meets, the ray is the meeting line of two
//! planes through it; the control points' signed distances to them,
//! (x, y), make a planar Bezier patch D(u, v) whose zeros are the ray's
//! hits, and each control point's ray parameter t rides along (the piece
//! in the ray's frame). Most pieces are settled by Newton's method from
//! the piece's centre with a proof that it misses no root
//! (`search::certified`): a contraction bound, from the Jacobian at the
//! centre and a bound of the second derivatives (first the one kept with
//! the piece, made in space, then the tighter one of the net in the ray's
//! frame), shows that D is one-to-one on the piece, so that it has at most
//! one root, and where that root can lie; Newton's method finds it, or
//! the bound shows there is none.
//!
//! A piece the bound cannot settle (a ray grazing it, a piece that folds
//! as the ray sees it) is searched by Bezier clipping (Nishita,
//! Sederberg & Kakimoto 1990, "Ray tracing trimmed rational surface
//! patches", SIGGRAPH '90; `search::clip`). Over and over: the distances of the
//! net to a line through the origin across the net's v direction, by
//! columns, are the Bernstein coefficients of a function of (u, v) that
//! D = 0 makes 0, so its zeros lie where the convex hull of the points
//! (c/3, distance) meets the axis: the u range outside that is cut away;
//! then v alike. A part that shrinks by less than a fifth is halved; a
//! part narrower than [`CONVERGED`] of its piece in both directions (or
//! whose net lies within the hit's tolerance of the ray, as where a
//! collapsed edge keeps u from narrowing) gives its centre to Newton's
//! method on D, and the hit is checked on the patch.
//!
//! Why no root is missed: a piece is passed by the bound only where no
//! root can be in it, or after the one root it can hold; in clipping, a
//! range is cut only where the convex hull of Bernstein coefficients
//! keeps from 0 a function that vanishes at every root (the convex hull
//! property of the Bernstein basis), a halving keeps both halves, and a
//! box or part whose least t lies beyond the nearest hit so far is
//! dropped only because it cannot hold a nearer one (its t lies in the
//! hull of its net's t). So every root stays in some part until that part
//! converges; Newton's method from its centre then stands within the
//! part's width of each root it holds, and the hit's t within the part's
//! span of t of the nearest (two roots in one part, a ray grazing the
//! sheet, are found as one). What can still fail, counted in
//! docs/STABILITY.md: a grazing ray (a double root, where the clips shrink
//! slowly and the halvings multiply) may run out of [`MAX_STEPS`] and
//! leave a hole; at a point where the patch has no tangent plane (a
//! collapsed edge) Newton's step is not taken and the normal is taken
//! nearby.
//!
//! The normal is exact: Pᵤ × Pᵥ at the hit's (u, v), in the local frame.
//! Everything per ray is in fixed arrays.

mod search;

use super::sweep::box_size;
use super::Near;
use crate::accel::Aabb;
use crate::types::{BoundingBox, DVec3, LocalHit, PatchShape, Ray};
use search::{Ask, Search};

/// A part converges when both its parameter ranges are narrower than this
/// share of its piece's; Newton's method then finishes the root.
pub const CONVERGED: f64 = 1e-4;

/// The most clipping steps one ray takes on one patch.
pub const MAX_STEPS: usize = 200;

/// The deepest the pieces are cut (4³ = 64 pieces at most).
pub const MAX_DEPTH: usize = 3;

/// A piece is cut while a control point stands farther than this share of
/// its box's diagonal from the bilinear sheet of its corners.
pub const FLAT: f64 = 0.02;

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

/// P(u, v), Pᵤ and Pᵥ of a net of 16 points of any kind of coordinates:
/// each row's cubic in u and its slope, then those in v.
fn eval<T>(net: &[T; 16], u: f64, v: f64) -> (T, T, T)
where
    T: Copy + Default + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T>,
{
    let ((bu, du), (bv, dv)) = (bernstein3(u), bernstein3(v));
    let (mut p, mut pu, mut pv) = (T::default(), T::default(), T::default());
    for r in 0..4 {
        let q = |c: usize| net[4 * r + c];
        let at = q(0) * bu[0] + q(1) * bu[1] + q(2) * bu[2] + q(3) * bu[3];
        let slope = q(0) * du[0] + q(1) * du[1] + q(2) * du[2] + q(3) * du[3];
        p = p + at * bv[r];
        pu = pu + slope * bv[r];
        pv = pv + at * dv[r];
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

/// The part [a, b] (0 ≤ a ≤ b ≤ 1) of a cubic Bezier curve, by de
/// Casteljau: the curve on [0, b], then its part from a/b.
fn part<T>(p: [T; 4], a: f64, b: f64) -> [T; 4]
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T>,
{
    let lerp = |x: T, y: T, s: f64| x + (y - x) * s;
    let split = |p: [T; 4], s: f64| {
        let (p01, p12, p23) = (lerp(p[0], p[1], s), lerp(p[1], p[2], s), lerp(p[2], p[3], s));
        let (p012, p123) = (lerp(p01, p12, s), lerp(p12, p23, s));
        let mid = lerp(p012, p123, s);
        ([p[0], p01, p012, mid], [mid, p123, p23, p[3]])
    };
    let l = if b < 1.0 { split(p, b).0 } else { p };
    if a <= 0.0 {
        l
    } else if b > 0.0 {
        split(l, (a / b).min(1.0)).1
    } else {
        [l[0]; 4]
    }
}

/// The two directions a net is cut in.
#[derive(Clone, Copy, PartialEq)]
enum Dir {
    U,
    V,
}

/// A net of 16 points cut to [a, b] of its range in `dir`.
fn cut<T>(net: &[T; 16], dir: Dir, a: f64, b: f64) -> [T; 16]
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T>,
{
    let mut out = *net;
    for line in 0..4 {
        let at = |k: usize| match dir {
            Dir::U => 4 * line + k,
            Dir::V => 4 * k + line,
        };
        let q = part(std::array::from_fn(|k| net[at(k)]), a, b);
        for (k, p) in q.into_iter().enumerate() {
            out[at(k)] = p;
        }
    }
    out
}

/// A piece of the patch before any ray: its control points, its ranges
/// of u and v in the whole patch, and what every ray's contraction bound
/// takes from it (`search::certified`): P, Pᵤ and Pᵥ at its centre, and
/// the bound of its second derivatives' change ([`change`]) in space,
/// which holds for the piece seen along any ray (a projection does not
/// lengthen a vector).
#[derive(Clone, Debug, PartialEq)]
struct Piece {
    net: [DVec3; 16],
    u: (f64, f64),
    v: (f64, f64),
    centre: (DVec3, DVec3, DVec3),
    change: f64,
}

impl Piece {
    fn new(net: [DVec3; 16], u: (f64, f64), v: (f64, f64)) -> Piece {
        Piece {
            centre: eval(&net, 0.5, 0.5),
            change: change(&net, DVec3::length_squared),
            net,
            u,
            v,
        }
    }
}

/// ½·√((M_uu + M_uv)² + (M_uv + M_vv)²), the M bounding a net's second
/// derivatives by its second differences (6·Δ²ᵤ, 9·ΔᵤΔᵥ, 6·Δ²ᵥ: the convex
/// hull of the Bernstein coefficients); `len2` a difference's length
/// squared. A NaN is kept (it fails every test of the bound).
fn change<T>(net: &[T; 16], len2: impl Fn(T) -> f64) -> f64
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Sub<Output = T> + std::ops::Mul<f64, Output = T>,
{
    let d = |r: usize, c: usize| net[4 * r + c];
    // The largest squares first, one root each.
    let most = |m: f64, x: f64| if x > m || x.is_nan() { x } else { m };
    let (mut uu, mut vv, mut uv) = (0.0f64, 0.0f64, 0.0f64);
    for a in 0..4 {
        for b in 0..2 {
            uu = most(uu, len2(d(a, b + 2) - d(a, b + 1) * 2.0 + d(a, b)));
            vv = most(vv, len2(d(b + 2, a) - d(b + 1, a) * 2.0 + d(b, a)));
        }
    }
    for r in 0..3 {
        for c in 0..3 {
            uv = most(uv, len2(d(r + 1, c + 1) - d(r + 1, c) - d(r, c + 1) + d(r, c)));
        }
    }
    let (uu, vv, uv) = (6.0 * uu.sqrt(), 6.0 * vv.sqrt(), 9.0 * uv.sqrt());
    0.5 * ((uu + uv) * (uu + uv) + (uv + vv) * (uv + vv)).sqrt()
}

/// A node of the pieces' quadtree: its box, and its four children (from
/// `first` on) or its piece.
#[derive(Clone, Debug, PartialEq)]
struct Node {
    bounds: Aabb,
    first: u32,
    piece: Option<u32>,
}

/// What is prepared for a patch before any ray (see the module doc): its
/// pieces in a quadtree of boxes. Made for a patch at rest once, for a
/// deforming one at each instant a ray first reaches it.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchCache {
    nodes: Vec<Node>,
    pieces: Vec<Piece>,
    /// The patch's size (its box's largest coordinate), for tolerances.
    size: f64,
}

/// The box of a net.
fn net_box(net: &[DVec3; 16]) -> Aabb {
    net.iter().fold(Aabb::EMPTY, |b, &p| Aabb {
        lo: b.lo.min(p),
        hi: b.hi.max(p),
    })
}

/// How far a net's points stand from the bilinear sheet of its corners,
/// as a share of its box's diagonal (0 for a net of no size).
fn unflatness(net: &[DVec3; 16]) -> f64 {
    let b = net_box(net);
    let size = (b.hi - b.lo).length();
    if !(size > 0.0 && size.is_finite()) {
        return 0.0;
    }
    let (p00, p03, p30, p33) = (net[0], net[3], net[12], net[15]);
    let mut most = 0.0f64;
    for r in 0..4 {
        for c in 0..4 {
            let (u, v) = (c as f64 / 3.0, r as f64 / 3.0);
            let bilinear = (p00 * (1.0 - u) + p03 * u) * (1.0 - v) + (p30 * (1.0 - u) + p33 * u) * v;
            most = most.max((net[4 * r + c] - bilinear).length());
        }
    }
    most / size
}

impl PatchCache {
    /// The pieces of `shape` (see the module doc).
    pub fn new(shape: &PatchShape) -> PatchCache {
        let mut cache = PatchCache {
            nodes: Vec::new(),
            pieces: Vec::new(),
            size: box_size(&patch_box(shape)),
        };
        cache.nodes.push(Node {
            bounds: net_box(&shape.points),
            first: 0,
            piece: None,
        });
        cache.split(0, shape.points, (0.0, 1.0), (0.0, 1.0), 0);
        cache
    }

    /// Node `at` (its box made) as a leaf of `net`, or cut in four.
    fn split(&mut self, at: usize, net: [DVec3; 16], u: (f64, f64), v: (f64, f64), depth: usize) {
        if depth == MAX_DEPTH || unflatness(&net) <= FLAT {
            self.nodes[at].piece = Some(self.pieces.len() as u32);
            self.pieces.push(Piece::new(net, u, v));
            return;
        }
        let first = self.nodes.len();
        self.nodes[at].first = first as u32;
        let half = |(a, b): (f64, f64), k: usize| if k == 0 { (a, 0.5 * (a + b)) } else { (0.5 * (a + b), b) };
        let mut kids = Vec::with_capacity(4);
        for k in 0..4 {
            let (ku, kv) = (k & 1, k >> 1);
            let across = cut(&net, Dir::U, 0.5 * ku as f64, 0.5 + 0.5 * ku as f64);
            let piece = cut(&across, Dir::V, 0.5 * kv as f64, 0.5 + 0.5 * kv as f64);
            self.nodes.push(Node {
                bounds: net_box(&piece),
                first: 0,
                piece: None,
            });
            kids.push((piece, half(u, ku), half(v, kv)));
        }
        for (k, (piece, ku, kv)) in kids.into_iter().enumerate() {
            self.split(first + k, piece, ku, kv, depth + 1);
        }
    }

    /// The number of pieces.
    pub fn pieces(&self) -> usize {
        self.pieces.len()
    }
}

/// The nearest hit of a ray with the patch beyond `tmin`, in its local
/// frame (see the module doc): `cache` its pieces (made here if `None`),
/// `reach` the radius of a sphere about the local origin holding it
/// ([`patch_reach`], or the object's `radius`). `searched` counts the
/// pieces clipped past their first test.
pub fn intersect_patch(
    shape: &PatchShape,
    cache: Option<&PatchCache>,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    searched: &mut u64,
) -> Option<LocalHit> {
    query(shape, cache, reach, ray, tmin, f64::INFINITY, false, searched)
}

/// The nearest hit beyond `tmin` (see the module doc), or with `first`
/// the first found before `tmax` (the caller's t): the shadow ray's
/// question, whose answer is whether that hit lies before `tmax`
/// ([`intersect_patch`] asks for the nearest).
#[allow(clippy::too_many_arguments)]
pub fn query(
    shape: &PatchShape,
    cache: Option<&PatchCache>,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    first: bool,
    searched: &mut u64,
) -> Option<LocalHit> {
    let near = Near::about_origin(ray, tmin, reach)?;
    let made;
    let cache = match cache {
        Some(c) => c,
        None => {
            made = PatchCache::new(shape);
            &made
        }
    };
    let ask = Ask {
        tmin: near.tmin,
        tmax,
        shift: near.shift,
        first,
    };
    let (t, u, v) = Search::new(cache, ask).run(&near.ray, searched)?;
    let (point, normal) = patch_point(shape, u, v);
    let normal = normal.unwrap_or(-near.ray.dir.normalize());
    near.back(Some(LocalHit { t, point, normal }))
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

    /// `patch_point`'s normal: Pᵤ × Pᵥ made unit where it is not 0; on a
    /// collapsed edge, the normal a step toward the middle; `None` on a
    /// patch collapsed to a point.
    #[test]
    fn normals_are_exact_and_collapsed_edges_take_the_next() {
        let bent = square(0.5);
        let (_, pu, pv) = eval(&bent.points, 0.3, 0.6);
        let exact = pu.cross(pv) / pu.cross(pv).length();
        let (_, n) = patch_point(&bent, 0.3, 0.6);
        assert!((n.unwrap() - exact).length() < 1e-14, "{n:?} against {exact}");
        // The first row drawn to one point: a flat fan in z = 0 whose edge
        // v = 0 has no Pᵤ.
        let mut fan = square(0.0);
        fan.points[..4].fill(DVec3::new(0.0, -1.0, 0.0));
        let (_, n) = patch_point(&fan, 0.3, 0.0);
        let n = n.expect("a normal from beside the edge");
        assert!((n.z.abs() - 1.0).abs() < 1e-12 && n.is_finite(), "{n}");
        let point = PatchShape {
            points: [DVec3::ONE; 16],
        };
        assert_eq!(patch_point(&point, 0.3, 0.6).1, None);
    }

    /// `change`, the bound on the second derivatives that makes Newton's
    /// root a piece's only one, is exact on z = 3u² + 2uv over the unit
    /// square (Bernstein coefficients 3·[0, 0, 1/3, 1] in u, 2·(c/3)(r/3)):
    /// |P_uu| = 6, |P_uv| = 2, P_vv = 0, so ½·√((6 + 2)² + (2 + 0)²) = √17.
    #[test]
    fn change_bounds_the_second_derivatives_exactly_on_a_quadratic() {
        let u2 = [0.0, 0.0, 1.0 / 3.0, 1.0];
        let net: [DVec3; 16] = std::array::from_fn(|k| {
            let (r, c) = ((k / 4) as f64, (k % 4) as f64);
            DVec3::new(c / 3.0, r / 3.0, 3.0 * u2[k % 4] + 2.0 * (c / 3.0) * (r / 3.0))
        });
        let m = change(&net, DVec3::length_squared);
        assert!((m - 17f64.sqrt()).abs() < 1e-12, "{m}");
        // Turned a quarter (u and v swapped), the same bound.
        let turned: [DVec3; 16] = std::array::from_fn(|k| net[4 * (k % 4) + k / 4]);
        assert!((change(&turned, DVec3::length_squared) - 17f64.sqrt()).abs() < 1e-12);
    }

    fn hit(p: &PatchShape, ray: &Ray) -> Option<LocalHit> {
        intersect_patch(p, Some(&PatchCache::new(p)), patch_reach(p), ray, 1e-9, &mut 0)
    }

    #[test]
    fn a_flat_square_is_met_where_the_plane_is() {
        let p = square(0.0);
        assert_eq!(PatchCache::new(&p).pieces(), 1, "a flat patch is one piece");
        for (x, y) in [(0.0, 0.0), (0.3, -0.7), (-0.99, 0.99), (0.5, 0.5)] {
            let ray = Ray::new(DVec3::new(x, y, 4.0), DVec3::NEG_Z);
            let h = hit(&p, &ray).unwrap();
            assert!((h.t - 4.0).abs() < 1e-12, "({x}, {y}): {}", h.t);
            assert!((h.point - DVec3::new(x, y, 0.0)).length() < 1e-12);
            assert!((h.normal.z.abs() - 1.0).abs() < 1e-12);
        }
        let ray = Ray::new(DVec3::new(1.01, 0.0, 4.0), DVec3::NEG_Z);
        assert!(hit(&p, &ray).is_none());
    }

    /// A bent patch: the hit lies on the surface, the normal is a unit
    /// vector, and no part of the sheet stands nearer on the ray; the
    /// same hits without a prepared cache.
    #[test]
    fn a_bent_patch_is_met_on_its_surface() {
        let p = square(1.5);
        let cache = PatchCache::new(&p);
        assert!(cache.pieces() > 4, "{}", cache.pieces());
        let mut hits = 0;
        for k in 0..400u64 {
            let r = |j: u64| 2.0 * crate::hash::hashed_uniform(4 * k + j) - 1.0;
            let o = DVec3::new(3.0 * r(0), 3.0 * r(1), 3.0);
            let target = DVec3::new(0.9 * r(2), 0.9 * r(3), 0.3);
            let ray = Ray::new(o, (target - o).normalize());
            let found = intersect_patch(&p, Some(&cache), patch_reach(&p), &ray, 1e-9, &mut 0);
            assert_eq!(found, intersect_patch(&p, None, patch_reach(&p), &ray, 1e-9, &mut 0));
            let Some(h) = found else {
                continue;
            };
            hits += 1;
            assert!((ray.at(h.t) - h.point).length() < 1e-9, "ray {k}");
            assert!((h.normal.length() - 1.0).abs() < 1e-12);
            // The patch is a height field over the square (x and y are
            // linear in u and v), and the ray stays above it up to the hit.
            let height = |x: f64, y: f64| eval(&p.points, (x + 1.0) / 2.0, (y + 1.0) / 2.0).0.z;
            for i in 1..2000 {
                let q = ray.at(h.t * i as f64 / 2000.0);
                if q.x.abs() < 1.0 && q.y.abs() < 1.0 {
                    assert!(q.z > height(q.x, q.y) - 1e-9, "ray {k} passed below the sheet");
                }
            }
        }
        assert!(hits > 150, "{hits}");
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
