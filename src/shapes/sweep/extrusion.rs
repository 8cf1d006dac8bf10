//! Translation and conic sweeps: one cubic a segment from the ray's
//! central projection into the contour's plane, and the end caps.

use super::contour::{inside_contour, tangent};
use super::probe::{Best, Candidates, Probe, CAP};
use super::{asc, finite, norm2, PARALLEL_TOL, RESIDUAL_TOL};
use crate::types::{DVec3, LocalHit, MAXSEGMENTS};

/// Translation and conic sweeps.
///
/// The conic contour at height z is k(z)·(U, V), k(z) = 1 + κz,
/// κ = (scale − 1)/length. Along the ray o + t d, k is linear in t:
/// k(t) = k0 + k1 t with k0 = 1 + κ o_z, k1 = κ d_z. The ray meets the
/// surface where o_x + t d_x = k(t) U(s) and o_y + t d_y = k(t) V(s).
/// Dividing by k — the central projection from the apex, where k = 0 —
/// maps the ray onto a straight line of the contour's plane, so t can be
/// eliminated: each equation is linear in t,
///   t (d_x − k1 U) = k0 U − o_x,   t (d_y − k1 V) = k0 V − o_y,
/// and their cross-multiplied difference cancels every product U V:
///   α U(s) + β V(s) + γ = 0,
///   α = k0 d_y − k1 o_y,  β = k1 o_x − k0 d_x,  γ = o_y d_x − o_x d_y,
/// a cubic in s. With κ = 0 it is the translation sweep's line
/// d_y (U − o_x) − d_x (V − o_y) = 0. t then comes from the two linear
/// equations by least squares.
///
/// α = β = 0 (then γ = 0 too) when the line degenerates to a point: the
/// ray runs through the apex (for translation, parallel to the axis).
///
/// A translation sweep's side hit at contour point X has
/// t = (X − o)·d / |d_xy|² (x and y only), so a segment's box bounds its
/// hits' t from below: the segments are tried in that order.
pub(super) fn extrusion(mut probe: Probe, conic: bool) -> Option<LocalHit> {
    Extrusion::new(&probe, conic)?.search(&mut probe);
    probe.finish()
}

/// What one ray gives a translation or conic sweep's phases (see
/// [`extrusion`]): the ray's numbers, the sweep's κ, and the line
/// α U + β V + γ = 0 of the ray's projection.
// The phases are compiled into `extrusion`, as the closures they were
// written as before: one function, its numbers kept in registers.
#[derive(Clone, Copy)]
struct Extrusion {
    conic: bool,
    len: f64,
    o: DVec3,
    d: DVec3,
    dn: f64,
    kappa: f64,
    k0: f64,
    k1: f64,
    alpha: f64,
    beta: f64,
    gamma: f64,
    nrm: f64,
    /// The scale of the side polynomial's coefficients.
    fscale: f64,
}

impl Extrusion {
    /// `None` for a sweep of no length, or a conic one of no finite scale:
    /// nothing to meet.
    #[inline(always)]
    fn new(p: &Probe, conic: bool) -> Option<Extrusion> {
        let (sw, size) = (p.sweep, p.size);
        let len = sw.length;
        if !(len > 0.0 && finite(len)) || (conic && !finite(sw.scale)) {
            return None;
        }
        let (o, d) = (p.ray.origin, p.ray.dir);
        let kappa = if conic { (sw.scale - 1.0) / len } else { 0.0 };
        let (k0, k1) = (1.0 + kappa * o.z, kappa * d.z);
        let alpha = k0 * d.y - k1 * o.y;
        let beta = k1 * o.x - k0 * d.x;
        let gamma = o.y * d.x - o.x * d.y;
        let nrm = norm2(alpha, beta);
        Some(Extrusion {
            conic,
            len,
            o,
            d,
            dn: d.length(),
            kappa,
            k0,
            k1,
            alpha,
            beta,
            gamma,
            nrm,
            fscale: nrm * size + gamma.abs(),
        })
    }

