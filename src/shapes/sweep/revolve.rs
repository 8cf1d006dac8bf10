//! Rotation sweeps: one sextic a segment from the ray's hyperbola in the
//! (radius, height) plane, with `outrectp` as the segment's bounding test.

use super::contour::tangent;
use super::probe::{Candidates, Probe};
use super::{asc, norm2, JOINT_SLACK, PARALLEL_TOL, RESIDUAL_TOL};
use crate::options::Solver;
use crate::proc::sweep::outrectp;
use crate::types::{Coeff, DVec3, LocalHit, Ray};

/// U(s), V(s) of segment (u, v), and the 2-D residual (radius, height) of
/// the ray point at t against that contour point of the rotation sweep.
pub(super) fn revolve_residual(u: &Coeff, v: &Coeff, ray: &Ray, s: f64, t: f64) -> (f64, f64, f64) {
    let (uu, vv) = (u.value(s), v.value(s));
    let p = ray.at(t);
    (uu, vv, norm2(norm2(p.x, p.y) - uu, p.z - vv))
}

/// Newton's method on the pair r(t)² = U(s)², z(t) = V(s) of a rotation
/// sweep, from (s, t); kept only while the residual falls. A start whose
/// residual exceeds `give_up` is returned as it is.
pub(super) fn polish_revolve(u: &Coeff, v: &Coeff, ray: &Ray, mut s: f64, mut t: f64, give_up: f64) -> (f64, f64, f64) {
    let (o, d) = (ray.origin, ray.dir);
    let (a, b, c) = (
        d.x * d.x + d.y * d.y,
        2.0 * (o.x * d.x + o.y * d.y),
        o.x * o.x + o.y * o.y,
    );
    // U and V kept from each residual for the step from there.
    let (mut uu, mut vv, mut res) = revolve_residual(u, v, ray, s, t);
    if res > give_up {
        return (s, t, res);
    }
    for _ in 0..5 {
        if res == 0.0 {
            break;
        }
        let (du, dv) = (u.slope(s), v.slope(s));
        let g1 = (a * t + b) * t + c - uu * uu;
        let g2 = o.z + t * d.z - vv;
        // J = [[2at + b, −2U U′], [d_z, −V′]] in (t, s).
        let (j11, j12, j21, j22) = (2.0 * a * t + b, -2.0 * uu * du, d.z, -dv);
        let det = j11 * j22 - j12 * j21;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let dt = (-g1 * j22 + g2 * j12) / det;
        let ds = (-g2 * j11 + g1 * j21) / det;
        let (ns, nt) = (s + ds, t + dt);
        let (nu, nv, nres) = revolve_residual(u, v, ray, ns, nt);
        if nres.is_nan() || nres >= res {
            break;
        }
        (s, t, uu, vv, res) = (ns, nt, nu, nv, nres);
    }
    (s, t, res)
}

/// The rotation sweep's outward normal at the hit point p of contour
/// point s: (V′ e_r − U′ e_z), for a counter-clockwise contour (the
/// caller turns it by the orientation, once for the hit it keeps).
pub(super) fn revolve_normal(u: &Coeff, v: &Coeff, s: f64, p: DVec3, size: f64) -> DVec3 {
    let (tu, tv) = tangent(u, v, s, size);
    let r = norm2(p.x, p.y);
    let (ex, ey) = if r > 1e-12 * size {
        (p.x / r, p.y / r)
    } else {
        (1.0, 0.0)
    };
    DVec3::new(tv * ex, tv * ey, -tu)
}

/// The rotation sweep's polynomial of segment (u, v) for `ray` (see
/// [`revolve`]): A (V − o_z)² + B d_z (V − o_z) + d_z² (C − U²),
/// ascending coefficients. Its constant term holds C d_z² = |o_xy|² d_z²
/// and A o_z²: from a ray that starts far away these cancel to a small
/// number and take the precision with them, which is why the driver forms
/// it from the ray [`Near`](crate::shapes::Near) the object.
pub(super) fn sextic(cu: &Coeff, cv: &Coeff, ray: &Ray) -> [f64; 7] {
    let (o, d) = (ray.origin, ray.dir);
    let a = d.x * d.x + d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.y * d.y);
    let c = o.x * o.x + o.y * o.y;
    let dz = d.z;
    let mut w = asc(cv);
    w[0] -= o.z;
    let uu = asc(cu);
    let mut p = [0.0; 7];
    for j in 0..4 {
        for k in 0..4 {
            p[j + k] += a * w[j] * w[k] - dz * dz * uu[j] * uu[k];
        }
        p[j] += b * dz * w[j];
    }
    p[0] += c * dz * dz;
    p
}

