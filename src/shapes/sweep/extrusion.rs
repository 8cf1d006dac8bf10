//! Translation and conic sweeps: one cubic a segment from the ray's
//! central projection into the contour's plane, and the end caps.

use super::contour::{inside_contour, orientation_of, tangent};
use super::{asc, closer, negligible, norm2, polish, solve, Best, Candidates, Query, Want, PARALLEL_TOL, RESIDUAL_TOL};
use crate::types::{Coeff, DVec3, Fidelity, LocalHit, Options, Ray, SweepShape};

/// The "segment" of a cap hit: after every side segment, so a side hit at
/// the same t stays the nearest, as when the caps were tried last.
const CAP: usize = usize::MAX;

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
#[allow(clippy::too_many_arguments)]
pub(super) fn extrusion(
    u: &[Coeff],
    v: &[Coeff],
    sw: &SweepShape,
    conic: bool,
    size: f64,
    ray: &Ray,
    tmin: f64,
    opts: &Options,
    query: Query,
) -> Option<LocalHit> {
    let len = sw.length;
    if !(len > 0.0 && len.is_finite()) || (conic && !sw.scale.is_finite()) {
        return None;
    }
    let (o, d) = (ray.origin, ray.dir);
    let dn = d.length();
    let kappa = if conic { (sw.scale - 1.0) / len } else { 0.0 };
    let k0 = 1.0 + kappa * o.z;
    let k1 = kappa * d.z;
    let apex_z = if kappa != 0.0 { Some(-1.0 / kappa) } else { None };
    let apex_in = apex_z.is_some_and(|z| (0.0..=len).contains(&z));
    let hit = |t: f64, normal: DVec3| LocalHit {
        t,
        point: o + d * t,
        normal,
    };

    // A ray in the plane of the apex: the contour is a point there.
    if conic && d.z.abs() <= PARALLEL_TOL * dn && k0.abs() <= PARALLEL_TOL {
        let z = apex_z?;
        if !apex_in {
            return None;
        }
        let apex = DVec3::new(0.0, 0.0, z);
        let t = (apex - o).dot(d) / (dn * dn);
        let miss = (o + d * t - apex).length();
        return (miss <= RESIDUAL_TOL * size && t > tmin).then(|| hit(t, DVec3::Z));
    }

    let alpha = k0 * d.y - k1 * o.y;
    let beta = k1 * o.x - k0 * d.x;
    let gamma = o.y * d.x - o.x * d.y;
    let nrm = norm2(alpha, beta);
    let oxy = norm2(o.x, o.y);

    // The ray's projection is a point: only the caps (and an apex).
    if nrm <= PARALLEL_TOL * (k0.abs() * dn + k1.abs() * oxy) {
        if d.z == 0.0 {
            return None;
        }
        let t0 = -o.z / d.z;
        let (px, py) = (o.x + t0 * d.x, o.y + t0 * d.y);
        let inside = inside_contour(sw, u, v, px, py);
        let mut best: Option<Best> = None;
        for (zc, nz) in [(0.0, -1.0), (len, 1.0)] {
            let t = (zc - o.z) / d.z;
            let at_apex = conic && sw.scale == 0.0 && zc == len;
            if (inside || at_apex) && closer(&best, t, tmin, CAP) {
                best = Some(Best {
                    t,
                    normal: DVec3::new(0.0, 0.0, nz),
                    segment: CAP,
                });
            }
        }
        return best.map(|b| hit(b.t, b.normal));
    }

    let mut best: Option<Best> = None;
    let ztol = 1e-12 * size;
    let fscale = nrm * size + gamma.abs();
    let dxy2 = d.x * d.x + d.y * d.y;
    // Slack on a segment's lower bound: its points may stand 1e-9 of the
    // size outside its box (the joint slack), rounding far less.
    let t_pad = 1e-6 * size / dxy2.sqrt();
    // A bound needs no exact quotient (its slack is t_pad): a product.
    let per_dxy2 = 1.0 / dxy2;
    // The t where a side hit may lie: beyond tmin, and where the ray's z is
    // within the sides' (the hits keep 10⁻¹² of the size beyond the caps;
    // a thousand times that here, far above rounding).
    let slab = {
        let zpad = 1e-9 * size;
        let (za, zb) = if d.z == 0.0 {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            let (a, b) = ((-zpad - o.z) / d.z, (len + zpad - o.z) / d.z);
            (a.min(b), a.max(b))
        };
        (za.max(tmin), zb)
    };
    // Do the segments' boxes hold their segments, so that they bound the
    // hits' t (D32)?
    let boxes_hold = match opts.fidelity {
        // Listing (erratum 9): an in-between segment's box is the first
        // key's widened by 2, which the segment can leave: the boxes only
        // order the segments, as before D32.
        Fidelity::Listing => false,
        // Thesis: each segment's box is its extrema.
        Fidelity::Thesis => true,
    };
    let mut candidates = Candidates::new();
    let gpad = 1e-12 * fscale;
    // The box's corners where α X + β Y is least and most: rounding keeps
    // a product's order, so α·min ≤ α·max when α > 0 (the lesser of the
    // two products, as a `min` of both would pick), and the choice is the
    // ray's, made once instead of per segment.
    let (a_pos, b_pos) = (alpha > 0.0, beta > 0.0);
    // Where the ray runs between the caps' planes, its projection is the
    // piece of the line from A to B: a segment whose box keeps away from
    // that piece's box has no hit to keep (D32; a thousand times the
    // bound's slack t_pad).
    let span = (boxes_hold && !conic && slab.0.is_finite() && slab.1.is_finite()).then(|| {
        let (ax, ay) = (o.x + slab.0 * d.x, o.y + slab.0 * d.y);
        let (bx, by) = (o.x + slab.1 * d.x, o.y + slab.1 * d.y);
        let p = 1e-6 * size;
        [ax.min(bx) - p, ax.max(bx) + p, ay.min(by) - p, ay.max(by) + p]
    });
    for i in 0..u.len() {
        let (cu, cv) = (&u[i], &v[i]);
        if let Some(span) = &span {
            // The four sides at once (`|`, not `||`): one branch, not four.
            if (cu.max < span[0]) | (cu.min > span[1]) | (cv.max < span[2]) | (cv.min > span[3]) {
                continue;
            }
        }
        // The segment's box against the line α X + β Y + γ = 0.
        let (x_lo, x_hi) = if a_pos { (cu.min, cu.max) } else { (cu.max, cu.min) };
        let (y_lo, y_hi) = if b_pos { (cv.min, cv.max) } else { (cv.max, cv.min) };
        let gmin = gamma + alpha * x_lo + beta * y_lo;
        let gmax = gamma + alpha * x_hi + beta * y_hi;
        if gmin > gpad || gmax < -gpad {
            continue;
        }
        let t_lo = if conic {
            f64::NEG_INFINITY
        } else {
            let x = if d.x > 0.0 { cu.min } else { cu.max };
            let y = if d.y > 0.0 { cv.min } else { cv.max };
            let t_lo = ((x - o.x) * d.x + (y - o.y) * d.y) * per_dxy2 - t_pad;
            // The box's far corner bounds the hits' t from above: a segment
            // whose hits all lie at or before tmin, or outside the span of
            // t where the ray is between the caps, has none to keep (D32).
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
    // The caps, where the ray's point lies inside the (scaled) contour.
    // The near cap is tried first: the ray reaches no side before it (the
    // sides lie between the caps' planes), so when it is hit it is the
    // nearest hit but for a side at the rim, and the sides beyond it are
    // skipped. Whatever the order, the hit kept is the least (t, segment).
    // The box holds the contour (at z = 0, where a conic's is unscaled).
    let cbox = &sw.bbox;
    let boxed = cbox.xmin < cbox.xmax && cbox.ymin < cbox.ymax;
    let pad = 1e-9 * size;
    let cap = |zc: f64, nz: f64, best: &mut Option<Best>| -> bool {
        let k = 1.0 + kappa * zc;
        if k == 0.0 {
            return false; // the cap is the apex: a ray through it took the path above
        }
        let t = (zc - o.z) / d.z;
        if !closer(best, t, tmin, CAP) || query.past(t, &None) {
            return false;
        }
        let p = o + d * t;
        // A translation sweep's k is 1: x / 1 is x, without the division.
        let (x, y) = if conic { (p.x / k, p.y / k) } else { (p.x, p.y) };
        // Outside the contour's box the contour test answers no (every
        // segment is skipped, or crossed an even number of times): asked
        // only inside it.
        if (boxed && (x < cbox.xmin - pad || x > cbox.xmax + pad || y < cbox.ymin - pad || y > cbox.ymax + pad))
            || !inside_contour(sw, u, v, x, y)
        {
            return false;
        }
        *best = Some(Best {
            t,
            normal: DVec3::new(0.0, 0.0, nz),
            segment: CAP,
        });
        true
    };
    let caps: &[(f64, f64)] = match d.z {
        z if z > 0.0 => &[(0.0, -1.0), (len, 1.0)],
        z if z < 0.0 => &[(len, 1.0), (0.0, -1.0)],
        _ => &[],
    };
    if let Some(&(zc, nz)) = caps.first() {
        if cap(zc, nz, &mut best) && query.done(best.map_or(f64::INFINITY, |b| b.t)) {
            return best.map(|b| hit(b.t, b.normal));
        }
    }
    for (t_lo, i) in candidates.iter() {
        if query.past(t_lo, &best) {
            break;
        }
        let (cu, cv) = (&u[i], &v[i]);
        let (pu, pv) = (asc(cu), asc(cv));
        let mut f = [0.0; 7];
        for k in 0..4 {
            f[k] = alpha * pu[k] + beta * pv[k];
        }
        f[0] += gamma;
        if negligible(&f, fscale) {
            continue; // a straight segment along the ray's projection: grazing
        }
        let found = solve(3, &f, opts);
        for &s0 in &found.s[..found.count] {
            let s = polish(3, &f, s0);
            let (uu, vv) = (cu.value(s), cv.value(s));
            let (ex, ey) = (d.x - k1 * uu, d.y - k1 * vv);
            let den = ex * ex + ey * ey;
            if den.is_nan() || den <= 1e-24 * dn * dn {
                continue; // the ray runs along the generator through this point
            }
            let t = (ex * (k0 * uu - o.x) + ey * (k0 * vv - o.y)) / den;
            let p = o + d * t;
            let k = 1.0 + kappa * p.z;
            let residual = norm2(p.x - k * uu, p.y - k * vv);
            if residual <= RESIDUAL_TOL * size && p.z >= -ztol && p.z <= len + ztol && closer(&best, t, tmin, i) {
                let (tu, tv) = tangent(cu, cv, s, size);
                let normal = DVec3::new(tv, -tu, kappa * (tu * vv - tv * uu)) * k.signum();
                if query.done(t) {
                    return Some(hit(t, normal));
                }
                best = Some(Best { t, normal, segment: i });
            }
        }
    }

    // The far cap, if it is nearer than what the sides gave.
    if let Some(&(zc, nz)) = caps.get(1) {
        cap(zc, nz, &mut best);
    }

    let b = best?;
    if matches!(query.want, Want::Before(_)) {
        return Some(hit(b.t, b.normal)); // the caller needs only its t
    }
    let normal = if b.segment == CAP {
        b.normal
    } else {
        b.normal * orientation_of(sw, u, v)
    };
    let normal = normal.try_normalize()?;
    Some(hit(b.t, normal))
}