    /// The phases in turn, each leaving the nearest hit so far in `p`; a
    /// phase that finds an answer at once ends the search.
    #[inline(always)]
    fn search(&self, p: &mut Probe) {
        let d = self.d;
        // A ray in the plane of the apex: the contour is a point there.
        if self.conic && d.z.abs() <= PARALLEL_TOL * self.dn && self.k0.abs() <= PARALLEL_TOL {
            return self.apex(p);
        }
        // The ray's projection is a point: only the caps (and an apex).
        let oxy = norm2(self.o.x, self.o.y);
        if self.nrm <= PARALLEL_TOL * (self.k0.abs() * self.dn + self.k1.abs() * oxy) {
            return self.caps_only(p);
        }
        // A conic sweep whose segments' boxes bound their hits: its own
        // order (D69, D91).
        if self.conic && p.boxes_hold() && !p.counted() {
            if let Some(order) = self.conic_order(p) {
                let found = order.candidates(self, p);
                return self.with_caps(p, |p| order.sides(self, p, found));
            }
        }
        // Filled where it stands: returned, its arrays would be copied.
        let mut candidates = Candidates::new();
        self.candidates(p, &mut candidates);
        self.with_caps(p, |p| self.sides(p, &candidates));
    }

    /// The caps around the sides (`sides`, true when a hit is an answer at
    /// once), where the ray's point lies inside the (scaled) contour. The
    /// near cap is tried first: the ray reaches no side before it (the
    /// sides lie between the caps' planes), so when it is hit it is the
    /// nearest hit but for a side at the rim, and the sides beyond it are
    /// skipped. Whatever the order, the hit kept is the least (t, segment).
    #[inline(always)]
    fn with_caps(&self, p: &mut Probe, sides: impl FnOnce(&mut Probe) -> bool) {
        let caps: &[(f64, f64)] = match self.d.z {
            z if z > 0.0 => &[(0.0, -1.0), (self.len, 1.0)],
            z if z < 0.0 => &[(self.len, 1.0), (0.0, -1.0)],
            _ => &[],
        };
        if let Some(&(zc, nz)) = caps.first() {
            if self.cap(p, zc, nz) {
                return;
            }
        }
        if sides(p) {
            return;
        }
        // The far cap, if it is nearer than what the sides gave.
        if let Some(&(zc, nz)) = caps.get(1) {
            self.cap(p, zc, nz);
        }
    }

    /// A ray in the plane of the apex: only the apex, if the sweep reaches
    /// it.
    fn apex(&self, p: &mut Probe) {
        let (o, d) = (self.o, self.d);
        if self.kappa == 0.0 {
            return;
        }
        let z = -1.0 / self.kappa;
        if !(0.0..=self.len).contains(&z) {
            return;
        }
        let apex = DVec3::new(0.0, 0.0, z);
        let t = (apex - o).dot(d) / (self.dn * self.dn);
        let miss = (o + d * t - apex).length();
        if miss <= RESIDUAL_TOL * p.size && p.closer(t, CAP) {
            p.keep(t, DVec3::Z, CAP);
        }
    }

    /// A ray whose projection is a point: a cap is hit where that point
    /// lies inside the contour (or the cap is the apex).
    fn caps_only(&self, p: &mut Probe) {
        let (o, d) = (self.o, self.d);
        if d.z == 0.0 {
            return;
        }
        let t0 = -o.z / d.z;
        let (px, py) = (o.x + t0 * d.x, o.y + t0 * d.y);
        let inside = inside_contour(p.grid, p.sweep, p.u, p.v, px, py);
        for (zc, nz) in [(0.0, -1.0), (self.len, 1.0)] {
            let t = (zc - o.z) / d.z;
            let at_apex = self.conic && p.sweep.scale == 0.0 && zc == self.len;
            if (inside || at_apex) && p.closer(t, CAP) {
                p.best = Some(Best {
                    t,
                    normal: DVec3::new(0.0, 0.0, nz),
                    segment: CAP,
                });
            }
        }
    }

