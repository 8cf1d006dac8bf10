//! One ray's search of a patch's pieces (see the module doc of
//! [`super`]): the quadtree's boxes walked nearest first, each piece's
//! root by Newton's method where the contraction bound proves it the
//! piece's only one ([`certified`]), Bezier clipping ([`clip`], the search's
//! step) where it cannot.

use glam::DVec2;

mod clip;

use super::{change, eval, Dir, PatchCache, Piece, CONVERGED, MAX_DEPTH};
use crate::accel::BoxRay;
use crate::shapes::sweep::RESIDUAL_TOL;
use crate::types::{DVec3, Ray};
use clip::Part;

/// Newton's method stops after a step shorter than this (in a piece's
/// parameters): where it converges quadratically, as at a root the
/// contraction bound has proved simple, the next would be of the order
/// of its square, 10⁻¹⁴, and it is not taken.
const LAST_STEP: f64 = 1e-7;

/// What a query asks, in the frame of the ray near the patch (whose t is
/// the caller's less `shift`).
#[derive(Clone, Copy)]
pub(super) struct Ask {
    pub(super) tmin: f64,
    /// The caller's `tmax`: no hit whose t (the caller's) is at or past it
    /// matters.
    pub(super) tmax: f64,
    pub(super) shift: f64,
    /// Stop at the first hit before `tmax`.
    pub(super) first: bool,
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

    /// A vector as its components across the ray (along the planes'
    /// normals).
    fn across(&self, w: DVec3) -> DVec2 {
        DVec2::new(self.n1.dot(w), self.n2.dot(w))
    }

    /// A point as (distance to plane 1, distance to plane 2, ray parameter).
    fn of(&self, p: DVec3) -> DVec3 {
        let w = p - self.o;
        DVec3::new(self.n1.dot(w), self.n2.dot(w), self.d.dot(w) * self.inv)
    }
}

/// The nearest root found so far: its t, and (u, v) in the whole patch.
pub(super) type Hit = (f64, f64, f64);

/// One ray's search of one patch.
pub(super) struct Search<'a> {
    pub(super) cache: &'a PatchCache,
    pub(super) ask: Ask,
    pub(super) best: Option<Hit>,
    pub(super) steps: usize,
}

