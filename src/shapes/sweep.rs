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

use crate::proc::robust::real_roots;
use crate::proc::sweep::{laguerre, outrectp, spline, Root, LAGUERRE_ROOTS};
use crate::types::{
    BoundingBox, Coeff, CurveKind, DVec3, Fidelity, LocalHit, Options, PrimitiveClass, Ray, Scene, Shape, Solver,
    SweepShape, MAXSEGMENTS,
};

/// Roots are kept in [−this, 1 + this], so that a ray through a joint is
/// not lost to rounding on both sides of it (it may be found twice: the
/// nearest hit is the same).
const JOINT_SLACK: f64 = 1e-9;

/// A root whose hit point is farther than this (relative to the object's
/// size) from the surface is rejected.
const RESIDUAL_TOL: f64 = 1e-9;

/// A ray component below this fraction of the ray's length counts as 0
/// (the special cases: parallel or perpendicular to an axis).
const PARALLEL_TOL: f64 = 1e-12;

/// x(s) = ((a s + b) s + c) s + d.
/// √(a² + b²). `f64::hypot` guards against overflow at a cost that shows in
/// the profile of every sweep render; scene coordinates are far from the
/// range where a² could overflow.
fn norm2(a: f64, b: f64) -> f64 {
    (a * a + b * b).sqrt()
}

/// Ascending coefficients [d, c, b, a].
fn asc(c: &Coeff) -> [f64; 4] {
    [c.d, c.c, c.b, c.a]
}

/// p(x) and p′(x) of a polynomial of degree ≤ 6 (ascending coefficients).
fn horner(p: &[f64; 7], x: f64) -> (f64, f64) {
    let (mut f, mut df) = (p[6], 0.0);
    for k in (0..6).rev() {
        df = df * x + f;
        f = f * x + p[k];
    }
    (f, df)
}

/// Newton steps on p from s, kept only while |p| falls.
fn polish(p: &[f64; 7], mut s: f64) -> f64 {
    let (mut f, mut df) = horner(p, s);
    for _ in 0..4 {
        if f == 0.0 || df == 0.0 {
            break;
        }
        let next = s - f / df;
        let (nf, ndf) = horner(p, next);
        if nf.is_nan() || nf.abs() >= f.abs() {
            break;
        }
        (s, f, df) = (next, nf, ndf);
    }
    s
}

/// The roots in [−JOINT_SLACK, 1 + JOINT_SLACK] of one segment's
/// polynomial.
struct Found {
    count: usize,
    s: [f64; 6],
}

