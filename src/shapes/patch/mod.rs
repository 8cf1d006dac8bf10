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
//! In a piece whose box it meets, the intersection is Bezier clipping
//! (Nishita, Sederberg & Kakimoto 1990, "Ray tracing trimmed rational
//! surface patches", SIGGRAPH '90). The ray is the meeting line of two
//! planes through it; the control points' signed distances to them,
//! (x, y), make a planar Bezier patch D(u, v) whose zeros are the ray's
//! hits, and each control point's ray parameter t rides along (the piece
//! in the ray's frame). Then, over and over: the distances of the net to a
//! line through the origin across the net's v direction, by columns, are
//! the Bernstein coefficients of a function of (u, v) that D = 0 makes 0,
//! so its zeros lie where the convex hull of the points (c/3, distance)
//! meets the axis: the u range outside that is cut away; then v alike. A
//! part that shrinks by less than a fifth is halved; a part narrower than
//! [`CONVERGED`] of its piece in both directions (or whose net lies within
//! the hit's tolerance of the ray, as where a collapsed edge keeps u from
//! narrowing) gives its centre to Newton's method on D, and the hit is
//! checked on the patch.
//!
//! Why no root is missed: a range is cut only where the convex hull of
//! Bernstein coefficients keeps from 0 a function that vanishes at every
//! root (the convex hull property of the Bernstein basis), a halving keeps
//! both halves, and a box or part whose least t lies beyond the nearest
//! hit so far is dropped only because it cannot hold a nearer one (its t
//! lies in the hull of its net's t). So every root stays in some part
//! until that part converges; Newton's method from its centre then stands
//! within the part's width of each root it holds, and the hit's t within
//! the part's span of t of the nearest (two roots in one part, a ray
//! grazing the sheet, are found as one). What can still fail, counted in
//! docs/STABILITY.md: a grazing ray (a double root, where the clips shrink
//! slowly and the halvings multiply) may run out of [`MAX_STEPS`] and
//! leave a hole; at a point where the patch has no tangent plane (a
//! collapsed edge) Newton's step is not taken and the normal is taken
//! nearby.
//!
//! The normal is exact: Pᵤ × Pᵥ at the hit's (u, v), in the local frame.
//! Everything per ray is in fixed arrays.

use glam::DVec2;

use super::sweep::{box_size, RESIDUAL_TOL};
use super::Near;
use crate::accel::{Aabb, BoxRay};
use crate::types::{BoundingBox, DVec3, LocalHit, PatchShape, Ray};

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

/// A clip that keeps more than this share of a range halves the part.
const SLOW: f64 = 0.8;

/// The deepest a part is halved.
const MAX_HALVINGS: u32 = 40;

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

/// A piece of the patch before any ray: its control points, its box, and
/// its ranges of u and v in the whole patch.
#[derive(Clone, Debug, PartialEq)]
struct Piece {
    net: [DVec3; 16],
    u: (f64, f64),
    v: (f64, f64),
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
            self.pieces.push(Piece { net, u, v });
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

/// What a query asks, in the frame of the ray near the patch (whose t is
/// the caller's less `shift`).
#[derive(Clone, Copy)]
struct Ask {
    tmin: f64,
    /// The caller's `tmax`: no hit whose t (the caller's) is at or past it
    /// matters.
    tmax: f64,
    shift: f64,
    /// Stop at the first hit before `tmax`.
    first: bool,
}

/// The ray's frame: two unit normals across the ray (from the axis it is
/// least along), and its parameter.
struct Frame {
    o: DVec3,
    n1: DVec3,
    n2: DVec3,
    d: DVec3,
    inv: f64,
}

impl Frame {
    fn new(ray: &Ray) -> Frame {
        let dn = ray.dir.normalize();
        let a = dn.abs();
        let axis = if a.x <= a.y && a.x <= a.z {
            DVec3::X
        } else if a.y <= a.z {
            DVec3::Y
        } else {
            DVec3::Z
        };
        let n1 = dn.cross(axis).normalize();
        Frame {
            o: ray.origin,
            n1,
            n2: dn.cross(n1),
            d: ray.dir,
            inv: 1.0 / ray.dir.length_squared(),
        }
    }