/// Rotation sweeps: the ray in (r, z) traces r² = (A t² + B t + C) with
/// A = d_x² + d_y², B = 2(o_x d_x + o_y d_y), C = o_x² + o_y², and
/// t = (z − o_z)/d_z, so with w = z − o_z
///   d_z² r² = A w² + B d_z w + C d_z²,
/// a hyperbola (`outrectp`'s a, b, c, d are A, B d_z, C d_z², d_z², with
/// heights measured from o_z). On the contour r = U(s), w = V(s) − o_z:
///   A (V − o_z)² + B d_z (V − o_z) + d_z² (C − U²) = 0,
/// a sextic in s.
pub(super) fn revolve(mut probe: Probe) -> Option<LocalHit> {
    let r = Revolve::new(&probe);
    // Filled where it stands: returned, its arrays would be copied.
    let mut candidates = Candidates::new();
    r.candidates(&probe, &mut candidates);
    r.sides(&mut probe, &candidates);
    probe.finish()
}

/// What one ray gives a rotation sweep's phases (see [`revolve`]): the
/// ray's numbers and its hyperbola in the (radius, height) plane.
// The phases are compiled into `revolve`, as the closures they were
// written as before: one function, its numbers kept in registers.
#[derive(Clone, Copy)]
struct Revolve {
    o: DVec3,
    d: DVec3,
    a: f64,
    b: f64,
    c: f64,
    // Along the axis (the ray keeps the radius √C), or perpendicular to
    // it (the height o_z): the special cases.
    along: bool,
    across: bool,
    /// Starts farther than this from the surface are not polished.
    give_up: f64,
    // √C, and the radius of the ray's closest approach to the axis.
    rc: f64,
    hu: f64,
    // `outrectp`'s hyperbola, and the height of its vertex.
    ha: f64,
    hb: f64,
    hc: f64,
    hd: f64,
    hv: f64,
    /// Does a segment's greatest radius bound its hits' t (D90)?
    radial: bool,
    // The t of the ray's closest approach to the axis, and the square of
    // its distance there: r(t)² = A (t − tc)² + hu2.
    tc: f64,
    hu2: f64,
}

impl Revolve {
    #[inline(always)]
    fn new(p: &Probe) -> Revolve {
        let (o, d) = (p.ray.origin, p.ray.dir);
        let dn = d.length();
        let a = d.x * d.x + d.y * d.y;
        let b = 2.0 * (o.x * d.x + o.y * d.y);
        let c = o.x * o.x + o.y * o.y;
        // Each root s is tried with three t (its height's, and the circle's
        // two crossings), of which one is the hit. A root of the robust
        // solver is the sextic's to rounding, so the others start far from
        // the surface and cannot polish to a hit of theirs (such a hit
        // would be another root, tried on its own): they are dropped before
        // the polish. A root of `laguerre` may be rough, and every start is
        // polished, as before.
        let give_up = match p.opts.solver {
            Solver::Robust => 1e-3 * p.size,
            Solver::Laguerre => f64::INFINITY,
        };
        let dz = d.z;
        let (ha, hb, hc, hd) = (a, b * dz, c * dz * dz, dz * dz);
        let (along, across) = (a.sqrt() <= PARALLEL_TOL * dn, d.z.abs() <= PARALLEL_TOL * dn);
        Revolve {
            o,
            d,
            a,
            b,
            c,
            along,
            across,
            give_up,
            rc: c.sqrt(),
            hu: (c - b * b / (4.0 * a)).max(0.0).sqrt(),
            ha,
            hb,
            hc,
            hd,
            hv: -hb / (2.0 * ha),
            radial: p.boxes_hold() && !p.counted() && !along && !across,
            tc: -b / (2.0 * a),
            hu2: c - b * b / (4.0 * a),
        }
    }

    /// The t where the ray is within the radius `umax` of the axis, the
    /// most a segment's hit can have, padded (D90): `None` where it never
    /// is. A kept hit lies within 10⁻⁹ of the size of the surface, at a
    /// radius |U(s)| with s at most 10⁻⁹ beyond the segment's ends, so
    /// its r(t) stands at most 2·10⁻⁹ of the size beyond `umax`; the
    /// radius is padded by 10⁻⁶ of the size, which widens the span of t on
    /// each side by more than 10⁻⁶ of the size over |d_xy| (r changes no
    /// faster than |d_xy|), and the span is padded by that again: far
    /// above the rounding of r(t)² = A (t − tc)² + hu2, whose terms are of
    /// the squared size of the object near which the ray starts.
    #[inline(always)]
    fn radial_span(&self, umax: f64, size: f64) -> Option<(f64, f64)> {
        let r = umax + 1e-6 * size;
        let room = r * r - self.hu2;
        if room.is_nan() || room < 0.0 {
            return None;
        }
        let (half, pad) = ((room / self.a).sqrt(), 1e-6 * size / self.a.sqrt());
        Some((self.tc - half - pad, self.tc + half + pad))
    }

