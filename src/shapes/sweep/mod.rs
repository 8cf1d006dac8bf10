//! The sweep objects of §2.3: a closed contour of cubic segments (uniform
//! cubic B-spline or composite cubic Bezier, §2.2) swept by translation,
//! by a conic sweep (translation while the contour scales linearly) or by
//! rotation, and the ray's intersection with them.
//!
//! Reconstructed: the thesis prints the procedures this driver calls
//! (`spline`, `laguerre`, `outrectp`, unit `proc`) but not the driver. It
//! follows van Wijk 1984 ("Ray tracing objects defined by sweeping planar
//! cubic splines", ACM TOG 3(3)) and the thesis's §2.3, §2.5 and §3.3:
//! per-object and per-segment bounding tests (`outrectp` for rotation),
//! one polynomial in the curve parameter s per segment (degree 3 for
//! translation and conic sweeps, 6 for rotation), its roots by
//! [`laguerre`] or the port's [`real_roots`] (`Options::solver`), the hits
//! from the roots, and the end caps of translation and conic sweeps.
//!
//! The caps: van Wijk decides whether a cap point is inside the contour by
//! the parity of the side roots before the cap's ray parameter, which is
//! what `roottesting` (make the count even) and `sorting` (the position of
//! `tmax`) are for. With `laguerre`, which misses roots (docs/
//! laguerre_misses.md), a wrong parity turns a strip of the cap's plane
//! outside the contour solid: a hit that is not on the object. The port
//! asks [`point_in_contour`] instead, so every hit it reports lies on the
//! surface whatever the solver; a root `laguerre` misses leaves a hole,
//! never a false surface. `roottesting` and `sorting` are ported and
//! tested as printed, and not called here.
//!
//! Local frame: the sweep axis is local z. Translation and conic sweeps
//! put the contour (x = U, y = V) in the plane z = 0 and sweep it to
//! z = `length`, the conic one scaled by k(z) = 1 + (scale − 1) z/length.
//! A rotation sweep revolves the contour (U the radius, V the height)
//! about local z.
//!
//! Everything per ray is allocation-free (fixed arrays).
//!
//! The files: this one the driver ([`Sweep`]) and what the kinds share
//! (the solvers' call, the Bernstein pre-test, the tolerances); `probe`
//! one ray's search of one object (the nearest hit so far, the candidate
//! segments, the hit finished); `extrusion` translation and conic sweeps;
//! `revolve` rotation sweeps; `contour` the contour's own geometry (the
//! cap test, orientation, tangents); `prepare` the coefficients and boxes
//! from the control points; `cache` what is kept of an object whose
//! contour keeps its shape (`cap_grid` its cap test's grid, `bounds` what
//! a ray takes from its box).

mod bounds;
mod cache;
mod cap_grid;
mod contour;
mod extrusion;
mod prepare;
mod probe;
mod revolve;

pub use cache::{prepare_caches, SweepCache};
pub use contour::{orientation, point_in_contour, signed_area};
pub use prepare::{fill_segments, prepare_sweeps, segment_points};

use super::Near;
use crate::options::{Fidelity, Options, Solver};
use crate::proc::sweep::{laguerre, laguerre_together, Root, LAGUERRE_ROOTS};
use crate::robust::{bernstein, bernstein_unit_of, newton_until, polygon_crossing, real_roots};
use crate::types::{BoundingBox, Coeff, DVec3, LocalHit, PrimitiveClass, Ray, SweepShape, MAXSEGMENTS};
use bounds::QueryBounds;
use cap_grid::CapGrid;
use extrusion::extrusion;
use probe::{Probe, Query, Want};
use revolve::revolve;

/// Roots are kept in [−this, 1 + this], so that a ray through a joint is
/// not lost to rounding on both sides of it (it may be found twice: the
/// nearest hit is the same).
pub(super) const JOINT_SLACK: f64 = 1e-9;

/// A root whose hit point is farther than this (relative to the object's
/// size) from the surface is rejected.
pub(super) const RESIDUAL_TOL: f64 = 1e-9;