impl<'a> Search<'a> {
    /// A search of `cache`'s pieces for what `ask` asks.
    pub(super) fn new(cache: &'a PatchCache, ask: Ask) -> Search<'a> {
        Search {
            cache,
            ask,
            best: None,
            steps: 0,
        }
    }

    /// The hit the ray (near the patch) meets: the nearest, or a shadow
    /// ray's first ([`Ask::first`]).
    pub(super) fn run(mut self, ray: &Ray, searched: &mut u64) -> Option<Hit> {
        self.walk(ray, searched);
        self.best
    }

    /// Can no hit at t ≥ `t` (near frame) matter? Beyond the nearest hit
    /// so far, or at or past the caller's `tmax`, compared as the caller
    /// compares the hit it gets back (rounding is monotone: a t past the
    /// limit stays past it once `shift` is added back).
    pub(super) fn past(&self, t: f64) -> bool {
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
        // Made when the ray first reaches a piece (many reach none).
        let mut frame = None;
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
                let frame = frame.get_or_insert_with(|| Frame::new(ray));
                if self.piece(frame, &self.cache.pieces[piece as usize], searched) {
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
            for &kid in &kids[..met] {
                stack[len] = kid;
                len += 1;
            }
        }
    }

    /// Searches one piece whose box the ray meets; true when the search is
    /// done (a shadow ray's hit, or the steps spent). The contraction
    /// bound first ([`certified`]) from what the piece keeps, then
    /// from its net in the ray's frame, tighter; Bezier clipping where
    /// neither tells.
    fn piece(&mut self, frame: &Frame, piece: &Piece, searched: &mut u64) -> bool {
        *searched += 1;
        let (p, pu, pv) = piece.centre;
        let at_centre = (frame.across(p - frame.o), frame.across(pu), frame.across(pv));
        let mut told = certified(at_centre, piece.change);
        if told == Roots::Zero {
            return false;
        }
        let net = Net::of(frame, piece);
        if told == Roots::Unsure {
            told = certified(at_centre, change(&net.xy, DVec2::length_squared));
        }
        match told {
            Roots::Zero => return false,
            Roots::AtMostOne => {
                // The piece's one root: nearer than the nearest so far, or
                // nothing in this piece is.
                if let Some(hit) = self.root(&net, piece, at_centre).filter(|h| !self.past(h.0)) {
                    self.best = Some(hit);
                    return self.ask.first;
                }
                return false;
            }
            Roots::Unsure => {}
        }
        let whole = Part {
            net: std::array::from_fn(|k| net.xy[k].extend(net.t[k])),
            u: (0.0, 1.0),
            v: (0.0, 1.0),
        };
        let (t_lo, t_hi) = whole.t_range();
        if t_hi <= self.ask.tmin || self.past(t_lo) {
            return false;
        }
        if whole.clip(Dir::U).is_none() || whole.clip(Dir::V).is_none() {
            return false;
        }
        self.clip(whole, &net, piece, 0)
    }

    /// The root of a piece that has at most one ([`certified`]): Newton's
    /// method from its centre, where D (its net `net` in the ray's frame)
    /// and its derivatives are `at_centre`; the hit if it ends on the piece
    /// ([`Search::hit_at`]) with D within rounding of 0.
    fn root(&self, net: &Net, piece: &Piece, at_centre: (DVec2, DVec2, DVec2)) -> Option<Hit> {
        let (u, v, p) = newton(&net.xy, (0.5, 0.5), at_centre);
        let slack = 1e-9;
        let inside = (-slack..=1.0 + slack).contains(&u) && (-slack..=1.0 + slack).contains(&v);
        (inside && p.length() <= RESIDUAL_TOL * self.cache.size).then(|| self.hit_at(piece, net, u, v))?
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
pub(super) struct Net {
    pub(super) xy: [DVec2; 16],
    pub(super) t: [f64; 16],
}

impl Net {
    fn of(frame: &Frame, piece: &Piece) -> Net {
        // Made whole, not zeroed and then written (a call to `memset` for
        // each piece a ray reaches).
        let q = piece.net.map(|p| frame.of(p));
        Net {
            xy: q.map(DVec3::truncate),
            t: q.map(|q| q.z),
        }
    }
}

/// What the contraction bound tells of a piece where D (its net in the
/// ray's frame) and its derivatives at the centre x₀ = (½, ½) are
/// `at_centre` and `change` bounds its second derivatives' change
/// ([`change`]): [`Roots::AtMostOne`] when D is one-to-one on the piece
/// and its root may lie in it, [`Roots::Zero`] where none can,
/// [`Roots::Unsure`] when that cannot be told (then the piece is
/// clipped).
///
/// With J₀ the Jacobian at x₀, for a root y in the piece
/// y − x₁ = −J₀⁻¹∫(J(z) − J₀)(y − x₀), x₁ = x₀ − J₀⁻¹D(x₀), so
/// ‖y − x₁‖ ≤ q‖y − x₀‖ with q the most ‖J₀⁻¹(J(z) − J₀)‖ takes on the
/// piece: every root lies within q·√½ of x₁ (none, if that disk misses the
/// piece), and with q < 1 there is at most one (two roots y, y′ would give
/// ‖y − y′‖ ≤ q‖y − y′‖). q ≤ ‖J₀⁻¹‖·`change`, ½ the most |z − x₀| takes
/// in each parameter. A bound made in space holds for the net seen along
/// any ray; one made in the ray's frame is tighter.
fn certified(at_centre: (DVec2, DVec2, DVec2), change: f64) -> Roots {
    let (p0, ju, jv) = at_centre;
    let det = ju.perp_dot(jv);
    // ‖J₀⁻¹‖² = 1/σ_min(J₀)², from the Frobenius norm and the determinant;
    // q² = change²/σ_min² (squares: no roots but the one σ_min needs).
    let f2 = ju.length_squared() + jv.length_squared();
    let smallest2 = 0.5 * (f2 - (f2 * f2 - 4.0 * det * det).max(0.0).sqrt());
    let change2 = change * change;
    // q < 1: change² < σ², a NaN unsure.
    if change2.partial_cmp(&smallest2) != Some(std::cmp::Ordering::Less) || det == 0.0 {
        return Roots::Unsure;
    }
    let x1 = DVec2::new(0.5 - p0.perp_dot(jv) / det, 0.5 - ju.perp_dot(p0) / det);
    let outside2 = (x1 - x1.clamp(DVec2::ZERO, DVec2::ONE)).length_squared();
    // outside > q·√½.
    if 2.0 * outside2 * smallest2 > change2 {
        Roots::Zero
    } else {
        Roots::AtMostOne
    }
}

/// What [`certified`] tells of a piece's roots.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Roots {
    Unsure,
    Zero,
    AtMostOne,
}

/// Newton's method on D, the net `xy`, from `start` = (u, v) where D and
/// its derivatives are `at`: each step kept while |D| falls, none after
/// one shorter than [`LAST_STEP`] (most roots take three or four; a
/// grazing ray's double root, where the steps halve the error, up to
/// sixteen); the (u, v) it ends at and D there.
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
        if q.length_squared() >= p.length_squared() || q.is_nan() {
            break;
        }
        (u, v, p, pu, pv) = (nu, nv, q, qu, qv);
        if du.abs() + dv.abs() < LAST_STEP {
            break;
        }
    }
    (u, v, p)
}