    /// The segments the ray's projection may meet, nearest first.
    #[inline(always)]
    fn candidates(&self, p: &Probe, candidates: &mut Candidates) {
        let (o, d, size) = (self.o, self.d, p.size);
        let dxy2 = d.x * d.x + d.y * d.y;
        // Slack on a segment's lower bound: its points may stand 1e-9 of
        // the size outside its box (the joint slack), rounding far less.
        let t_pad = 1e-6 * size / dxy2.sqrt();
        // A bound needs no exact quotient (its slack is t_pad): a product.
        let per_dxy2 = 1.0 / dxy2;
        let slab = self.between_caps(p);
        let boxes_hold = p.boxes_hold();
        let gpad = 1e-12 * self.fscale;
        // The box's corners where α X + β Y is least and most: rounding
        // keeps a product's order, so α·min ≤ α·max when α > 0 (the lesser
        // of the two products, as a `min` of both would pick), and the
        // choice is the ray's, made once instead of per segment.
        let (a_pos, b_pos) = (self.alpha > 0.0, self.beta > 0.0);
        // A conic sweep's span (D69) is taken by `ConicOrder` where it is
        // known; here it is not.
        let span = match (boxes_hold, self.conic) {
            (true, false) => self.span(p, slab),
            _ => None,
        };
        for (i, (cu, cv)) in p.u.iter().zip(p.v).enumerate() {
            if let Some(span) = &span {
                // The four sides at once (`|`, not `||`): one branch, not four.
                if (cu.max < span[0]) | (cu.min > span[1]) | (cv.max < span[2]) | (cv.min > span[3]) {
                    continue;
                }
            }
            // The segment's box against the line α X + β Y + γ = 0.
            let (x_lo, x_hi) = if a_pos { (cu.min, cu.max) } else { (cu.max, cu.min) };
            let (y_lo, y_hi) = if b_pos { (cv.min, cv.max) } else { (cv.max, cv.min) };
            let gmin = self.gamma + self.alpha * x_lo + self.beta * y_lo;
            let gmax = self.gamma + self.alpha * x_hi + self.beta * y_hi;
            if gmin > gpad || gmax < -gpad {
                continue;
            }
            let t_lo = if self.conic {
                f64::NEG_INFINITY
            } else {
                let x = if d.x > 0.0 { cu.min } else { cu.max };
                let y = if d.y > 0.0 { cv.min } else { cv.max };
                let t_lo = ((x - o.x) * d.x + (y - o.y) * d.y) * per_dxy2 - t_pad;
                // The box's far corner bounds the hits' t from above: a
                // segment whose hits all lie at or before tmin, or outside
                // the span of t where the ray is between the caps, has none
                // to keep (D32).
                let x = if d.x > 0.0 { cu.max } else { cu.min };
                let y = if d.y > 0.0 { cv.max } else { cv.min };
                let t_hi = ((x - o.x) * d.x + (y - o.y) * d.y) * per_dxy2 + t_pad;
                if boxes_hold && (t_hi < slab.0 || t_lo > slab.1) {
                    continue;
                }
                t_lo
            };
            candidates.push(t_lo, i);
        }
    }

    /// The t where a side hit may lie: beyond tmin, and where the ray's z
    /// is within the sides' (the hits keep 10⁻¹² of the size beyond the
    /// caps; a thousand times that here, far above rounding).
    #[inline(always)]
    fn between_caps(&self, p: &Probe) -> (f64, f64) {
        let (o, d) = (self.o, self.d);
        let zpad = 1e-9 * p.size;
        let (za, zb) = if d.z == 0.0 {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            let (a, b) = ((-zpad - o.z) / d.z, (self.len + zpad - o.z) / d.z);
            // Of finite numbers over one that is not 0: no NaN, so the
            // lesser by a comparison (`f64::min`'s care for NaN costs more).
            if a < b {
                (a, b)
            } else {
                (b, a)
            }
        };
        (if za > p.tmin { za } else { p.tmin }, zb)
    }