/// A ray component below this fraction of the ray's length counts as 0
/// (the special cases: parallel or perpendicular to an axis).
pub(super) const PARALLEL_TOL: f64 = 1e-12;

/// x(s) = ((a s + b) s + c) s + d.
/// √(a² + b²). `f64::hypot` guards against overflow at a cost that shows in
/// the profile of every sweep render; scene coordinates are far from the
/// range where a² could overflow.
pub(super) fn norm2(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// Ascending coefficients [d, c, b, a].
pub(super) fn asc(c: &Coeff) -> [f64; 4] {
    [c.d, c.c, c.b, c.a]
}

/// p(x) and p′(x) of a polynomial of degree ≤ `n` ≤ 6 (ascending
/// coefficients; those above n are 0).
pub(super) fn horner(n: usize, p: &[f64; 7], x: f64) -> (f64, f64) {
    let n = n.min(6);
    let (mut f, mut df) = (p[n], 0.0);
    for k in (0..n).rev() {
        df = df * x + f;
        f = f * x + p[k];
    }
    (f, df)
}

/// Newton steps on the degree-`n` polynomial p from s, kept only while
/// |p| falls.
pub(super) fn polish(n: usize, p: &[f64; 7], mut s: f64) -> f64 {
    let (mut f, mut df) = horner(n, p, s);
    for _ in 0..4 {
        if f == 0.0 || df == 0.0 {
            break;
        }
        let next = s - f / df;
        let (nf, ndf) = horner(n, p, next);
        if nf.is_nan() || nf.abs() >= f.abs() {
            break;
        }
        (s, f, df) = (next, nf, ndf);
    }
    s
}

/// The roots in [−JOINT_SLACK, 1 + JOINT_SLACK] of one segment's
/// polynomial.
pub(super) struct Found {
    pub(super) count: usize,
    pub(super) s: [f64; 6],
}

/// The segment's polynomial of degree `n` solved by the chosen method.
/// A cubic is asked of its Bernstein count first ([`unit_crossings`]):
/// none there is none for either solver; one is taken at once by the
/// robust solver (DEVIATIONS D30, D31), and given to `laguerre` without
/// its pre-test [`may_have_root`], which a count of one always passes (p
/// keeps the signs of b₀ and bₙ on the slack, which differ).
///
/// The cubic's count is made where the call is (most segments end
/// there); the rest of the work is [`solve_further`].
///
/// `searched` counts the polynomials searched ([`solve_further`]).
#[inline(always)]
pub(super) fn solve(n: usize, a: &[f64; 7], opts: &Options, searched: &mut u64) -> Found {
    let mut crosses = false;
    if n == 3 {
        let b = bernstein_unit_of::<3>(a);
        match unit_crossings(3, &b) {
            Crossings::None => return Found { count: 0, s: [0.0; 6] },
            Crossings::One if opts.solver == Solver::Robust => {
                let mut out = Found { count: 1, s: [0.0; 6] };
                out.s[0] = one_crossing(n, a, &b, SIDE_SETTLE);
                return out;
            }
            Crossings::One => crosses = true,
            Crossings::Unknown => {}
        }
    }
    solve_further(n, a, crosses, opts, searched)
}

/// [`solve`] past the cubic's count: `laguerre` behind its Bernstein
/// pre-test (unless the polynomial is known to `cross` [−δ, 1 + δ]), or
/// the robust solver. Each polynomial past the pre-tests (which settle
/// most of them) is counted in `searched`: what makes one ray dearer than
/// another in a scene of sweeps, which the adaptive sampler weighs. A ray
/// is traced on one thread, so its count is the same for any number of
/// threads.
#[inline(never)]
fn solve_further(n: usize, a: &[f64; 7], crosses: bool, opts: &Options, searched: &mut u64) -> Found {
    let mut out = Found { count: 0, s: [0.0; 6] };
    let (lo, hi) = (-JOINT_SLACK, 1.0 + JOINT_SLACK);
    if opts.solver == Solver::Laguerre && !crosses && !may_have_root(n, a, lo, hi) {
        return out;
    }
    *searched += 1;
    match opts.solver {
        // The thesis's `laguerre`, its starts taken together: the same
        // roots ([`laguerre_together`]).
        Solver::Laguerre if opts.fidelity == Fidelity::Thesis && matches!(n, 3 | 4 | 6) => {
            out.count = match n {
                3 => laguerre_together::<3>(a, hi, lo, &mut out.s),
                4 => laguerre_together::<4>(a, hi, lo, &mut out.s),
                _ => laguerre_together::<6>(a, hi, lo, &mut out.s),
            };
        }
        Solver::Laguerre => {
            let mut root = [Root::default(); LAGUERRE_ROOTS];
            let total = laguerre(n, a, hi, lo, &mut root, opts.fidelity);
            for r in &root[..total.min(6)] {
                out.s[out.count] = r.a;
                out.count += 1;
            }
        }
        Solver::Robust => {
            let r = real_roots(n, a, lo, hi);
            for &s in r.roots() {
                out.s[out.count] = s;
                out.count += 1;
            }
        }
    }
    out
}

/// Can the degree-`n` polynomial `a` (ascending coefficients) vanish in
/// [lo, hi]? Not when its Bernstein coefficients on that interval
/// ([`bernstein`]) are all of one strict sign: the polynomial lies in their
/// convex hull. A test before `laguerre` that spares the solve for most
/// segments a ray's line passes near without crossing; where it answers
/// "no" there is no root for a solver to find, so no image changes
/// (DEVIATIONS D18). The robust solver makes the same count itself.
pub(super) fn may_have_root(n: usize, a: &[f64; 7], lo: f64, hi: f64) -> bool {
    let n = n.min(6);
    let (b, tiny) = bernstein(n, a, lo, hi);
    if tiny.is_nan() || tiny <= 0.0 || tiny.is_infinite() {
        return true; // zero, or not finite: let the solver decide
    }
    let (mut pos, mut neg) = (false, false);
    for &bk in &b[..=n] {
        if bk > tiny {
            pos = true;
        } else if bk < -tiny {
            neg = true;
        } else {
            return true;
        }
        if pos && neg {
            return true;
        }
    }
    false
}

/// What [`unit_crossings`] knows of a cubic's roots on a segment.
pub(super) enum Crossings {
    /// No root in [−δ, 1 + δ].
    None,
    /// Exactly one, simple, inside (0, 1).
    One,
    /// Not known: the solver must say.
    Unknown,
}

/// What the Bernstein coefficients on [0, 1] `b[..=n]`
/// ([`bernstein_unit`](crate::robust::bernstein_unit), no shift: the
/// cheap half of [`bernstein`]) tell of the roots in [−δ, 1 + δ]
/// (δ = [`JOINT_SLACK`]) when each is beyond 10⁻⁷ of the largest. On the
/// slack p strays from its values on [0, 1] by at most δ·max|p′| ≤
/// 2nδ·max|bₖ|, far less than that margin, so p keeps the signs of
/// p(0) = b₀ and p(1) = bₙ there. Of one sign: no root (the finer tests,
/// `may_have_root` and the robust solver's count, would find none either):
/// the most common case, a segment whose box the ray's line crosses and
/// whose curve it does not, decided first. One change of sign: exactly one
/// root, simple, inside (0, 1) (Descartes' rule in the Bernstein basis
/// bounds the roots by the changes, with their parity), which the robust
/// solver takes at once ([`one_crossing`]). Else nothing is known. Asked of
/// the cubics only: a sextic has passed `outrectp` first, after which the
/// test rejects too few to pay.
#[inline(always)]
pub(super) fn unit_crossings(n: usize, b: &[f64; 7]) -> Crossings {
    let margin = 1e-7 * b[..=n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(margin > 0.0 && finite(margin)) || b[..=n].iter().any(|bk| bk.abs() <= margin) {
        return Crossings::Unknown;
    }
    match (1..=n).filter(|&k| (b[k] < 0.0) != (b[k - 1] < 0.0)).count() {
        0 => Crossings::None,
        1 => Crossings::One,
        _ => Crossings::Unknown,
    }
}

/// The one root in (0, 1) of p (degree `n`) when [`unit_crossings`] says
/// [`Crossings::One`] of its Bernstein coefficients `b` on [0, 1]: the
/// robust solver's bracketed Newton from where the control polygon
/// crosses 0, as [`real_roots`] would take it on [−δ, 1 + δ], but without
/// counting again; stopped after a Newton step of at most `settle`
/// ([`newton_until`]; 0: at rounding).
// Out of line, as the compiler left it before the phases of `extrusion`
// were methods: inlined there (with `newton_until`), it took fig5_7 3 %
// more time (interleaved A/B, robust solver).
#[inline(never)]
pub(super) fn one_crossing(n: usize, a: &[f64; 7], b: &[f64; 7], settle: f64) -> f64 {
    newton_until(a, n, 0.0, 1.0, b[0], polygon_crossing(n, b), settle)
}

/// The step after which a side root is taken ([`one_crossing`]): the
/// polish on the hit's polynomial that follows brings it to rounding.
const SIDE_SETTLE: f64 = 1e-8;

/// Is `x` neither infinite nor NaN? x·0 is ±0 for a finite x and NaN
/// otherwise: `f64::is_finite`'s answer in a product and a comparison,
/// where this target compiles `is_finite` (and `abs() < ∞`, and `x > 0 &&`
/// it) to an integer classification of a dozen instructions, on every ray.
#[inline(always)]
pub(super) fn finite(x: f64) -> bool {
    x * 0.0 == 0.0
}

/// Is every coefficient negligible beside `scale`? (A segment that lies
/// on the ray's projected line, or a polynomial that vanishes everywhere.)
pub(super) fn negligible(p: &[f64; 7], scale: f64) -> bool {
    p.iter().all(|c| c.abs() <= 1e-13 * scale)
}

/// Does the ray meet the box [lo, hi] at some t > tmin?
#[inline(always)]
pub(super) fn ray_meets_box(ray: &Ray, tmin: f64, lo: DVec3, hi: DVec3) -> bool {
    let (mut t0, mut t1) = (tmin, f64::INFINITY);
    for k in 0..3 {
        let (o, d) = (ray.origin[k], ray.dir[k]);
        if d == 0.0 {
            if o < lo[k] || o > hi[k] {
                return false;
            }
        } else {
            let (a, b) = ((lo[k] - o) / d, (hi[k] - o) / d);
            let (a, b) = if a < b { (a, b) } else { (b, a) };
            t0 = t0.max(a);
            t1 = t1.min(b);
            // t0 only grows and t1 only shrinks: a miss now is a miss.
            if t0 > t1 {
                return false;
            }
        }
    }
    t0 <= t1
}

/// The largest coordinate of the box: the object's size for relative
/// tolerances.
pub(super) fn box_size(b: &BoundingBox) -> f64 {
    [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// A sweep object as the driver meets it, in its local frame: its class,
/// its shape (the object's own, or its contour of the moment when it
/// deforms) and the cache made with that shape ([`SweepCache`]; `None`
/// for a contour of the moment, whose caps are then solved and whose
/// bounds are made per ray).
#[derive(Clone, Copy, Debug)]
pub struct Sweep<'a> {
    pub class: PrimitiveClass,
    pub shape: &'a SweepShape,
    pub cache: Option<&'a SweepCache>,
}

impl Sweep<'_> {
    /// The intersection of a ray with the sweep object: the nearest hit
    /// with t > `tmin`, with its unit outward normal, in the object's local
    /// frame. `searched` counts the polynomials searched past the solvers'
    /// pre-tests.
    ///
    /// Reconstructed from van Wijk 1984 and the thesis's §2.3, §2.5, §3.3
    /// (see the module doc). The sweep's `u`, `v` and `bbox` must be filled
    /// ([`prepare_sweeps`], or the key-frame code for in-between shapes),
    /// and each `u[i]`, `v[i]` must bound its segment with `min`, `max`.
    ///
    /// Special cases, each on its own path:
    /// - translation, a ray parallel to the axis: its projection is a
    ///   point, inside the contour or not; only the caps can be hit;
    /// - conic, a ray through the apex: the same, with the point the ray's
    ///   central projection from the apex; a ray in the plane of the apex
    ///   (where the contour shrinks to a point) can only touch the apex;
    /// - rotation, a ray along the axis (constant radius): U(s) = r, a
    ///   cubic; a ray perpendicular to the axis (constant height):
    ///   V(s) = z, a cubic, then the ray's two crossings of the circle of
    ///   radius U(s).
    ///
    /// The ray is taken [`Near`] the object's box first, so the
    /// polynomials' coefficients are of the object's size whatever the
    /// eye's distance.
    ///
    /// The segments the ray's line may meet are tried nearest first, by a
    /// lower bound on their hits' t (translation: from the segment's box
    /// along the ray's projection; rotation: from its height range and, in
    /// thesis fidelity, where the ray runs within its greatest radius,
    /// D90), and
    /// the rest skipped once the bound passes the nearest hit so far: the
    /// same nearest hit as trying them all (of two at one t, the lower
    /// segment's). In thesis fidelity, where the boxes hold their segments,
    /// a translation sweep's segments whose boxes put every hit before
    /// `tmin` or outside the span of the ray between the caps' planes are
    /// not tried at all (D32), nor a rotation sweep's that the ray leaves
    /// by `tmin` or never comes within the radius of (D90). The caps of a
    /// contour that keeps its shape are answered by its cache's cap grid
    /// where no segment passes.
    ///
    /// Each root gives its hit from the better conditioned equation, is
    /// polished, and is rejected unless the hit lies on the surface
    /// (within 1e-9 of the object's size); so a spurious root of either
    /// solver (the listing's `laguerre` can return one, erratum 7) never
    /// becomes a hit.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, tmin: f64, opts: &Options, searched: &mut u64) -> Option<LocalHit> {
        self.query(ray, tmin, opts, Want::Nearest, searched)
    }

    /// Does the ray meet the sweep object at some t with `tmin` < t <
    /// `tmax`? The shadow ray's question (a light `tmax` away): the answer
    /// of [`Sweep::intersect`] (its nearest hit lies before `tmax`),
    /// reached by stopping at the first hit before `tmax` instead of the
    /// nearest.
    #[inline(always)]
    pub fn blocks(&self, ray: &Ray, tmin: f64, tmax: f64, opts: &Options, searched: &mut u64) -> bool {
        self.query(ray, tmin, opts, Want::Before(tmax), searched)
            .is_some_and(|h| h.t < tmax)
    }

    #[inline(always)]
    fn query(&self, ray: &Ray, tmin: f64, opts: &Options, want: Want, searched: &mut u64) -> Option<LocalHit> {
        let (class, sweep) = (self.class, self.shape);
        let n = sweep.segment.min(sweep.u.len()).min(sweep.v.len()).min(MAXSEGMENTS);
        // `is_finite`, not [`finite`]'s products: those the compiler
        // computes ahead of `Posed::intersect`'s dispatch, where this is
        // inlined, for every shape's ray (10 instructions a sample of
        // fig5_1, which has no sweep; 8–9 more here on fig5_6–5_8).
        if n == 0 || !ray.origin.is_finite() || !ray.dir.is_finite() || ray.dir == DVec3::ZERO || tmin.is_nan() {
            return None;
        }
        let (u, v) = (&sweep.u[..n], &sweep.v[..n]);
        let computed;
        let bounds = match self.cache.and_then(|c| c.bounds.as_ref()) {
            Some(b) if b.holds(class, &sweep.bbox) => b,
            _ => {
                // Borrowed where it was made: moved out of the `Option`,
                // it was copied (a `memcpy` of its fields just written).
                computed = QueryBounds::of(class, sweep, u, v);
                computed.as_ref()?
            }
        };
        let (size, lo, hi) = (bounds.size, bounds.lo, bounds.hi);
        // Every polynomial below is formed from the ray near the object.
        let near = Near::of(ray, tmin, bounds.centre, bounds.radius2);
        if bounds.boxed && !ray_meets_box(&near.ray, near.tmin, lo, hi) {
            return None;
        }
        let probe = Probe {
            sweep,
            u,
            v,
            grid: self.cache.and_then(|c| c.cap_grid.as_ref()),
            size,
            ray: near.ray,
            tmin: near.tmin,
            opts,
            query: Query {
                want,
                shift: near.shift,
            },
            best: None,
            searched,
        };
        near.back(match class {
            PrimitiveClass::Rotation => revolve(probe),
            _ => extrusion(probe, class == PrimitiveClass::Conic),
        })
    }
}

/// `n` points round the origin at radii `r_even` and `r_odd` in turn, at
/// equal angles from +x: the unit tests' stars and rings.
#[cfg(test)]
fn star_points(n: usize, r_even: f64, r_odd: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / n as f64;
            let r = if k % 2 == 0 { r_even } else { r_odd };
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// A translation sweep of `length` over the contour through `points`,
/// filled as `prepare_sweeps` fills it, with its own box: the unit tests'
/// contours.
#[cfg(test)]
fn translation_sweep(points: Vec<[f64; 2]>, curve: crate::types::CurveKind, length: f64) -> SweepShape {
    let mut sw = SweepShape {
        orientt: crate::types::Axis::Z,
        curve,
        points,
        segment: 0,
        u: vec![],
        v: vec![],
        length,
        scale: 1.0,
        bbox: BoundingBox::default(),
        orientation: 0.0,
    };
    let sbox = fill_segments(PrimitiveClass::Translation, &mut sw);
    sw.bbox = prepare::own_box(PrimitiveClass::Translation, &sw, &sbox);
    sw
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::hashed_uniform;
    use crate::robust::poly_from_roots;

    /// `solve_further` with `laguerre` gives `laguerre`'s roots, to the bit
    /// and in its order, in either fidelity: `listing`'s through `laguerre`
    /// itself, whose stale x2 can pass from one start to the next (the
    /// polynomial 0, where `listing` finds the stale 0 and `thesis` keeps
    /// each start), `thesis`'s through `laguerre_together` for n = 3, 4, 6.
    #[test]
    fn solve_further_gives_laguerres_roots_in_either_fidelity() {
        let (lo, hi) = (-JOINT_SLACK, 1.0 + JOINT_SLACK);
        let mut polynomials = vec![[0.0; 7]];
        for k in 0..300u64 {
            let r = |j: u64| hashed_uniform(8 * k + j);
            let roots: Vec<f64> = (0..6).map(|j| 1.6 * r(j) - 0.3).collect();
            let mut a = [0.0; 7];
            let n = [3, 4, 6][(k % 3) as usize];
            a[..=n].copy_from_slice(&poly_from_roots(&roots[..n], 0.5 + r(7))[..=n]);
            polynomials.push(a);
        }
        for fidelity in [Fidelity::Listing, Fidelity::Thesis] {
            let opts = Options {
                fidelity,
                solver: Solver::Laguerre,
                ..Options::default()
            };
            for a in &polynomials {
                for n in [3, 4, 6] {
                    let found = solve_further(n, a, true, &opts, &mut 0);
                    let mut root = [Root::default(); LAGUERRE_ROOTS];
                    let total = laguerre(n, a, hi, lo, &mut root, fidelity).min(6);
                    let want: Vec<u64> = root[..total].iter().map(|r| r.a.to_bits()).collect();
                    let got: Vec<u64> = found.s[..found.count].iter().map(|s| s.to_bits()).collect();
                    assert_eq!(got, want, "{fidelity:?}, n = {n}: {a:?}");
                }
            }
            let zero = solve_further(4, &[0.0; 7], true, &opts, &mut 0);
            let expected: &[f64] = match fidelity {
                Fidelity::Listing => &[0.0],
                Fidelity::Thesis => &[0.245, 0.49, 0.735, 0.98],
            };
            assert_eq!(zero.count, expected.len(), "{fidelity:?}");
            for (s, e) in zero.s.iter().zip(expected) {
                assert!((s - e).abs() < 1e-12, "{fidelity:?}: {s} against {e}");
            }
        }
    }

    /// What the Bernstein count says of a cubic is what the robust solver
    /// finds on [−δ, 1 + δ]: no root, or the one root, to 1e-12; on cubics
    /// built from three roots anywhere in [−1, 2] (a third of them near the
    /// ends, inside and outside the slack) at scales from 10⁻⁶ to 10⁶.
    #[test]
    fn the_bernstein_count_agrees_with_the_robust_solver() {
        let (mut none, mut one) = (0, 0);
        for k in 0..20_000u64 {
            let r = |j: u64| hashed_uniform(8 * k + j);
            let end = |x: f64, j: u64| match (r(j) * 6.0) as u32 {
                0 => (r(j + 3) - 0.5) * 4e-9,
                1 => 1.0 + (r(j + 3) - 0.5) * 4e-9,
                _ => x,
            };
            let roots = [end(3.0 * r(0) - 1.0, 5), end(3.0 * r(1) - 1.0, 6), 3.0 * r(2) - 1.0];
            let scale = 10f64.powf(12.0 * r(4) - 6.0) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let p = poly_from_roots(&roots, scale);
            let b = bernstein_unit_of::<3>(&p);
            let found = real_roots(3, &p, -JOINT_SLACK, 1.0 + JOINT_SLACK);
            match unit_crossings(3, &b) {
                Crossings::None => {
                    none += 1;
                    assert_eq!(found.count, 0, "{roots:?}: {:?}", found.roots());
                }
                Crossings::One => {
                    one += 1;
                    assert_eq!(found.count, 1, "{roots:?}: {:?}", found.roots());
                    // Why `solve` gives it to `laguerre` without the pre-test.
                    assert!(may_have_root(3, &p, -JOINT_SLACK, 1.0 + JOINT_SLACK), "{roots:?}");
                    let s = one_crossing(3, &p, &b, 0.0);
                    let settled = one_crossing(3, &p, &b, SIDE_SETTLE);
                    assert!((settled - s).abs() < 1e-11, "{roots:?}: {settled} against {s}");
                    assert!(s > 0.0 && s < 1.0, "{roots:?}: {s}");
                    assert!((s - found.x[0]).abs() < 1e-12, "{roots:?}: {s} against {}", found.x[0]);
                }
                Crossings::Unknown => {}
            }
        }
        assert!(
            none > 2000 && one > 2000,
            "both answers are asked: {none} none, {one} one"
        );
    }

    /// `finite` answers as `is_finite`, at the edges too.
    #[test]
    fn finite_is_is_finite() {
        let edges = [
            0.0,
            -0.0,
            1.0,
            -2.5,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for x in edges {
            assert_eq!(finite(x), x.is_finite(), "{x}");
        }
    }

    /// `solve` counts the polynomials the solvers search, and only those:
    /// not a cubic the Bernstein count settles, nor one `laguerre`'s
    /// pre-test turns away; one each for the rest, with either solver.
    #[test]
    fn searched_counts_the_searches() {
        let opts = |solver| Options {
            solver,
            ..Options::default()
        };
        let searches = |p: &[f64; 7], n: usize, solver| {
            let mut searched = 0;
            solve(n, p, &opts(solver), &mut searched);
            searched
        };
        // No root near [0, 1]: the count settles it for both solvers.
        let far = poly_from_roots(&[3.0, 4.0, 5.0], 1.0);
        assert_eq!(searches(&far, 3, Solver::Laguerre), 0);
        assert_eq!(searches(&far, 3, Solver::Robust), 0);
        // One crossing: `laguerre` searches, the robust solver takes it
        // from the count.
        let one = poly_from_roots(&[0.5, 3.0, -2.0], 1.0);
        assert_eq!(searches(&one, 3, Solver::Laguerre), 1);
        assert_eq!(searches(&one, 3, Solver::Robust), 0);
        // Three roots in [0, 1]: the count cannot tell; both search.
        let three = poly_from_roots(&[0.2, 0.5, 0.8], 1.0);
        assert_eq!(searches(&three, 3, Solver::Laguerre), 1);
        assert_eq!(searches(&three, 3, Solver::Robust), 1);
        // A sextic with no root near [0, 1]: `laguerre`'s pre-test turns
        // it away; the robust solver searches it.
        let mut sextic = [0.0; 7];
        sextic[0] = 1.0;
        sextic[6] = 1.0;
        assert_eq!(searches(&sextic, 6, Solver::Laguerre), 0);
        assert_eq!(searches(&sextic, 6, Solver::Robust), 1);
    }

    /// `laguerre`'s roots are its own whatever the count says: where the
    /// count is one, the robust solver takes the one-crossing root, and
    /// `laguerre` still gives what it finds (the thesis's method, misses
    /// and all).
    #[test]
    fn only_the_robust_solver_takes_the_one_crossing() {
        let opts = |solver| Options {
            solver,
            ..Options::default()
        };
        let mut checked = 0;
        for k in 0..2000u64 {
            let r = |j: u64| hashed_uniform(8 * k + j);
            let p = poly_from_roots(&[r(0), 1.5 + r(1), -0.5 - r(2)], 1.0 + r(3));
            let b = bernstein_unit_of::<3>(&p);
            if !matches!(unit_crossings(3, &b), Crossings::One) {
                continue;
            }
            checked += 1;
            let robust = solve(3, &p, &opts(Solver::Robust), &mut 0);
            assert_eq!(robust.count, 1);
            assert_eq!(robust.s[0], one_crossing(3, &p, &b, SIDE_SETTLE));
            let (lo, hi) = (-JOINT_SLACK, 1.0 + JOINT_SLACK);
            let mut root = [Root::default(); LAGUERRE_ROOTS];
            let total = laguerre(3, &p, hi, lo, &mut root, opts(Solver::Laguerre).fidelity);
            let own: Vec<f64> = root[..total.min(6)].iter().map(|r| r.a).collect();
            let lag = solve(3, &p, &opts(Solver::Laguerre), &mut 0);
            assert_eq!(&lag.s[..lag.count], &own[..], "cubic {k}");
        }
        assert!(checked > 500, "{checked}");
    }

    /// A contour's orientation kept with its segments, or computed when it
    /// is not (0), gives the same hits; the filling of `prepare_sweeps`
    /// (`fill_segments`) keeps −1 for a clockwise contour and +1 for a
    /// counter-clockwise one.
    #[test]
    fn kept_and_computed_orientation_give_the_same_hits() {
        use crate::types::CurveKind;
        let ring = star_points(8, 1.0, 0.6);
        for (turn, want) in [(false, 1.0), (true, -1.0)] {
            let mut points = ring.clone();
            if turn {
                points.reverse();
            }
            let sw = translation_sweep(points, CurveKind::Bspline, 1.0);
            let cache = SweepCache::new(PrimitiveClass::Translation, &sw);
            let kept = Sweep {
                class: PrimitiveClass::Translation,
                shape: &sw,
                cache: cache.as_ref(),
            };
            assert_eq!(sw.orientation, want);
            let unknown_shape = SweepShape {
                orientation: 0.0,
                ..sw.clone()
            };
            let unknown = Sweep {
                shape: &unknown_shape,
                cache: None,
                ..kept
            };
            let mut hits = 0;
            for k in 0..400u64 {
                let r = |j: u64| 2.0 * hashed_uniform(8 * k + j) - 1.0;
                let o = DVec3::new(3.0 * r(0), 3.0 * r(1), 0.5 + 2.0 * r(2));
                let ray = Ray::new(o, (DVec3::new(0.8 * r(3), 0.8 * r(4), 0.5) - o).normalize());
                for solver in [Solver::Laguerre, Solver::Robust] {
                    let opts = Options {
                        solver,
                        ..Options::default()
                    };
                    let a = kept.intersect(&ray, 1e-9, &opts, &mut 0);
                    let b = unknown.intersect(&ray, 1e-9, &opts, &mut 0);
                    assert_eq!(a, b, "ray {k}");
                    hits += a.is_some() as usize;
                }
            }
            assert!(hits > 200, "{hits}");
        }
    }
}