    /// The segments whose bounds the ray passes, nearest first: `outrectp`
    /// on the segment's box, then its heights' span of t and (thesis
    /// fidelity, D90) its radius's.
    #[inline(always)]
    fn candidates(&self, p: &Probe, candidates: &mut Candidates) {
        let (o, size) = (self.o, p.size);
        let pad = 1e-9 * size;
        // Slack on a segment's lower bound on t from its heights: a hit's
        // height is V(s) to 1e-9 of the size, with s 1e-9 outside [0, 1].
        let t_pad = 1e-6 * size / self.d.z.abs();
        for (i, (cu, cv)) in p.u.iter().zip(p.v).enumerate() {
            // The segment's greatest radius |U| (a deck's U is never
            // negative; an in-between's extrema may be, a little).
            let umax = cu.max.abs().max(cu.min.abs());
            if umax <= 1e-12 * size {
                continue; // a segment on the axis sweeps no surface
            }
            let t_lo = if self.along {
                // Along the axis: the ray keeps the radius √C.
                if cu.min > self.rc + pad || cu.max < self.rc - pad {
                    continue;
                }
                f64::NEG_INFINITY
            } else if self.across {
                // Perpendicular to the axis: the ray keeps the height o_z.
                if cv.min > o.z + pad || cv.max < o.z - pad || cu.max < self.hu - pad {
                    continue;
                }
                f64::NEG_INFINITY
            } else {
                let pu = Coeff {
                    min: cu.min - pad,
                    max: cu.max + pad,
                    ..*cu
                };
                let pv = Coeff {
                    min: cv.min - o.z - pad,
                    max: cv.max - o.z + pad,
                    ..*cv
                };
                if outrectp(&pu, &pv, self.ha, self.hb, self.hc, self.hd, self.hu, self.hv) {
                    continue;
                }
                let (ta, tb) = ((cv.min - o.z) / self.d.z, (cv.max - o.z) / self.d.z);
                let t_lo = ta.min(tb) - t_pad;
                if !self.radial {
                    t_lo
                } else if let Some((r_lo, r_hi)) = self.radial_span(umax, size) {
                    // The ray leaves the segment's heights or its radius by
                    // tmin: no hit to keep (D90).
                    if ta.max(tb) + t_pad <= p.tmin || r_hi <= p.tmin {
                        continue;
                    }
                    t_lo.max(r_lo)
                } else {
                    continue; // the ray never comes within the segment's radius (D90)
                }
            };
            candidates.push(t_lo, i);
        }
    }

    /// Each candidate segment's polynomial, nearest first, until no hit
    /// beyond can matter or one is an answer at once: along the axis
    /// U(s) = √C, a cubic, t from the height; perpendicular to it
    /// V(s) = o_z, a cubic, t from the circle of radius U(s); else the
    /// sextic, t from the better conditioned of the height and the radius
    /// equations (each tried, and what lands on the surface kept).
    #[inline(always)]
    fn sides(&self, p: &mut Probe, candidates: &Candidates) {
        let size = p.size;
        for (t_lo, i) in candidates.iter() {
            if p.past(t_lo) {
                break;
            }
            let (cu, cv) = (&p.u[i], &p.v[i]);
            let answered = if self.along {
                let mut poly = [0.0; 7];
                poly[..4].copy_from_slice(&asc(cu));
                poly[0] -= self.rc;
                p.roots(3, &poly, size, |p, s| self.at_height(p, i, s))
            } else if self.across {
                let mut poly = [0.0; 7];
                poly[..4].copy_from_slice(&asc(cv));
                poly[0] -= self.o.z;
                p.roots(3, &poly, size, |p, s| self.on_circle(p, i, s))
            } else {
                let poly = sextic(cu, cv, &p.ray);
                let pscale = self.a * size * size + self.hd * (size * size + self.c);
                p.roots(6, &poly, pscale, |p, s| {
                    self.at_height(p, i, s) || self.on_circle(p, i, s)
                })
            };
            if answered {
                return;
            }
        }
    }

    /// Root s of segment i with the t of its height.
    #[inline(always)]
    fn at_height(&self, p: &mut Probe, i: usize, s: f64) -> bool {
        self.consider(p, i, s, (p.v[i].value(s) - self.o.z) / self.d.z)
    }

