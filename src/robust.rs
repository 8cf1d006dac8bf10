//! A second root solver for the sweep intersection, not the thesis's (the
//! thesis uses [`laguerre`](crate::proc::sweep::laguerre)): every real root of a
//! polynomial of degree ≤ 6 in an interval.
//!
//! First the cheap answer of the polynomial's Bernstein coefficients on the
//! interval (their sign changes bound the roots, [`real_roots`]): none, or
//! one simple root found by Newton's method, which is what a ray meets on
//! most segments. Where that cannot decide, recursive derivative-root
//! bracketing (after Yuksel 2022, *High-Performance Polynomial Root Finding
//! for Graphics*): the roots of p′ cut the interval into pieces on which p
//! is monotone; a piece whose ends differ in sign holds exactly one simple
//! root, found by Newton's method kept inside the bracket (bisection when a
//! step leaves it; closed form for degrees 1 and 2); a root of p′ where p
//! vanishes (to rounding) is a multiple root, reported once with its
//! multiplicity. The roots of p′ come the same way from p″, down to a
//! linear polynomial.
//!
//! Chosen with `--solver robust` ([`Solver::Robust`](crate::options::Solver)).
//! Allocation-free: fixed arrays of seven coefficients and six roots.

/// The highest degree [`real_roots`] takes (the rotation sweep's sextic).
pub(crate) const MAX_DEGREE: usize = 6;

/// Unit roundoff of f64.
const EPS: f64 = f64::EPSILON;

/// The real roots [`real_roots`] found, ascending.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RealRoots {
    pub count: usize,
    pub x: [f64; MAX_DEGREE],
    /// The multiplicity of each root: 1 for a simple root, 2 for a double
    /// root (a tangency) and so on. Two distinct roots closer than rounding
    /// can tell apart (about √ε of the polynomial's scale) come as one
    /// double root.
    pub multiplicity: [u8; MAX_DEGREE],
    /// Every coefficient is 0 (after dropping negligible leading ones): every
    /// x is a root, and none is listed.
    pub identically_zero: bool,
}

impl RealRoots {
    /// No roots.
    pub const NONE: RealRoots = RealRoots {
        count: 0,
        x: [0.0; MAX_DEGREE],
        multiplicity: [0; MAX_DEGREE],
        identically_zero: false,
    };

    /// The roots, ascending.
    pub fn roots(&self) -> &[f64] {
        &self.x[..self.count]
    }

    fn push(&mut self, x: f64, m: u8) {
        if self.count < MAX_DEGREE {
            self.x[self.count] = x;
            self.multiplicity[self.count] = m;
            self.count += 1;
        }
    }
}

/// p(x), p′(x), and a bound on the rounding error of evaluating p(x) by
/// Horner's rule (with a margin): |p(x)| below it counts as 0.
#[inline(always)]
fn eval3(p: &[f64; 7], m: usize, x: f64) -> (f64, f64, f64) {
    let ax = x.abs();
    let (mut f, mut df, mut s) = (p[m], 0.0, p[m].abs());
    for k in (0..m).rev() {
        df = df * x + f;
        f = f * x + p[k];
        s = s * ax + p[k].abs();
    }
    (f, df, 32.0 * EPS * s)
}

/// The one root of the monotone `p` in (x0, x1), where p(x0), p(x1) differ
/// in sign. Degrees 1 and 2 in closed form; above, Newton's method kept
/// inside the shrinking bracket (bisection when a step leaves it), stopped
/// when the step is at rounding level.
fn bracketed(p: &[f64; 7], m: usize, x0: f64, x1: f64, f0: f64, f1: f64) -> f64 {
    if m <= 2 {
        if let Some(x) = closed_form(p, m, x0, x1) {
            return x;
        }
    }
    newton_in(p, m, x0, x1, f0, x0 - f0 * (x1 - x0) / (f1 - f0))
}