    /// Where the ray runs between the caps' planes (`slab`), its projection
    /// is the piece of the line from A to B: a segment whose box keeps away
    /// from that piece's box, padded here (a thousand times the slack of a
    /// segment's bound on t), has no hit to keep (D32). `None` where the
    /// piece is not finite.
    #[inline(always)]
    fn span(&self, p: &Probe, slab: (f64, f64)) -> Option<[f64; 4]> {
        let (o, d) = (self.o, self.d);
        (finite(slab.0) & finite(slab.1)).then(|| {
            let (ax, ay) = (o.x + slab.0 * d.x, o.y + slab.0 * d.y);
            let (bx, by) = (o.x + slab.1 * d.x, o.y + slab.1 * d.y);
            let pad = 1e-6 * p.size;
            [ax.min(bx) - pad, ax.max(bx) + pad, ay.min(by) - pad, ay.max(by) + pad]
        })
    }

    /// [`Extrusion::span`] for a conic sweep: where the ray runs between
    /// the caps' planes, its central projection from the apex into the
    /// contour's plane, (x, y)/k, is the piece of a line from A to B (the
    /// projections at the two ends) when k stays above 0 there (the apex
    /// plane not between the caps): a segment whose box keeps away from
    /// that piece's box has no hit to keep (D69). Padded as the
    /// translation sweep's, over the least k (a hit's contour point stands
    /// within its residual over k of the projection), which pad it gives
    /// too. `None` where k reaches 0 between the caps or the piece is not
    /// finite.
    #[inline(always)]
    fn conic_span(&self, p: &Probe, slab: (f64, f64)) -> Option<([f64; 4], f64)> {
        let (o, d) = (self.o, self.d);
        let k_at = |t: f64| self.k0 + self.k1 * t;
        let (ka, kb) = (k_at(slab.0), k_at(slab.1));
        // The lesser and the greater by a comparison: past the test below
        // the numbers are finite, k above 0, so none is NaN (`f64::min`'s
        // care for NaN costs more).
        let order = |a: f64, b: f64| if a < b { (a, b) } else { (b, a) };
        let least = order(ka, kb).0;
        if !(least > 1e-6 && finite(slab.0) & finite(slab.1)) {
            return None;
        }
        let (ax, ay) = ((o.x + slab.0 * d.x) / ka, (o.y + slab.0 * d.y) / ka);
        let (bx, by) = ((o.x + slab.1 * d.x) / kb, (o.y + slab.1 * d.y) / kb);
        let pad = 1e-6 * p.size / least;
        let ((x0, x1), (y0, y1)) = (order(ax, bx), order(ay, by));
        let span = [x0 - pad, x1 + pad, y0 - pad, y1 + pad];
        span.iter().all(|&v| finite(v)).then_some((span, pad))
    }

    /// The order of a conic sweep's segments where its span is known
    /// ([`Extrusion::conic_span`]); `None` where it is not.
    #[inline(always)]
    fn conic_order(&self, p: &Probe) -> Option<ConicOrder> {
        let (span, pad) = self.conic_span(p, self.between_caps(p))?;
        let (o, d) = (self.o, self.d);
        let (wx, wy) = (-self.beta, self.alpha);
        Some(ConicOrder {
            span,
            wx,
            wy,
            a: wx * o.x + wy * o.y,
            b: wx * d.x + wy * d.y,
            // A hit's contour point stands within 10⁻⁹ of the size of its
            // segment's box, and its projection within its residual over k
            // of the point: a thousand times both (the span's pad the
            // second), along w.
            pad: self.nrm * (1e-6 * p.size + pad),
            gpad: 1e-12 * self.fscale,
        })
    }