    /// Root s of segment i with the two t where the ray crosses the circle
    /// of radius U(s) (A t² + B t + C = U²), if it does.
    #[inline(always)]
    fn on_circle(&self, p: &mut Probe, i: usize, s: f64) -> bool {
        let r = p.u[i].value(s);
        let (a, b) = (self.a, self.b);
        let cc = self.c - r * r;
        let disc = b * b - 4.0 * a * cc;
        if disc < 0.0 {
            return false;
        }
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        let (t1, t2) = if q == 0.0 {
            let t = -b / (2.0 * a);
            (t, t)
        } else {
            (q / a, cc / q)
        };
        self.consider(p, i, s, t1) || self.consider(p, i, s, t2)
    }

    /// The hit polished from (s, t) on segment i, kept if it lies on the
    /// surface and is the nearest so far; true when it is an answer at
    /// once.
    #[inline(always)]
    fn consider(&self, p: &mut Probe, i: usize, s: f64, t: f64) -> bool {
        if !t.is_finite() {
            return false;
        }
        let (cu, cv) = (&p.u[i], &p.v[i]);
        let (s, t, res) = polish_revolve(cu, cv, &p.ray, s, t, self.give_up);
        if res <= RESIDUAL_TOL * p.size && (-JOINT_SLACK..=1.0 + JOINT_SLACK).contains(&s) && p.closer(t, i) {
            let normal = revolve_normal(cu, cv, s, p.ray.at(t), p.size);
            return p.keep(t, normal, i);
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::Near;

    /// The goblet's bowl segment of Fig. 5.8 (Bezier 0.15 1.2, 0.9 1.25,
    /// 1 1.9, 0.95 2.5).
    fn bowl() -> (Coeff, Coeff) {
        let bez = |p: [f64; 4]| Coeff {
            a: -p[0] + 3.0 * p[1] - 3.0 * p[2] + p[3],
            b: 3.0 * p[0] - 6.0 * p[1] + 3.0 * p[2],
            c: -3.0 * p[0] + 3.0 * p[1],
            d: p[0],
            ..Coeff::default()
        };
        (bez([0.15, 0.9, 1.0, 0.95]), bez([1.2, 1.25, 1.9, 2.5]))
    }

    /// A start farther from the surface than `give_up` comes back as it
    /// is; the same start with no limit is polished onto the surface.
    #[test]
    fn polish_revolve_gives_up_on_far_starts() {
        let (cu, cv) = bowl();
        let ray = Ray::new(DVec3::new(3.0, 0.2, 1.9), DVec3::new(-1.0, 0.0, 0.0));
        // The bowl at height 1.9 has radius about 0.99; start off by 0.05.
        let (s0, t0) = (0.6, 1.95);
        let (_, _, r0) = revolve_residual(&cu, &cv, &ray, s0, t0);
        assert!(r0 > 1e-3 && r0 < 1.0, "{r0}");
        assert_eq!(polish_revolve(&cu, &cv, &ray, s0, t0, 0.5 * r0), (s0, t0, r0));
        let (s, t, res) = polish_revolve(&cu, &cv, &ray, s0, t0, f64::INFINITY);
        assert!(res < 1e-12 && res < r0, "{s} {t} {res}");
        let (s1, t1, r1) = polish_revolve(&cu, &cv, &ray, s0, t0, r0);
        assert_eq!((s1, t1, r1), (s, t, res), "a residual at the limit is polished");
    }

    /// The sextic of one line of sight, formed from an origin 10 units
    /// away and from one 10⁶ units away taken near the object: the same
    /// coefficients to 1e-9 of the largest. Formed from the far origin as
    /// it is, the constant term's cancellation loses about 10¹² ε of it.
    #[test]
    fn sextic_from_far_is_conditioned_as_from_near() {
        let (cu, cv) = bowl();
        let target = DVec3::new(0.93, 0.1, 1.8);
        let dir = DVec3::new(-0.6, 1.0, -0.25).normalize();
        let at = |dist: f64| Ray::new(target - dir * dist, dir);
        let reference = sextic(&cu, &cv, &at(10.0));
        let scale = reference.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let gap = |p: &[f64; 7]| p.iter().zip(&reference).fold(0.0f64, |m, (a, b)| m.max((a - b).abs())) / scale;
        for dist in [1e4, 1e5, 1e6] {
            let near = Near::of(&at(dist), 1e-9, DVec3::new(0.0, 0.0, 1.28), 4.0);
            assert!(near.shift > dist - 3.0, "re-based near the object");
            let g = gap(&sextic(&cu, &cv, &near.ray));
            assert!(g < 1e-9, "{dist}: {g:e}");
        }
        let raw = gap(&sextic(&cu, &cv, &at(1e6)));
        assert!(raw > 1e-6, "the far origin as it is loses precision: {raw:e}");
    }
}