/// Newton's method on `p` from `start`, kept inside the bracket (x0, x1)
/// that holds its one root (p(x0) = `f0`, of the other sign than p(x1));
/// a start outside it becomes the midpoint. Stopped when the step is at
/// rounding level.
pub(crate) fn newton_in(p: &[f64; 7], m: usize, x0: f64, x1: f64, f0: f64, start: f64) -> f64 {
    newton_until(p, m, x0, x1, f0, start, 0.0)
}

/// [`newton_in`], stopped also after a Newton step (not a bisection) of
/// at most `settle`: the root is then nearer than the step by its square
/// (times p″/2p′), so a caller that polishes the root can spare the last
/// steps.
pub(crate) fn newton_until(p: &[f64; 7], m: usize, x0: f64, x1: f64, f0: f64, start: f64, settle: f64) -> f64 {
    // The sweeps' cubics by a body of their own, whose evaluations unroll
    // (the same operations).
    match m {
        3 => newton_steps(|x| eval3(p, 3, x), x0, x1, f0, start, settle),
        _ => newton_steps(|x| eval3(p, m, x), x0, x1, f0, start, settle),
    }
}

/// The steps of [`newton_until`], with `eval` the polynomial's [`eval3`].
#[inline(always)]
fn newton_steps(eval: impl Fn(f64) -> (f64, f64, f64), x0: f64, x1: f64, f0: f64, start: f64, settle: f64) -> f64 {
    let (mut a, mut b, mut fa) = (x0, x1, f0);
    let mut x = if start > x0 && start < x1 {
        start
    } else {
        0.5 * (x0 + x1)
    };
    for _ in 0..200 {
        let (fx, dfx, _) = eval(x);
        if fx == 0.0 {
            return x;
        }
        if (fx < 0.0) == (fa < 0.0) {
            a = x;
            fa = fx;
        } else {
            b = x;
        }
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        let newton = x - fx / dfx;
        let inside = newton > lo && newton < hi;
        let next = if inside { newton } else { 0.5 * (lo + hi) };
        // x, next, lo and hi lie in the bracket, finite: the larger of two
        // by a comparison (`f64::max`'s care for NaN is not needed).
        let larger = |p: f64, q: f64| if p > q { p } else { q };
        let scale = larger(larger(x.abs(), next.abs()), f64::MIN_POSITIVE);
        let step = (next - x).abs();
        // A bisection's step says nothing of the error: only Newton's settles.
        let settled = inside && step <= settle;
        if step <= 2.0 * EPS * scale || settled || hi - lo <= 4.0 * EPS * larger(lo.abs(), hi.abs()) {
            return next;
        }
        x = next;
    }
    x
}

/// The root in [x0, x1] of a line or a quadratic that changes sign there:
/// the quadratic's root of larger magnitude first and the other from the
/// product of the roots (no cancellation), the one in the bracket kept
/// (clamped into it against rounding). `None` when rounding leaves no
/// real root (the caller falls back to Newton's method).
fn closed_form(p: &[f64; 7], m: usize, x0: f64, x1: f64) -> Option<f64> {
    let clamp = |x: f64| x.clamp(x0, x1);
    if m == 1 || p[2] == 0.0 {
        return (p[1] != 0.0).then(|| clamp(-p[0] / p[1]));
    }
    let (qa, qb, qc) = (p[2], p[1], p[0]);
    let disc = qb * qb - 4.0 * qa * qc;
    if disc.is_nan() || disc < 0.0 {
        return None;
    }
    let q = -0.5 * (qb + qb.signum() * disc.sqrt());
    if q == 0.0 {
        return Some(clamp(0.0));
    }
    let (r1, r2) = (q / qa, qc / q);
    let mid = 0.5 * (x0 + x1);
    // The root inside; when rounding puts both out, the nearer.
    let out = |r: f64| {
        if r < x0 {
            x0 - r
        } else if r > x1 {
            r - x1
        } else {
            0.0
        }
    };
    let r = if out(r1) < out(r2) || (out(r1) == out(r2) && (r1 - mid).abs() <= (r2 - mid).abs()) {
        r1
    } else {
        r2
    };
    Some(clamp(r))
}