    /// A point as (distance to plane 1, distance to plane 2, ray parameter).
    fn of(&self, p: DVec3) -> DVec3 {
        let w = p - self.o;
        DVec3::new(self.n1.dot(w), self.n2.dot(w), self.d.dot(w) * self.inv)
    }
}

/// The nearest root found so far: its t, and (u, v) in the whole patch.
type Hit = (f64, f64, f64);

/// One ray's search of one patch.
struct Search<'a> {
    cache: &'a PatchCache,
    ask: Ask,
    best: Option<Hit>,
    steps: usize,
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
    let mut search = Search {
        cache,
        ask: Ask {
            tmin: near.tmin,
            tmax,
            shift: near.shift,
            first,
        },
        best: None,
        steps: 0,
    };
    search.walk(&near.ray, searched);
    let (t, u, v) = search.best?;
    let (point, normal) = patch_point(shape, u, v);
    let normal = normal.unwrap_or(-near.ray.dir.normalize());
    near.back(Some(LocalHit { t, point, normal }))
}

impl Search<'_> {
    /// Can no hit at t ≥ `t` (near frame) matter? Beyond the nearest hit
    /// so far, or at or past the caller's `tmax`, compared as the caller
    /// compares the hit it gets back (rounding is monotone: a t past the
    /// limit stays past it once `shift` is added back).
    fn past(&self, t: f64) -> bool {
        self.best.is_some_and(|b| t >= b.0) || t + self.ask.shift >= self.ask.tmax
    }

    /// The far end of the span the boxes are tested over: the nearest hit
    /// so far (the caller's `tmax` is asked of each entry by
    /// [`Search::past`]).
    fn reach(&self) -> f64 {
        self.best.map_or(f64::INFINITY, |b| b.0)
    }

    /// The quadtree's boxes the ray meets, nearest first, and the pieces
    /// in them clipped; stops when a box lies beyond the nearest hit, or
    /// at the first hit for a shadow ray.
    fn walk(&mut self, ray: &Ray, searched: &mut u64) {
        let boxes = BoxRay::new(ray);
        let frame = Frame::new(ray);
        let nodes = &self.cache.nodes;
        let Some((enter, _)) = boxes.span(&nodes[0].bounds, self.ask.tmin, self.reach()) else {
            return;
        };
        // At most three children a level wait while the nearest is taken.
        let mut stack = [(0u32, 0.0f64); 3 * MAX_DEPTH + 1];
        stack[0] = (0, enter);
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let (at, enter) = stack[len];
            if self.past(enter) {
                continue;
            }
            let node = &nodes[at as usize];
            if let Some(piece) = node.piece {
                if self.piece(&frame, &self.cache.pieces[piece as usize], searched) {
                    return;
                }
                continue;
            }
            let mut kids: [(u32, f64); 4] = [(0, 0.0); 4];
            let mut met = 0;
            for k in 0..4 {
                let child = node.first + k;
                if let Some((e, _)) = boxes.span(&nodes[child as usize].bounds, self.ask.tmin, self.reach()) {
                    kids[met] = (child, e);
                    met += 1;
                }
            }
            // Farthest pushed first, so the nearest comes off next.
            kids[..met].sort_unstable_by(|a, b| b.1.total_cmp(&a.1));
            stack[len..len + met].copy_from_slice(&kids[..met]);
            len += met;
        }
    }

    /// Clips one piece; true when the search is done (a shadow ray's hit,
    /// or the steps spent).
    fn piece(&mut self, frame: &Frame, piece: &Piece, searched: &mut u64) -> bool {
        let mut net = Net {
            xy: [DVec2::ZERO; 16],
            t: [0.0; 16],
        };
        // (Plain comparisons: `f64::min` and `max`, which pass NaN over,
        // were a tenth of the patches' time; a NaN t here fails both tests
        // below as it would theirs.)
        let (mut t_lo, mut t_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, p) in piece.net.iter().enumerate() {
            let q = frame.of(*p);
            net.xy[k] = q.truncate();
            net.t[k] = q.z;
            t_lo = if q.z < t_lo { q.z } else { t_lo };
            t_hi = if q.z > t_hi { q.z } else { t_hi };
        }
        if t_hi <= self.ask.tmin || self.past(t_lo) {
            return false;
        }
        *searched += 1;
        if let Some(root) = self.certified(&net, piece) {
            // The piece's one root: nearer than the nearest so far, or
            // nothing in this piece is.
            if let Some(hit) = root.filter(|h| !self.past(h.0)) {
                self.best = Some(hit);
                return self.ask.first;
            }
            return false;
        }
        let whole = Part {
            net: std::array::from_fn(|k| net.xy[k].extend(net.t[k])),
            u: (0.0, 1.0),
            v: (0.0, 1.0),
        };
        if whole.clip(Dir::U).is_none() || whole.clip(Dir::V).is_none() {
            return false;
        }
        self.clip(whole, &net, piece, 0)
    }

    /// The piece's root by Newton's method from its centre, where that is
    /// sure to be its only one: `Some(root)` when D (its net `net` in the
    /// ray's frame) is one-to-one on the piece and Newton's method ends on
    /// a root in it, or where no root can be in it (`Some(None)`, also
    /// when the one root lies at or before `tmin`); `None` when that
    /// cannot be told (then the piece is clipped).
    ///
    /// With J₀ the Jacobian at the centre x₀, for a root y in the piece
    /// y − x₁ = −J₀⁻¹∫(J(z) − J₀)(y − x₀), x₁ = x₀ − J₀⁻¹D(x₀) the first
    /// Newton step, so ‖y − x₁‖ ≤ q‖y − x₀‖ with q the most
    /// ‖J₀⁻¹(J(z) − J₀)‖ takes on the piece: every root lies within q·√½
    /// of x₁ (none, if that disk misses the piece), and with q < 1 there is
    /// at most one (two roots y, y′ would give ‖y − y′‖ ≤ q‖y − y′‖).
    /// q ≤ ‖J₀⁻¹‖·½·√((M_uu + M_uv)² + (M_uv + M_vv)²), the M bounding the
    /// second derivatives by the net's second differences (6·Δ²ᵤ, 9·ΔᵤΔᵥ,
    /// 6·Δ²ᵥ, the convex hull of the Bernstein coefficients) and ½ the most
    /// |z − x₀| takes in each parameter.
    fn certified(&self, net: &Net, piece: &Piece) -> Option<Option<Hit>> {
        let d = |r: usize, c: usize| net.xy[4 * r + c];
        // The largest squares first, one root each (a NaN is kept: it
        // fails the test of q below).
        let most = |m: f64, x: f64| if x > m || x.is_nan() { x } else { m };
        let (mut uu, mut vv, mut uv) = (0.0f64, 0.0f64, 0.0f64);
        for a in 0..4 {
            for b in 0..2 {
                uu = most(uu, (d(a, b + 2) - 2.0 * d(a, b + 1) + d(a, b)).length_squared());
                vv = most(vv, (d(b + 2, a) - 2.0 * d(b + 1, a) + d(b, a)).length_squared());
            }
        }
        for r in 0..3 {
            for c in 0..3 {
                uv = most(
                    uv,
                    (d(r + 1, c + 1) - d(r + 1, c) - d(r, c + 1) + d(r, c)).length_squared(),
                );
            }
        }
        let (uu, vv, uv) = (6.0 * uu.sqrt(), 6.0 * vv.sqrt(), 9.0 * uv.sqrt());
        let change = 0.5 * ((uu + uv) * (uu + uv) + (uv + vv) * (uv + vv)).sqrt();
        let start = eval(&net.xy, 0.5, 0.5);
        let (p0, ju, jv) = start;
        let det = ju.perp_dot(jv);
        // ‖J₀⁻¹‖ = 1/σ_min(J₀), from the Frobenius norm and the determinant.
        let f2 = ju.length_squared() + jv.length_squared();
        let smallest2 = 0.5 * (f2 - (f2 * f2 - 4.0 * det * det).max(0.0).sqrt());
        let q = change / smallest2.sqrt();
        if q >= 1.0 || q.is_nan() || det == 0.0 {
            return None;
        }
        let x1 = DVec2::new(0.5 - p0.perp_dot(jv) / det, 0.5 - ju.perp_dot(p0) / det);
        let outside = (x1 - x1.clamp(DVec2::ZERO, DVec2::ONE)).length();
        if outside > q * std::f64::consts::FRAC_1_SQRT_2 {
            return Some(None);
        }
        let (u, v, p) = newton(&net.xy, (0.5, 0.5), start);
        let slack = 1e-9;
        let inside = (-slack..=1.0 + slack).contains(&u) && (-slack..=1.0 + slack).contains(&v);
        (inside && p.length() <= RESIDUAL_TOL * self.cache.size).then(|| self.hit_at(piece, net, u, v))
    }

    /// Bezier clipping of `part` of the piece whose net in the ray's frame
    /// is `net` (see the module doc); true when the search is done.
    fn clip(&mut self, mut part: Part, net: &Net, piece: &Piece, halvings: u32) -> bool {
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

    /// A converged part's root: Newton's method on D (the piece's net
    /// `net` in the ray's frame) from the part's centre; the hit if it ends
    /// within the part's width (at least [`CONVERGED`]) of it
    /// ([`Search::hit_at`]).
    fn finish(&self, net: &Net, piece: &Piece, part: &Part) -> Option<Hit> {
        let centre = (0.5 * (part.u.0 + part.u.1), 0.5 * (part.v.0 + part.v.1));
        let (u, v, p) = newton(&net.xy, centre, eval(&net.xy, centre.0, centre.1));
        let within = |x: f64, (a, b): (f64, f64)| {
            let margin = (b - a).max(CONVERGED);
            x >= a - margin && x <= b + margin
        };
        (within(u, part.u) && within(v, part.v) && p.length() <= RESIDUAL_TOL * self.cache.size)
            .then(|| self.hit_at(piece, net, u, v))
            .flatten()
    }

    /// The hit (t, u, v in the whole patch) at (u, v) of `piece`, its net
    /// in the ray's frame `net` (D vanishing there): if it is on the patch
    /// and beyond `tmin`.
    fn hit_at(&self, piece: &Piece, net: &Net, u: f64, v: f64) -> Option<Hit> {
        let global = |x: f64, (a, b): (f64, f64)| a + x * (b - a);
        let (gu, gv) = (global(u, piece.u), global(v, piece.v));
        let on = |x: f64| (-1e-9..=1.0 + 1e-9).contains(&x);
        let t = eval(&net.t, u, v).0;
        (on(gu) && on(gv) && t > self.ask.tmin).then_some((t, gu.clamp(0.0, 1.0), gv.clamp(0.0, 1.0)))
    }
}