    /// The cap in the plane z = `zc` (outward normal z = `nz`), kept where
    /// the ray's point there lies inside the (scaled) contour and is
    /// nearer than the hit so far; true when it is an answer at once.
    #[inline(always)]
    fn cap(&self, p: &mut Probe, zc: f64, nz: f64) -> bool {
        let (o, d) = (self.o, self.d);
        let k = 1.0 + self.kappa * zc;
        if k == 0.0 {
            return false; // the cap is the apex: a ray through it took the path above
        }
        let t = (zc - o.z) / d.z;
        if !p.closer(t, CAP) || p.query.past(t, &None) {
            return false;
        }
        let at = o + d * t;
        // A translation sweep's k is 1: x / 1 is x, without the division.
        let (x, y) = if self.conic { (at.x / k, at.y / k) } else { (at.x, at.y) };
        // The box holds the contour (at z = 0, where a conic's is
        // unscaled). Outside it the contour test answers no (every segment
        // is skipped, or crossed an even number of times): asked only
        // inside it.
        let cbox = &p.sweep.bbox;
        let boxed = cbox.xmin < cbox.xmax && cbox.ymin < cbox.ymax;
        let pad = 1e-9 * p.size;
        if (boxed && (x < cbox.xmin - pad || x > cbox.xmax + pad || y < cbox.ymin - pad || y > cbox.ymax + pad))
            || !inside_contour(p.grid, p.sweep, p.u, p.v, x, y)
        {
            return false;
        }
        p.keep(t, DVec3::new(0.0, 0.0, nz), CAP)
    }

    /// The sides: each candidate segment's cubic, nearest first, until no
    /// hit beyond can matter; true when a hit is an answer at once.
    #[inline(always)]
    fn sides(&self, p: &mut Probe, candidates: &Candidates) -> bool {
        for (t_lo, i) in candidates.iter() {
            if p.past(t_lo) {
                break;
            }
            if self.segment(p, i) {
                return true;
            }
        }
        false
    }

    /// Segment i's cubic α U + β V + γ solved, each root's hit tried
    /// ([`Extrusion::side`]); true when a hit is an answer at once.
    #[inline(always)]
    fn segment(&self, p: &mut Probe, i: usize) -> bool {
        let (pu, pv) = (asc(&p.u[i]), asc(&p.v[i]));
        let mut f = [0.0; 7];
        for k in 0..4 {
            f[k] = self.alpha * pu[k] + self.beta * pv[k];
        }
        f[0] += self.gamma;
        p.roots(3, &f, self.fscale, |p, s| self.side(p, i, s))
    }

    /// The hit of root s of segment i's cubic, kept if it lies on the
    /// surface between the caps and is the nearest so far; true when it is
    /// an answer at once.
    #[inline(always)]
    fn side(&self, p: &mut Probe, i: usize, s: f64) -> bool {
        let (o, d, k0, k1) = (self.o, self.d, self.k0, self.k1);
        let (cu, cv) = (&p.u[i], &p.v[i]);
        let (uu, vv) = (cu.value(s), cv.value(s));
        let (ex, ey) = (d.x - k1 * uu, d.y - k1 * vv);
        let den = ex * ex + ey * ey;
        if den.is_nan() || den <= 1e-24 * self.dn * self.dn {
            return false; // the ray runs along the generator through this point
        }
        let t = (ex * (k0 * uu - o.x) + ey * (k0 * vv - o.y)) / den;
        let at = o + d * t;
        let k = 1.0 + self.kappa * at.z;
        let residual = norm2(at.x - k * uu, at.y - k * vv);
        let ztol = 1e-12 * p.size;
        if residual <= RESIDUAL_TOL * p.size && at.z >= -ztol && at.z <= self.len + ztol && p.closer(t, i) {
            let (tu, tv) = tangent(cu, cv, s, p.size);
            let normal = DVec3::new(tv, -tu, self.kappa * (tu * vv - tv * uu)) * k.signum();
            return p.keep(t, normal, i);
        }
        false
    }
}