/// The roots in [lo, hi] of the degree-`m` polynomial `p`, given `crit`,
/// the roots of p′ in [lo, hi] with their multiplicities.
fn level_roots(p: &[f64; 7], m: usize, lo: f64, hi: f64, crit: &RealRoots) -> RealRoots {
    // Break points: lo, the critical points inside, hi; each with its
    // multiplicity as a root of p′ (0 for an end that is not one).
    let mut xs = [0.0; MAX_DEGREE + 2];
    let mut dm = [0u8; MAX_DEGREE + 2];
    let mut len = 1;
    xs[0] = lo;
    let near = |a: f64, b: f64| (a - b).abs() <= 8.0 * EPS * a.abs().max(b.abs()).max(1.0);
    let mut dm_hi = 0;
    for (&c, &mc) in crit.roots().iter().zip(&crit.multiplicity) {
        if c <= lo || near(c, lo) {
            dm[0] = dm[0].max(mc);
        } else if c >= hi || near(c, hi) {
            dm_hi = dm_hi.max(mc);
        } else {
            xs[len] = c;
            dm[len] = mc;
            len += 1;
        }
    }
    if hi > lo {
        xs[len] = hi;
        dm[len] = dm_hi;
        len += 1;
    } else {
        dm[0] = dm[0].max(dm_hi);
    }
    let mut fs = [0.0; MAX_DEGREE + 2];
    let mut zero = [false; MAX_DEGREE + 2];
    for k in 0..len {
        let (f, _, tol) = eval3(p, m, xs[k]);
        fs[k] = f;
        zero[k] = f.abs() <= tol;
    }
    let mut out = RealRoots::NONE;
    for k in 0..len {
        if zero[k] {
            out.push(xs[k], (dm[k] + 1).min(m as u8));
        }
        if k + 1 < len && !zero[k] && !zero[k + 1] && (fs[k] < 0.0) != (fs[k + 1] < 0.0) {
            out.push(bracketed(p, m, xs[k], xs[k + 1], fs[k], fs[k + 1]), 1);
        }
    }
    out
}

/// Every real root in [lo, hi] of `a[0] + a[1]x + … + a[n]xⁿ`, n ≤ 6
/// (coefficients above n are ignored), ascending, each once with its
/// multiplicity.
///
/// Leading coefficients too small to change p anywhere in the interval
/// (`|a[k]|·Mᵏ ≤ 10⁻¹⁵ Σ_{i<k} |a[i]|·Mⁱ`, M = max(|lo|, |hi|, 1)) are
/// dropped, so a degree that has dropped does not throw roots to infinity.
/// Nothing is found for non-finite input or an empty interval.
///
/// Two methods, one answer. First the polynomial's Bernstein coefficients
/// on the interval are counted for sign changes (Descartes' rule of signs
/// in the Bernstein basis: the roots inside, with multiplicity, are at
/// most the changes, and of the same parity). No change: no root. One: one
/// simple root, found by bracketed Newton on p itself. More: the interval
/// is halved (de Casteljau) up to [`HALVINGS`] times and each half counted
/// again. Where a count cannot be trusted (a coefficient within rounding
/// of 0) or the halvings run out, the derivative bracketing of the module
/// doc takes that interval whole; it alone finds multiple roots. The count
/// is the fast path for what a ray meets most: a segment it crosses once.
pub fn real_roots(n: usize, a: &[f64; 7], lo: f64, hi: f64) -> RealRoots {
    let n = n.min(MAX_DEGREE);
    if !lo.is_finite() || !hi.is_finite() || lo > hi || a[..=n].iter().any(|c| !c.is_finite()) {
        return RealRoots::NONE;
    }
    let mut c = [0.0; 7];
    c[..=n].copy_from_slice(&a[..=n]);
    let big = lo.abs().max(hi.abs()).max(1.0);
    // |c[i]|·Mⁱ, and their sums below each degree.
    let mut weighted = [0.0; 7];
    let mut below = [0.0; 8];
    let mut power = 1.0;
    for i in 0..=n {
        weighted[i] = c[i].abs() * power;
        below[i + 1] = below[i] + weighted[i];
        power *= big;
    }
    let mut deg = n;
    while deg > 0 {
        if c[deg] != 0.0 && weighted[deg] > 1e-15 * below[deg] {
            break;
        }
        c[deg] = 0.0;
        deg -= 1;
    }
    if deg == 0 {
        return RealRoots {
            identically_zero: c[0] == 0.0,
            ..RealRoots::NONE
        };
    }
    let mut out = RealRoots::NONE;
    if hi > lo {
        let (b, tiny) = bernstein(deg, &c, lo, hi);
        isolate(&c, deg, &b, tiny, lo, hi, HALVINGS, &mut out);
    } else {
        derivative_roots(&c, deg, lo, hi, &mut out);
    }
    out
}