/// The segment's polynomial of degree `n` solved by the chosen method.
fn solve(n: usize, a: &[f64; 7], opts: &Options) -> Found {
    let mut out = Found { count: 0, s: [0.0; 6] };
    let (lo, hi) = (-JOINT_SLACK, 1.0 + JOINT_SLACK);
    if !may_have_root(n, a, lo, hi) {
        return out;
    }
    match opts.solver {
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
/// [lo, hi]? Not when its Bernstein coefficients on that interval are all
/// of one strict sign: the polynomial lies in their convex hull. A test
/// before either solver that spares the solve for most segments a ray's
/// line passes near without crossing; where it answers "no" there is no
/// root for a solver to find, so no image changes (DEVIATIONS D18).
fn may_have_root(n: usize, a: &[f64; 7], lo: f64, hi: f64) -> bool {
    // Binomial coefficients C(k, j) for k, j ≤ 6.
    const C: [[f64; 7]; 7] = [
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 2.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 3.0, 3.0, 1.0, 0.0, 0.0, 0.0],
        [1.0, 4.0, 6.0, 4.0, 1.0, 0.0, 0.0],
        [1.0, 5.0, 10.0, 10.0, 5.0, 1.0, 0.0],
        [1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0],
    ];
    let n = n.min(6);
    // q(x) = p(lo + (hi − lo)·x): a Taylor shift by lo, then a scaling.
    let mut c = [0.0; 7];
    c[..=n].copy_from_slice(&a[..=n]);
    for i in 0..n {
        for j in (i..n).rev() {
            c[j] += lo * c[j + 1];
        }
    }
    let w = hi - lo;
    let mut wk = 1.0;
    for ck in c.iter_mut().take(n + 1) {
        *ck *= wk;
        wk *= w;
    }
    let tiny = 1e-12 * c[..=n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if tiny.is_nan() || tiny <= 0.0 || tiny.is_infinite() {
        return true; // zero, or not finite: let the solver decide
    }
    let (mut pos, mut neg) = (false, false);
    for (k, ck) in C.iter().enumerate().take(n + 1) {
        // b_k = Σ_{j ≤ k} C(k, j) / C(n, j) · c_j
        let b: f64 = (0..=k).map(|j| ck[j] / C[n][j] * c[j]).sum();
        if b > tiny {
            pos = true;
        } else if b < -tiny {
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

/// Is every coefficient negligible beside `scale`? (A segment that lies
/// on the ray's projected line, or a polynomial that vanishes everywhere.)
fn negligible(p: &[f64; 7], scale: f64) -> bool {
    p.iter().all(|c| c.abs() <= 1e-13 * scale)
}

/// The contour's curve direction at s of segment (u, v): the derivative;
/// where it vanishes (a cusp from repeated control points), the limit
/// direction from the second or third derivative.
fn tangent(u: &Coeff, v: &Coeff, s: f64, size: f64) -> (f64, f64) {
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
fn orientation(u: &[Coeff], v: &[Coeff]) -> f64 {
    if signed_area(u, v) < 0.0 {
        -1.0
    } else {
        1.0
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
/// the port's [`real_roots`] whatever `Options::solver` says: one missed
/// crossing turns a whole cap inside out along a line.
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
        let mut p = [0.0; 7];
        p[..4].copy_from_slice(&asc(cv));
        p[0] -= y;
        if !may_have_root(3, &p, 0.0, 1.0) {
            continue; // V − y keeps one strict sign over the segment (D18)
        }
        let r = real_roots(3, &p, 0.0, 1.0);
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

/// Does the ray meet the box [lo, hi] at some t > tmin?
fn ray_meets_box(ray: &Ray, tmin: f64, lo: DVec3, hi: DVec3) -> bool {
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
        }
    }
    t0 <= t1
}

/// The largest coordinate of the box: the object's size for relative
/// tolerances.
fn box_size(b: &BoundingBox) -> f64 {
    [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The intersection of a ray with a sweep object: the nearest hit with
/// t > `tmin`, with its unit outward normal, in the object's local frame.
///
/// Reconstructed from van Wijk 1984 and the thesis's §2.3, §2.5, §3.3 (see
/// the module doc). The sweep's `u`, `v` and `bbox` must be filled
/// ([`prepare_sweeps`], or the key-frame code for in-between shapes), and
/// each `u[i]`, `v[i]` must bound its segment with `min`, `max`.
///
/// Special cases, each on its own path:
/// - translation, a ray parallel to the axis: its projection is a point,
///   inside the contour or not; only the caps can be hit;
/// - conic, a ray through the apex: the same, with the point the ray's
///   central projection from the apex; a ray in the plane of the apex
///   (where the contour shrinks to a point) can only touch the apex;
/// - rotation, a ray along the axis (constant radius): U(s) = r, a cubic;
///   a ray perpendicular to the axis (constant height): V(s) = z, a cubic,
///   then the ray's two crossings of the circle of radius U(s).
///
/// Each root gives its hit from the better conditioned equation, is
/// polished, and is rejected unless the hit lies on the surface (within
/// 1e-9 of the object's size); so a spurious root of either solver (the
/// listing's `laguerre` can return one, erratum 7) never becomes a hit.
pub fn intersect_sweep(
    class: PrimitiveClass,
    sweep: &SweepShape,
    ray: &Ray,
    tmin: f64,
    opts: &Options,
) -> Option<LocalHit> {
    let n = sweep.segment.min(sweep.u.len()).min(sweep.v.len()).min(MAXSEGMENTS);
    if n == 0 || !ray.origin.is_finite() || !ray.dir.is_finite() || ray.dir == DVec3::ZERO || tmin.is_nan() {
        return None;
    }
    let (u, v) = (&sweep.u[..n], &sweep.v[..n]);
    let mut size = box_size(&sweep.bbox);
    if !(size > 0.0 && size.is_finite()) {
        size = u
            .iter()
            .chain(v)
            .fold(0.0f64, |m, c| m.max(c.min.abs()).max(c.max.abs()));
        size = size.max(sweep.length.abs());
    }
    if !(size > 0.0 && size.is_finite()) {
        return None;
    }
    let b = &sweep.bbox;
    let pad = 1e-9 * size;
    let boxed = b.xmin < b.xmax && b.zmin < b.zmax;
    match class {
        PrimitiveClass::Translation | PrimitiveClass::Conic => {
            let lo = DVec3::new(b.xmin, b.ymin, b.zmin) - pad;
            let hi = DVec3::new(b.xmax, b.ymax, b.zmax) + pad;
            if boxed && !ray_meets_box(ray, tmin, lo, hi) {
                return None;
            }
            let conic = class == PrimitiveClass::Conic;
            extrusion(u, v, sweep, conic, size, ray, tmin, opts)
        }
        PrimitiveClass::Rotation => {
            let r = b.xmin.abs().max(b.xmax.abs()).max(b.ymin.abs()).max(b.ymax.abs());
            let lo = DVec3::new(-r, -r, b.zmin) - pad;
            let hi = DVec3::new(r, r, b.zmax) + pad;
            if boxed && !ray_meets_box(ray, tmin, lo, hi) {
                return None;
            }
            revolve(u, v, size, ray, tmin, opts)
        }
        _ => None,
    }
}

/// The nearest hit so far.
#[derive(Clone, Copy)]
struct Best {
    t: f64,
    normal: DVec3,
}

fn closer(best: &Option<Best>, t: f64, tmin: f64) -> bool {
    t > tmin && best.is_none_or(|b| t < b.t)
}

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
#[allow(clippy::too_many_arguments)]
fn extrusion(
    u: &[Coeff],
    v: &[Coeff],
    sw: &SweepShape,
    conic: bool,
    size: f64,
    ray: &Ray,
    tmin: f64,
    opts: &Options,
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
        let inside = point_in_contour(u, v, px, py);
        let mut best: Option<Best> = None;
        for (zc, nz) in [(0.0, -1.0), (len, 1.0)] {
            let t = (zc - o.z) / d.z;
            let at_apex = conic && sw.scale == 0.0 && zc == len;
            if (inside || at_apex) && closer(&best, t, tmin) {
                best = Some(Best {
                    t,
                    normal: DVec3::new(0.0, 0.0, nz),
                });
            }
        }
        return best.map(|b| hit(b.t, b.normal));
    }

    let mut best: Option<Best> = None;
    let mut side = false;
    let ztol = 1e-12 * size;
    let fscale = nrm * size + gamma.abs();
    for i in 0..u.len() {
        let (cu, cv) = (&u[i], &v[i]);
        // The segment's box against the line α X + β Y + γ = 0.
        let gmin = gamma + (alpha * cu.min).min(alpha * cu.max) + (beta * cv.min).min(beta * cv.max);
        let gmax = gamma + (alpha * cu.min).max(alpha * cu.max) + (beta * cv.min).max(beta * cv.max);
        let gpad = 1e-12 * fscale;
        if gmin > gpad || gmax < -gpad {
            continue;
        }
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
            let s = polish(&f, s0);
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
            if residual <= RESIDUAL_TOL * size && p.z >= -ztol && p.z <= len + ztol && closer(&best, t, tmin) {
                let (tu, tv) = tangent(cu, cv, s, size);
                let normal = DVec3::new(tv, -tu, kappa * (tu * vv - tv * uu)) * k.signum();
                best = Some(Best { t, normal });
                side = true;
            }
        }
    }

    // The caps, where the ray's point lies inside the (scaled) contour.
    if d.z != 0.0 {
        for (zc, nz) in [(0.0, -1.0), (len, 1.0)] {
            let k = 1.0 + kappa * zc;
            if k == 0.0 {
                continue; // the cap is the apex: a ray through it took the path above
            }
            let t = (zc - o.z) / d.z;
            if !closer(&best, t, tmin) {
                continue;
            }
            let p = o + d * t;
            if point_in_contour(u, v, p.x / k, p.y / k) {
                best = Some(Best {
                    t,
                    normal: DVec3::new(0.0, 0.0, nz),
                });
                side = false;
            }
        }
    }

    let b = best?;
    let normal = if side { b.normal * orientation(u, v) } else { b.normal };
    let normal = normal.try_normalize()?;
    Some(hit(b.t, normal))
}

/// The rotation sweep's surface point nearest the ray point at t, for the
/// contour point s of segment (u, v): the 2-D residual (radius, height).
fn revolve_residual(u: &Coeff, v: &Coeff, ray: &Ray, s: f64, t: f64) -> f64 {
    let p = ray.at(t);
    norm2(norm2(p.x, p.y) - u.value(s), p.z - v.value(s))
}

/// Newton's method on the pair r(t)² = U(s)², z(t) = V(s) of a rotation
/// sweep, from (s, t); kept only while the residual falls.
fn polish_revolve(u: &Coeff, v: &Coeff, ray: &Ray, mut s: f64, mut t: f64) -> (f64, f64, f64) {
    let (o, d) = (ray.origin, ray.dir);
    let (a, b, c) = (
        d.x * d.x + d.y * d.y,
        2.0 * (o.x * d.x + o.y * d.y),
        o.x * o.x + o.y * o.y,
    );
    let mut res = revolve_residual(u, v, ray, s, t);
    for _ in 0..5 {
        if res == 0.0 {
            break;
        }
        let (uu, vv, du, dv) = (u.value(s), v.value(s), u.slope(s), v.slope(s));
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
        let nres = revolve_residual(u, v, ray, ns, nt);
        if nres.is_nan() || nres >= res {
            break;
        }
        (s, t, res) = (ns, nt, nres);
    }
    (s, t, res)
}

/// The rotation sweep's outward normal at the hit point p of contour
/// point s: (V′ e_r − U′ e_z), turned by the contour's orientation.
fn revolve_normal(u: &Coeff, v: &Coeff, s: f64, p: DVec3, size: f64, sign: f64) -> DVec3 {
    let (tu, tv) = tangent(u, v, s, size);
    let r = norm2(p.x, p.y);
    let (ex, ey) = if r > 1e-12 * size {
        (p.x / r, p.y / r)
    } else {
        (1.0, 0.0)
    };
    DVec3::new(tv * ex, tv * ey, -tu) * sign
}

/// Rotation sweeps: the ray in (r, z) traces r² = (A t² + B t + C) with
/// A = d_x² + d_y², B = 2(o_x d_x + o_y d_y), C = o_x² + o_y², and
/// t = (z − o_z)/d_z, so with w = z − o_z
///   d_z² r² = A w² + B d_z w + C d_z²,
/// a hyperbola (`outrectp`'s a, b, c, d are A, B d_z, C d_z², d_z², with
/// heights measured from o_z). On the contour r = U(s), w = V(s) − o_z:
///   A (V − o_z)² + B d_z (V − o_z) + d_z² (C − U²) = 0,
/// a sextic in s.
fn revolve(u: &[Coeff], v: &[Coeff], size: f64, ray: &Ray, tmin: f64, opts: &Options) -> Option<LocalHit> {
    let (o, d) = (ray.origin, ray.dir);
    let dn = d.length();
    let a = d.x * d.x + d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.y * d.y);
    let c = o.x * o.x + o.y * o.y;
    let sign = orientation(u, v);
    let pad = 1e-9 * size;
    let along = a.sqrt() <= PARALLEL_TOL * dn;
    let across = d.z.abs() <= PARALLEL_TOL * dn;
    let mut best: Option<Best> = None;
    let consider = |cu: &Coeff, cv: &Coeff, s: f64, t: f64, best: &mut Option<Best>| {
        if !t.is_finite() {
            return;
        }
        let (s, t, res) = polish_revolve(cu, cv, ray, s, t);
        if res <= RESIDUAL_TOL * size && (-JOINT_SLACK..=1.0 + JOINT_SLACK).contains(&s) && closer(best, t, tmin) {
            let normal = revolve_normal(cu, cv, s, ray.at(t), size, sign);
            *best = Some(Best { t, normal });
        }
    };
    // Both crossings of the circle of radius r (A t² + B t + C = r²).
    let circle = |r: f64| -> Option<(f64, f64)> {
        let cc = c - r * r;
        let disc = b * b - 4.0 * a * cc;
        if disc < 0.0 {
            return None;
        }
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        if q == 0.0 {
            let t = -b / (2.0 * a);
            return Some((t, t));
        }
        Some((q / a, cc / q))
    };

    for i in 0..u.len() {
        let (cu, cv) = (&u[i], &v[i]);
        if cu.max.abs().max(cu.min.abs()) <= 1e-12 * size {
            continue; // a segment on the axis sweeps no surface
        }
        if along {
            // Along the axis: the ray keeps the radius √C; U(s) = √C.
            let rc = c.sqrt();
            if cu.min > rc + pad || cu.max < rc - pad {
                continue;
            }
            let mut p = [0.0; 7];
            p[..4].copy_from_slice(&asc(cu));
            p[0] -= rc;
            if negligible(&p, size) {
                continue;
            }
            let found = solve(3, &p, opts);
            for &s in &found.s[..found.count] {
                let s = polish(&p, s);
                consider(cu, cv, s, (cv.value(s) - o.z) / d.z, &mut best);
            }
        } else if across {
            // Perpendicular to the axis: the ray keeps the height o_z.
            let hu = (c - b * b / (4.0 * a)).max(0.0).sqrt();
            if cv.min > o.z + pad || cv.max < o.z - pad || cu.max < hu - pad {
                continue;
            }
            let mut p = [0.0; 7];
            p[..4].copy_from_slice(&asc(cv));
            p[0] -= o.z;
            if negligible(&p, size) {
                continue;
            }
            let found = solve(3, &p, opts);
            for &s in &found.s[..found.count] {
                let s = polish(&p, s);
                if let Some((t1, t2)) = circle(cu.value(s)) {
                    consider(cu, cv, s, t1, &mut best);
                    consider(cu, cv, s, t2, &mut best);
                }
            }
        } else {
            let dz = d.z;
            let (ha, hb, hc, hd) = (a, b * dz, c * dz * dz, dz * dz);
            let hv = -hb / (2.0 * ha);
            let hu = (c - b * b / (4.0 * a)).max(0.0).sqrt();
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
            if outrectp(&pu, &pv, ha, hb, hc, hd, hu, hv) {
                continue;
            }
            let mut w = asc(cv);
            w[0] -= o.z;
            let uu = asc(cu);
            let mut p = [0.0; 7];
            for j in 0..4 {
                for k in 0..4 {
                    p[j + k] += a * w[j] * w[k] - hd * uu[j] * uu[k];
                }
                p[j] += b * dz * w[j];
            }
            p[0] += hc;
            let pscale = a * size * size + hd * (size * size + c);
            if negligible(&p, pscale) {
                continue;
            }
            let found = solve(6, &p, opts);
            for &s in &found.s[..found.count] {
                let s = polish(&p, s);
                // The better conditioned of the height and the radius
                // equations: try each, keep what lands on the surface.
                consider(cu, cv, s, (cv.value(s) - o.z) / dz, &mut best);
                if let Some((t1, t2)) = circle(cu.value(s)) {
                    consider(cu, cv, s, t1, &mut best);
                    consider(cu, cv, s, t2, &mut best);
                }
            }
        }
    }
    let bst = best?;
    let normal = bst.normal.try_normalize()?;
    Some(LocalHit {
        t: bst.t,
        point: ray.at(bst.t),
        normal,
    })
}

/// The four control points of segment i: B-spline points i … i+3
/// (wrapping), Bezier P[3i] … P[3i+3 mod 3k].
fn segment_points(curve: CurveKind, points: &[[f64; 2]], i: usize) -> [[f64; 2]; 4] {
    let n = points.len();
    match curve {
        CurveKind::Bspline => std::array::from_fn(|k| points[(i + k) % n]),
        CurveKind::Bezier => {
            let m = 3 * (n / 3);
            std::array::from_fn(|k| points[(3 * i + k) % m])
        }
    }
}

/// `u`, `v` and `segment` of one sweep from its control points, by
/// `spline`; returns the box `spline` widened (x from U; y, or for a
/// rotation z, from V).
fn fill_segments(class: PrimitiveClass, sw: &mut SweepShape) -> BoundingBox {
    let n = sw.points.len();
    let segments = match sw.curve {
        CurveKind::Bspline => n,
        CurveKind::Bezier => n / 3,
    }
    .min(MAXSEGMENTS);
    sw.segment = segments;
    sw.u.clear();
    sw.v.clear();
    let mut sbox = BoundingBox::EMPTY;
    for i in 0..segments {
        let p = segment_points(sw.curve, &sw.points, i);
        let (mut cu, mut cv) = (Coeff::default(), Coeff::default());
        spline(
            sw.curve, p[0][0], p[1][0], p[2][0], p[3][0], &mut cu, class, 1, &mut sbox,
        );
        spline(
            sw.curve, p[0][1], p[1][1], p[2][1], p[3][1], &mut cv, class, 2, &mut sbox,
        );
        sw.u.push(cu);
        sw.v.push(cv);
    }
    sbox
}

/// The box the listing's class box gets from one sweep: `spline`'s x and
/// y (rotation: x and z) plus what `spline` does not write: the height
/// 0..length of translation and conic sweeps, the conic contour scaled to
/// `scale`; for rotation y copies x (the listing leaves `rbox.y` alone).
fn listing_box(class: PrimitiveClass, sw: &SweepShape, sbox: &BoundingBox) -> BoundingBox {
    let mut b = *sbox;
    match class {
        PrimitiveClass::Rotation => {
            b.ymin = b.xmin;
            b.ymax = b.xmax;
        }
        _ => {
            if class == PrimitiveClass::Conic && sw.scale.is_finite() {
                let s = sw.scale;
                let (x0, x1) = (b.xmin * s, b.xmax * s);
                let (y0, y1) = (b.ymin * s, b.ymax * s);
                b.xmin = b.xmin.min(x0).min(x1);
                b.xmax = b.xmax.max(x0).max(x1);
                b.ymin = b.ymin.min(y0).min(y1);
                b.ymax = b.ymax.max(y0).max(y1);
            }
            b.zmin = 0.0f64.min(sw.length);
            b.zmax = 0.0f64.max(sw.length);
        }
    }
    b
}

/// The object's own local box: as [`listing_box`], but a rotation sweep's
/// x and y span ±(largest radius).
fn own_box(class: PrimitiveClass, sw: &SweepShape, sbox: &BoundingBox) -> BoundingBox {
    let mut b = listing_box(class, sw, sbox);
    if class == PrimitiveClass::Rotation {
        let r = sbox.xmin.abs().max(sbox.xmax.abs());
        (b.xmin, b.xmax, b.ymin, b.ymax) = (-r, r, -r, r);
    }
    b
}

/// Fills every sweep object's `u`, `v`, `segment` and `bbox` from its
/// control points (`spline`, one `Coeff` per segment and coordinate), and
/// widens the object's bounding-sphere `radius` to hold its own box.
///
/// Reconstructed from the thesis's §2.2–2.3 and §3.3 (`spline` is printed;
/// who calls it is not). B-spline segment i uses points i, i+1, i+2, i+3
/// (wrapping, n points give n segments); Bezier segment i uses `P[3i]`,
/// `P[3i+1]`, `P[3i+2]`, `P[3i+3 mod 3k]` (3k points give k). At most 60.
///
/// Erratum 9: `Thesis` gives each object its own box. `Listing` keeps one
/// box per class as the listing's globals `tbox`, `cbox`, `rbox` do: every
/// sweep of a class gets the union of the class's boxes, with a rotation
/// box's x (and y) the radius range min U … max U as `spline` writes it.
pub fn prepare_sweeps(scene: &mut Scene, fidelity: Fidelity) {
    let classes = [
        PrimitiveClass::Translation,
        PrimitiveClass::Conic,
        PrimitiveClass::Rotation,
    ];
    let mut class_box = [BoundingBox::EMPTY; 3];
    // The later key shapes of a keyframe record stood in the Pascal's table
    // too until `goahead` deleted them: they get coefficients and widen
    // the class's box like every other sweep.
    let Scene { objects, keyframes, .. } = scene;
    for obj in objects
        .iter_mut()
        .chain(keyframes.iter_mut().flat_map(|k| k.rest.iter_mut()))
    {
        let class = obj.class;
        let Some(ci) = classes.iter().position(|&c| c == class) else {
            continue;
        };
        let Shape::Sweep(sw) = &mut obj.shape else {
            continue;
        };
        let sbox = fill_segments(class, sw);
        if sw.segment == 0 {
            sw.bbox = BoundingBox::default();
            continue;
        }
        let own = own_box(class, sw, &sbox);
        class_box[ci] = class_box[ci].union(&listing_box(class, sw, &sbox));
        sw.bbox = own;
        let corner = DVec3::new(
            own.xmin.abs().max(own.xmax.abs()),
            own.ymin.abs().max(own.ymax.abs()),
            own.zmin.abs().max(own.zmax.abs()),
        );
        if corner.is_finite() {
            obj.radius = obj.radius.max(corner.length() * (1.0 + 1e-9));
        }
    }
    match fidelity {
        // Erratum 9, listing: `spline` widens the one global box of the
        // class (`tbox`, `cbox`, `rbox`), which every object of it uses.
        Fidelity::Listing => {
            for obj in objects
                .iter_mut()
                .chain(keyframes.iter_mut().flat_map(|k| k.rest.iter_mut()))
            {
                let Some(ci) = classes.iter().position(|&c| c == obj.class) else {
                    continue;
                };
                if let Shape::Sweep(sw) = &mut obj.shape {
                    if sw.segment > 0 {
                        sw.bbox = class_box[ci];
                    }
                }
            }
        }
        // Thesis (§3.3): "the bounding box of each picture" — each
        // object keeps its own.
        Fidelity::Thesis => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(points: &[[f64; 2]], curve: CurveKind) -> SweepShape {
        let mut sw = SweepShape {
            orientt: crate::types::Axis::Z,
            curve,
            points: points.to_vec(),
            segment: 0,
            u: vec![],
            v: vec![],
            length: 2.0,
            scale: 1.0,
            bbox: BoundingBox::default(),
        };
        let sbox = fill_segments(PrimitiveClass::Translation, &mut sw);
        sw.bbox = own_box(PrimitiveClass::Translation, &sw, &sbox);
        sw
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