/// A piece's net in the ray's frame: each control point's distances to
/// the two planes through the ray, and its ray parameter.
struct Net {
    xy: [DVec2; 16],
    t: [f64; 16],
}

/// Newton's method on D, the net `xy`, from `start` = (u, v) where D and
/// its derivatives are `at`: each step kept while |D| falls, none after
/// one at rounding's size (most roots take two or three; a grazing ray's
/// double root, where the steps halve the error, up to sixteen); the
/// (u, v) it ends at and D there.
fn newton(xy: &[DVec2; 16], start: (f64, f64), at: (DVec2, DVec2, DVec2)) -> (f64, f64, DVec2) {
    let ((mut u, mut v), (mut p, mut pu, mut pv)) = (start, at);
    for _ in 0..16 {
        let det = pu.perp_dot(pv);
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let (du, dv) = (p.perp_dot(pv) / det, pu.perp_dot(p) / det);
        let (nu, nv) = (u - du, v - dv);
        let (q, qu, qv) = eval(xy, nu, nv);
        if q.length() >= p.length() || q.is_nan() {
            break;
        }
        (u, v, p, pu, pv) = (nu, nv, q, qu, qv);
        if du.abs() + dv.abs() < 1e-13 {
            break;
        }
    }
    (u, v, p)
}

/// A part of a piece in the ray's frame: its net (x, y, t) and its ranges
/// of the piece's own u and v.
#[derive(Clone, Copy)]
struct Part {
    net: [DVec3; 16],
    u: (f64, f64),
    v: (f64, f64),
}

impl Part {
    /// The part cut to [a, b] of its own range in `dir`.
    fn cut(&self, dir: Dir, a: f64, b: f64) -> Part {
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
    fn t_range(&self) -> (f64, f64) {
        self.net.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        })
    }

    /// The part of the part's own range in `dir` where a zero of D can
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