/// How many times [`real_roots`] halves an interval whose Bernstein
/// coefficients change sign more than once before it brackets by the
/// derivatives: enough to part the two crossings of most rays that enter
/// and leave through one segment, few enough that a tangency (a double
/// root, never parted) costs little before the method that finds it.
pub const HALVINGS: u32 = 3;

/// The sign changes of the Bernstein coefficients `b[..=n]`, or `None` when
/// one of them is within `tiny` of 0 (its sign is rounding's).
fn sign_changes(b: &[f64; 7], n: usize, tiny: f64) -> Option<u32> {
    let mut changes = 0;
    for k in 0..=n {
        if b[k].abs() <= tiny {
            return None;
        }
        if k > 0 && (b[k] < 0.0) != (b[k - 1] < 0.0) {
            changes += 1;
        }
    }
    Some(changes)
}

/// The roots in [x0, x1] of the degree-`n` polynomial `p` whose Bernstein
/// coefficients there are `b`, appended to `out`. Where every coefficient
/// is farther than `tiny` from 0 (so p(x0) = b[0] and p(x1) = b[n] are not
/// roots) the sign count decides; where one is not, the derivative
/// bracketing takes the interval whole (only the first call can meet that
/// with an end at 0: a half whose midpoint is within `tiny` is not made).
#[allow(clippy::too_many_arguments)]
fn isolate(p: &[f64; 7], n: usize, b: &[f64; 7], tiny: f64, x0: f64, x1: f64, halvings: u32, out: &mut RealRoots) {
    match sign_changes(b, n, tiny) {
        Some(0) => {}
        Some(1) => {
            let u = polygon_crossing(n, b);
            out.push(newton_in(p, n, x0, x1, b[0], x0 + u * (x1 - x0)), 1);
        }
        Some(_) if halvings > 0 => {
            let (left, right) = halves(b, n);
            let mid = 0.5 * (x0 + x1);
            if left[n].abs() <= tiny || !(mid > x0 && mid < x1) {
                // p(mid) is within rounding of 0, or the interval is too short to halve.
                derivative_roots(p, n, x0, x1, out);
                return;
            }
            isolate(p, n, &left, tiny, x0, mid, halvings - 1, out);
            isolate(p, n, &right, tiny, mid, x1, halvings - 1, out);
        }
        _ => derivative_roots(p, n, x0, x1, out),
    }
}

/// Where, in [0, 1] of its interval, the control polygon of the Bernstein
/// coefficients `b[..=n]` first crosses 0: Newton's start for the one root
/// of a count of one, nearer the root than the chord's crossing when the
/// curve bends, and the root itself where p is linear.
pub(crate) fn polygon_crossing(n: usize, b: &[f64; 7]) -> f64 {
    let k = (0..n).find(|&k| (b[k] < 0.0) != (b[k + 1] < 0.0)).unwrap_or(0);
    (k as f64 + b[k] / (b[k] - b[k + 1])) / n as f64
}

