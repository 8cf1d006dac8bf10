//! A second root solver for the sweep intersection, not the thesis's (the
//! thesis uses [`laguerre`](super::sweep::laguerre)): every real root of a
//! polynomial of degree ≤ 6 in an interval, by recursive derivative-root
//! bracketing. The roots of p′ cut the interval into pieces on which p is
//! monotone; a piece whose ends differ in sign holds exactly one simple
//! root, found by Newton's method kept inside the bracket (bisection when
//! a step leaves it); a root of p′ where p vanishes (to rounding) is a
//! multiple root, reported once with its multiplicity. The roots of p′
//! come the same way from p″, down to a linear polynomial.
//!
//! Chosen with `--solver robust` ([`Solver::Robust`](crate::types::Solver)).
//! Allocation-free: fixed arrays of seven coefficients and six roots.

/// The highest degree [`real_roots`] takes (the rotation sweep's sextic).
pub const MAX_DEGREE: usize = 6;

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

/// p(x) and p′(x) of the degree-`m` polynomial `p` (ascending coefficients).
fn eval2(p: &[f64; 7], m: usize, x: f64) -> (f64, f64) {
    let (mut f, mut df) = (p[m], 0.0);
    for k in (0..m).rev() {
        df = df * x + f;
        f = f * x + p[k];
    }
    (f, df)
}

/// A bound on the rounding error of evaluating `p` at x by Horner's rule
/// (with a margin): |p(x)| below it counts as 0.
fn zero_tol(p: &[f64; 7], m: usize, x: f64) -> f64 {
    let ax = x.abs();
    let mut s = 0.0;
    for k in (0..=m).rev() {
        s = s * ax + p[k].abs();
    }
    32.0 * EPS * s
}

/// The one root of the monotone `p` in (x0, x1), where p(x0), p(x1) differ
/// in sign: Newton's method kept inside the shrinking bracket.
fn bracketed(p: &[f64; 7], m: usize, x0: f64, x1: f64, f0: f64, f1: f64) -> f64 {
    let (mut a, mut b, mut fa) = (x0, x1, f0);
    let secant = x0 - f0 * (x1 - x0) / (f1 - f0);
    let mut x = if secant > x0 && secant < x1 {
        secant
    } else {
        0.5 * (x0 + x1)
    };
    for _ in 0..200 {
        let (fx, dfx) = eval2(p, m, x);
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
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let scale = x.abs().max(next.abs()).max(f64::MIN_POSITIVE);
        if (next - x).abs() <= 2.0 * EPS * scale || hi - lo <= 4.0 * EPS * lo.abs().max(hi.abs()) {
            return next;
        }
        x = next;
    }
    x
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
        fs[k] = eval2(p, m, xs[k]).0;
        zero[k] = fs[k].abs() <= zero_tol(p, m, xs[k]);
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
pub fn real_roots(n: usize, a: &[f64; 7], lo: f64, hi: f64) -> RealRoots {
    let n = n.min(MAX_DEGREE);
    if !lo.is_finite() || !hi.is_finite() || lo > hi || a[..=n].iter().any(|c| !c.is_finite()) {
        return RealRoots::NONE;
    }
    let mut c = [0.0; 7];
    c[..=n].copy_from_slice(&a[..=n]);
    let big = lo.abs().max(hi.abs()).max(1.0);
    let mut deg = n;
    while deg > 0 {
        let lower: f64 = (0..deg).map(|i| c[i].abs() * big.powi(i as i32)).sum();
        if c[deg] != 0.0 && c[deg].abs() * big.powi(deg as i32) > 1e-15 * lower {
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
    // The derivatives: polys[k] is p⁽ᵏ⁾, of degree deg − k.
    let mut polys = [[0.0; 7]; MAX_DEGREE];
    polys[0] = c;
    for k in 1..deg {
        for i in 0..deg - k + 1 {
            polys[k][i] = (i + 1) as f64 * polys[k - 1][i + 1];
        }
    }
    let mut roots = RealRoots::NONE;
    for k in (0..deg).rev() {
        roots = level_roots(&polys[k], deg - k, lo, hi, &roots);
    }
    roots
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