// A conic sweep's candidates are kept as bits of a word.
const _: () = assert!(MAXSEGMENTS <= u64::BITS as usize);

/// A conic sweep's segments in the order of the ray's central projection
/// (D91). Where the ray runs between the caps' planes, k stays above 0
/// and its projection P(t) = (x, y)/k moves along the line
/// α X + β Y + γ = 0 in the direction w = (−β, α): λ(t) = w·P(t) =
/// (a + b t)/(k0 + k1 t) grows with t (dλ/dt = |w|²/k²). A segment's box
/// bounds λ at its hits from below (its corner least along w), so the
/// segments are tried by that bound and the rest skipped once it passes
/// λ at the nearest hit so far: the same nearest hit as trying them all
/// (D69's candidates, in segment order), as the translation sweep's t
/// bound does (D32).
struct ConicOrder {
    /// The box of the piece of the line where the ray is between the caps
    /// (D69).
    span: [f64; 4],
    wx: f64,
    wy: f64,
    /// λ's numerator a + b t.
    a: f64,
    b: f64,
    /// Slack on a segment's bound on λ.
    pad: f64,
    /// Slack on the line's side of a box.
    gpad: f64,
}

impl ConicOrder {
    /// The segments whose boxes meet the piece of the line between the
    /// caps (D69), as bits.
    #[inline(always)]
    fn candidates(&self, x: &Extrusion, p: &Probe) -> u64 {
        let span = &self.span;
        // The box's corners where α X + β Y is least and most, as in
        // `Extrusion::candidates`.
        let (a_pos, b_pos) = (x.alpha > 0.0, x.beta > 0.0);
        let mut found = 0u64;
        for (i, (cu, cv)) in p.u.iter().zip(p.v).enumerate() {
            // The four sides at once (`|`, not `||`): one branch, not four.
            if (cu.max < span[0]) | (cu.min > span[1]) | (cv.max < span[2]) | (cv.min > span[3]) {
                continue;
            }
            let (x_lo, x_hi) = if a_pos { (cu.min, cu.max) } else { (cu.max, cu.min) };
            let (y_lo, y_hi) = if b_pos { (cv.min, cv.max) } else { (cv.max, cv.min) };
            let gmin = x.gamma + x.alpha * x_lo + x.beta * y_lo;
            let gmax = x.gamma + x.alpha * x_hi + x.beta * y_hi;
            if gmin > self.gpad || gmax < -self.gpad {
                continue;
            }
            found |= 1 << i;
        }
        found
    }

    /// The least λ over segment i's box.
    #[inline(always)]
    fn lambda_lo(&self, p: &Probe, i: usize) -> f64 {
        let (cu, cv) = (&p.u[i], &p.v[i]);
        let x = if self.wx > 0.0 { cu.min } else { cu.max };
        let y = if self.wy > 0.0 { cv.min } else { cv.max };
        self.wx * x + self.wy * y
    }

    /// The candidates `left`, least λ bound first (of equal ones the lower
    /// segment), until the bound passes λ at the nearest hit so far; true
    /// when a hit is an answer at once.
    #[inline(always)]
    fn sides(&self, x: &Extrusion, p: &mut Probe, mut left: u64) -> bool {
        while left != 0 {
            let mut bits = left;
            let mut k = bits.trailing_zeros() as usize;
            let mut least = self.lambda_lo(p, k);
            bits &= bits - 1;
            while bits != 0 {
                let i = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let lambda = self.lambda_lo(p, i);
                if lambda < least {
                    (k, least) = (i, lambda);
                }
            }
            if let Some(best) = p.best {
                // A hit's k is above 0 (it lies between the caps); a NaN
                // skips nothing.
                let kb = x.k0 + x.k1 * best.t;
                if kb > 0.0 && least - self.pad > (self.a + self.b * best.t) / kb {
                    break;
                }
            }
            left &= !(1 << k);
            if x.segment(p, k) {
                return true;
            }
        }
        false
    }
}