/// The Bernstein coefficients of the two halves of the interval of `b`
/// (de Casteljau at ½).
fn halves(b: &[f64; 7], n: usize) -> ([f64; 7], [f64; 7]) {
    let mut w = *b;
    let (mut left, mut right) = ([0.0; 7], [0.0; 7]);
    left[0] = w[0];
    right[n] = w[n];
    for k in 1..=n {
        for j in 0..=n - k {
            w[j] = 0.5 * (w[j] + w[j + 1]);
        }
        left[k] = w[0];
        right[n - k] = w[n - k];
    }
    (left, right)
}

/// The roots in [lo, hi] of the degree-`deg` polynomial `c` (leading
/// coefficient not negligible), by the derivative bracketing of the module
/// doc, appended to `out`.
fn derivative_roots(c: &[f64; 7], deg: usize, lo: f64, hi: f64, out: &mut RealRoots) {
    let roots = if deg == 1 {
        level_roots(c, 1, lo, hi, &RealRoots::NONE)
    } else {
        // The derivatives: polys[k] is p⁽ᵏ⁾, of degree deg − k.
        let mut polys = [[0.0; 7]; MAX_DEGREE];
        polys[0] = *c;
        for k in 1..deg {
            for i in 0..deg - k + 1 {
                polys[k][i] = (i + 1) as f64 * polys[k - 1][i + 1];
            }
        }
        // The bottom level, the root of the linear p^(deg−1), in closed
        // form: a break point of the level above, whose ends are
        // evaluated there anyway.
        let lin = &polys[deg - 1];
        let mut roots = RealRoots::NONE;
        let x = -lin[0] / lin[1];
        if x >= lo && x <= hi {
            roots.push(x, 1);
        }
        for k in (0..deg - 1).rev() {
            roots = level_roots(&polys[k], deg - k, lo, hi, &roots);
        }
        roots
    };
    for k in 0..roots.count {
        out.push(roots.x[k], roots.multiplicity[k]);
    }
}

/// Binomial coefficients C(k, j) for k, j ≤ 6.
const BINOMIAL: [[f64; 7]; 7] = [
    [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 2.0, 1.0, 0.0, 0.0, 0.0, 0.0],
    [1.0, 3.0, 3.0, 1.0, 0.0, 0.0, 0.0],
    [1.0, 4.0, 6.0, 4.0, 1.0, 0.0, 0.0],
    [1.0, 5.0, 10.0, 10.0, 5.0, 1.0, 0.0],
    [1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0],
];

/// `BERNSTEIN_WEIGHTS[n][k][j]` = C(k, j) / C(n, j): the power-to-Bernstein
/// weights of degree n on [0, 1], divided once here instead of per segment
/// and ray (the same quotients, so the same results).
const BERNSTEIN_WEIGHTS: [[[f64; 7]; 7]; 7] = {
    let mut r = [[[0.0; 7]; 7]; 7];
    let mut n = 0;
    while n < 7 {
        let mut k = 0;
        while k <= n {
            let mut j = 0;
            while j <= k {
                r[n][k][j] = BINOMIAL[k][j] / BINOMIAL[n][j];
                j += 1;
            }
            k += 1;
        }
        n += 1;
    }
    r
};

/// The Bernstein coefficients on [lo, hi] of the degree-`n` polynomial `a`
/// (ascending power coefficients; n ≤ 6), and the size below which one
/// counts as 0: 10⁻¹² of the largest power coefficient of p(lo + (hi − lo)x)
/// (0 or not finite when that is). The polynomial lies in the convex hull
/// of its Bernstein coefficients, and changes sign inside no more often
/// than they do.
pub(crate) fn bernstein(n: usize, a: &[f64; 7], lo: f64, hi: f64) -> ([f64; 7], f64) {
    // One body per degree, so that each is unrolled (the same operations
    // in the same order whatever the degree: the same results).
    match n {
        0 => bernstein_of::<0>(a, lo, hi),
        1 => bernstein_of::<1>(a, lo, hi),
        2 => bernstein_of::<2>(a, lo, hi),
        3 => bernstein_of::<3>(a, lo, hi),
        4 => bernstein_of::<4>(a, lo, hi),
        5 => bernstein_of::<5>(a, lo, hi),
        _ => bernstein_of::<6>(a, lo, hi),
    }
}

fn bernstein_of<const N: usize>(a: &[f64; 7], lo: f64, hi: f64) -> ([f64; 7], f64) {
    // q(x) = p(lo + (hi − lo)·x): a Taylor shift by lo, then a scaling.
    let mut c = [0.0; 7];
    c[..=N].copy_from_slice(&a[..=N]);
    for i in 0..N {
        for j in (i..N).rev() {
            c[j] += lo * c[j + 1];
        }
    }
    let w = hi - lo;
    let mut wk = 1.0;
    for ck in c.iter_mut().take(N + 1) {
        *ck *= wk;
        wk *= w;
    }
    let tiny = 1e-12 * c[..=N].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (bernstein_unit(N, &c), tiny)
}

/// The Bernstein coefficients on [0, 1] of the degree-`n` polynomial `c`
/// (ascending power coefficients; n ≤ 6): the conversion at the end of
/// [`bernstein`], without its shift to another interval.
pub(crate) fn bernstein_unit(n: usize, c: &[f64; 7]) -> [f64; 7] {
    // One body per degree, as in `bernstein`.
    match n {
        0 => bernstein_unit_of::<0>(c),
        1 => bernstein_unit_of::<1>(c),
        2 => bernstein_unit_of::<2>(c),
        3 => bernstein_unit_of::<3>(c),
        4 => bernstein_unit_of::<4>(c),
        5 => bernstein_unit_of::<5>(c),
        _ => bernstein_unit_of::<6>(c),
    }
}

/// [`bernstein_unit`] of degree `N`.
#[inline(always)]
pub(crate) fn bernstein_unit_of<const N: usize>(c: &[f64; 7]) -> [f64; 7] {
    let mut b = [0.0; 7];
    for (k, wk) in BERNSTEIN_WEIGHTS[N].iter().enumerate().take(N + 1) {
        // b_k = Σ_{j ≤ k} C(k, j) / C(n, j) · c_j
        b[k] = (0..=k).map(|j| wk[j] * c[j]).sum();
    }
    b
}

/// The ascending coefficients of scale·∏(x − rᵢ), padded to seven (at
/// most six roots): a polynomial whose roots are known, to test and
/// measure the solvers with.
pub fn poly_from_roots(roots: &[f64], scale: f64) -> [f64; 7] {
    let mut p = [0.0; 7];
    p[0] = scale;
    for (k, &r) in roots.iter().take(6).enumerate() {
        for i in (0..=k + 1).rev() {
            let lower = if i > 0 { p[i - 1] } else { 0.0 };
            p[i] = lower - r * p[i];
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_three_roots() {
        let a = poly_from_roots(&[0.2, 0.5, 0.8], 1.0);
        let r = real_roots(3, &a, 0.0, 1.0);
        assert_eq!(r.count, 3);
        for (x, w) in r.roots().iter().zip([0.2, 0.5, 0.8]) {
            assert!((x - w).abs() < 1e-14);
        }
        assert_eq!(&r.multiplicity[..3], &[1, 1, 1]);
    }

    /// Stopped after a step of at most `settle`, Newton's method has the
    /// root to about the step's square; with 0 it goes to rounding.
    #[test]
    fn newton_until_settles_at_the_square_of_the_step() {
        let mut early = 0;
        for (k, &root) in [0.13, 0.5, 0.77, 0.999].iter().enumerate() {
            let a = poly_from_roots(&[root, 1.6 + k as f64, -0.4], 1.0);
            let f0 = a[0];
            let exact = newton_in(&a, 3, 0.0, 1.0, f0, 0.9);
            assert!((exact - root).abs() < 1e-15, "{root}: {exact}");
            let settled = newton_until(&a, 3, 0.0, 1.0, f0, 0.9, 1e-2);
            assert!((settled - root).abs() < 1e-3, "{root}: {settled}");
            early += (settled != exact) as usize;
        }
        assert!(early > 0, "a step of 1e-2 stops before rounding");
    }

    /// The control polygon of a line crosses 0 at its root; of a cubic,
    /// inside the segment whose ends differ in sign.
    #[test]
    fn polygon_crossing_of_a_line_is_its_root() {
        for root in [0.0625, 0.3, 0.5, 0.71, 0.96875] {
            let b = bernstein_unit(3, &poly_from_roots(&[root], 2.0));
            assert!((polygon_crossing(3, &b) - root).abs() < 1e-15, "{root}");
        }
        // 1, 1, −1, −1 crosses halfway between its second and third points.
        let b = [1.0, 1.0, -1.0, -1.0, 0.0, 0.0, 0.0];
        assert_eq!(polygon_crossing(3, &b), 0.5);
        let b = [-2.0, 1.0, 3.0, 5.0, 0.0, 0.0, 0.0];
        assert_eq!(polygon_crossing(3, &b), 2.0 / 9.0);
    }

    #[test]
    fn double_root_reported_once() {
        let a = poly_from_roots(&[0.3, 0.6, 0.6], 1.0);
        let r = real_roots(3, &a, 0.0, 1.0);
        assert_eq!(r.count, 2, "{:?}", r);
        assert!((r.x[0] - 0.3).abs() < 1e-12);
        assert!((r.x[1] - 0.6).abs() < 1e-7);
        assert_eq!(&r.multiplicity[..2], &[1, 2]);
    }

    #[test]
    fn triple_root() {
        let a = poly_from_roots(&[0.4, 0.4, 0.4], 2.0);
        let r = real_roots(3, &a, 0.0, 1.0);
        assert_eq!(r.count, 1, "{:?}", r);
        assert!((r.x[0] - 0.4).abs() < 1e-5);
        assert_eq!(r.multiplicity[0], 3);
    }

    #[test]
    fn degree_drop_and_zero() {
        // 1e-20 x⁶ + (x − 0.25)(x − 0.75): a quadratic in disguise.
        let mut a = poly_from_roots(&[0.25, 0.75], 1.0);
        a[6] = 1e-20;
        let r = real_roots(6, &a, 0.0, 1.0);
        assert_eq!(r.roots().len(), 2);
        assert!((r.x[0] - 0.25).abs() < 1e-14 && (r.x[1] - 0.75).abs() < 1e-14);
        let z = real_roots(6, &[0.0; 7], 0.0, 1.0);
        assert!(z.identically_zero && z.count == 0);
        let k = real_roots(3, &[2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], 0.0, 1.0);
        assert!(!k.identically_zero && k.count == 0);
    }

    #[test]
    fn roots_at_the_ends() {
        let a = poly_from_roots(&[0.0, 1.0, 0.5], 1.0);
        let r = real_roots(3, &a, 0.0, 1.0);
        assert_eq!(r.count, 3);
        assert_eq!((r.x[0], r.x[2]), (0.0, 1.0), "the ends exactly");
        assert!((r.x[1] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn bad_input_finds_nothing() {
        let mut a = poly_from_roots(&[0.5], 1.0);
        assert_eq!(real_roots(1, &a, 1.0, 0.0).count, 0);
        a[0] = f64::NAN;
        assert_eq!(real_roots(1, &a, 0.0, 1.0).count, 0);
    }
}
