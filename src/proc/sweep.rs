//! The sweep procedures of unit `proc` (OCR text lines 1669–2035), in the
//! listing's order: [`laguerre`], [`sorting`], [`spline`], [`outrectp`],
//! [`roottesting`]. The driver that calls them is not printed; it is
//! reconstructed in `shapes::sweep`.
//!
//! Index convention: the listing's root arrays are 1-based (`root[1..10]`,
//! `roots[1..number]`); here they are Rust slices, so the listing's
//! `root[i]` is `root[i - 1]`, and a position returned by [`sorting`] is
//! 0-based. The coefficient array `a[0..n]` of `laguerre` is 0-based in the
//! listing too (a\[k\] multiplies xᵏ) and keeps its indices.
//!
//! Globals of the listing become arguments: the class boxes `tbox`, `cbox`,
//! `rbox` that `spline` widens are passed as the box to widen; `flag` is an
//! argument. Pure outputs of `var` parameters become return values
//! (`laguerre`'s `total`, `sorting`'s `pos`, `outrectp`'s `outrect`).

use crate::types::{BoundingBox, Coeff, CurveKind, PrimitiveClass};

use crate::options::Fidelity;

mod together;
pub use together::laguerre_together;

/// The root record of the listing (the element type of `col` and `co2`):
/// `a` the root, `b` the derivative there (`laguerre` fills it), `c` what
/// `roottesting` compares: how nearly the root is a double one (the sweep
/// driver stores the cosine between the ray and the surface normal, which
/// is 0 for a grazing, double, root).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Root {
    pub a: f64,
    pub b: f64,
    pub c: f64,
}

/// `root[1..10]`: the listing clears ten records before it searches.
pub const LAGUERRE_ROOTS: usize = 10;

/// f, f′ and f″ of the degree-`n` polynomial `a` at `xi`, with the
/// listing's own expressions for n = 3 and n = 6 (so the arithmetic is
/// the same, rounding included) and Horner's rule for the other degrees,
/// which the listing leaves undefined. Inlined, so that where n is known
/// (`laguerre_together`) only its arm is left, the loop unrolled.
#[inline(always)]
fn laguerre_values(n: usize, a: &[f64; 7], xi: f64) -> (f64, f64, f64) {
    match n {
        3 => (
            xi * xi * (a[3] * xi + a[2]) + xi * a[1] + a[0],
            xi * (3.0 * a[3] * xi + 2.0 * a[2]) + a[1],
            6.0 * a[3] * xi + 2.0 * a[2],
        ),
        6 => (
            a[0] + xi * (a[1] + xi * (a[2] + xi * (a[3] + xi * (a[4] + xi * (a[5] + a[6] * xi))))),
            a[1] + xi * (2.0 * a[2] + xi * (3.0 * a[3] + xi * (4.0 * a[4] + xi * (5.0 * a[5] + 6.0 * a[6] * xi)))),
            a[2] * 2.0 + xi * (6.0 * a[3] + xi * (12.0 * a[4] + xi * (20.0 * a[5] + 30.0 * a[6] * xi))),
        ),
        _ => {
            let (mut f1, mut f2, mut f3) = (0.0, 0.0, 0.0);
            // `0..n + 1`, not `0..=n`: a loop the compiler unrolls where n
            // is known.
            for k in (0..n + 1).rev() {
                f3 = f3 * xi + 2.0 * f2;
                f2 = f2 * xi + f1;
                f1 = f1 * xi + a[k];
            }
            (f1, f2, f3)
        }
    }
}

/// `laguerre(n: integer; a: col; max, min: real; var total: integer;
/// root: col)` (unit `proc`, §2.5, OCR lines 1669–1826; ref. Ralston 78):
/// the real roots in [min, max] of `a[0] + a[1]x + … + a[n]xⁿ`, n = 3 or 6.
/// Returns `total`, the number of roots stored in `root[0..total]`.
///
/// As printed: starts at x₀ = 0.98/n and steps by 0.98/n while x₀ < 1 (so
/// n starts); from each start at most 4 iterations of
/// x ← x − n f/(f′ ± √H), H = (n−1)((n−1)f′² − n f f″), the sign that
/// makes the denominator larger; when H < 0, x ← x − n f/f′ instead. A
/// step shorter than 0.0001 that lands in [min, max] is a root: set to 0
/// below 1e-7, dropped if within 0.001 of one already found. A start is
/// abandoned when x leaves [−100, 100]. Then `root[i].b` is set.
///
/// Erratum 7, both fidelities shown where they part:
/// - `root[i].b`: the listing sets `a[1] + x(2a[2] + 3a[3]x)`, the cubic's
///   derivative, also for n = 6 (`Listing`); `Thesis` sets the derivative
///   of the degree-n polynomial.
/// - zero denominators: `Listing` reproduces the arithmetic. With H ≥ 0
///   and f′ = 0 neither branch assigns x2, so x2 keeps the value of the
///   previous step (0 before the first: Pascal left it undefined). With
///   H < 0 and f′ = 0, x − n f/0 is ±∞: it fails the 0.0001 test and
///   trips the ±100 bound, so it is never stored (f ≠ 0 there, since
///   H < 0 needs f f″ > 0, so 0/0 = NaN cannot occur; a NaN would fail
///   every comparison and never be stored either). The stale x2, though,
///   can pass the test at a point that is no root (a constant polynomial
///   gets the "root" 0): the sweep driver rejects every root whose hit
///   point is not on the surface. `Thesis` guards: with H ≥ 0 it divides
///   by f′ ± √H even when f′ = 0; a zero denominator, or f′ = 0 when
///   H < 0, keeps x as a root if f(x) = 0 and abandons the start otherwise.
///
/// Both fidelities keep the printed method otherwise (fixed starts, four
/// iterations, the x − n f/f′ step): it misses roots, which
/// docs/laguerre_misses.md measures.
pub fn laguerre(
    n: usize,
    a: &[f64; 7],
    max: f64,
    min: f64,
    root: &mut [Root; LAGUERRE_ROOTS],
    fidelity: Fidelity,
) -> usize {
    for r in root.iter_mut() {
        r.a = 0.0;
    }
    // The listing has n starts, so at most n roots fit `root[1..10]`.
    if n == 0 || n > 6 {
        return 0;
    }
    let nf = n as f64;
    let mut temp = 0.98 / nf;
    let temp1 = temp;
    let mut total = 0usize;
    let mut x2 = 0.0;
    while temp < 1.0 {
        let mut xi = temp;
        let mut iteration = 1;
        while iteration <= 4 {
            let (f1, f2, f3) = laguerre_values(n, a, xi);
            let mut h = (nf - 1.0) * f2 * f2 - nf * f1 * f3;
            h *= nf - 1.0;
            if h >= 0.0 {
                h = h.sqrt();
                match fidelity {
                    // Erratum 7, listing: `if (f2<0) and (f2-h<>0) then
                    // x2 := xi-n*f1/(f2-h) else if (f2+h<>0) and (f2>0)
                    // then x2 := xi-n*f1/(f2+h)`; f2 = 0 assigns nothing.
                    Fidelity::Listing => {
                        if f2 < 0.0 && (f2 - h) != 0.0 {
                            x2 = xi - nf * f1 / (f2 - h);
                        } else if (f2 + h) != 0.0 && f2 > 0.0 {
                            x2 = xi - nf * f1 / (f2 + h);
                        }
                    }
                    // Thesis (§2.5): x − n f/(f′ ± √H) whenever the
                    // denominator is not 0.
                    Fidelity::Thesis => {
                        let den = if f2 < 0.0 { f2 - h } else { f2 + h };
                        if den != 0.0 {
                            x2 = xi - nf * f1 / den;
                        } else if f1 == 0.0 {
                            x2 = xi;
                        } else {
                            break;
                        }
                    }
                }
            } else {
                match fidelity {
                    // Erratum 7, listing: `x2 := xi-n*f1/f2` unguarded.
                    Fidelity::Listing => x2 = xi - nf * f1 / f2,
                    // Thesis: the same step, not taken when f′ = 0.
                    Fidelity::Thesis => {
                        if f2 != 0.0 {
                            x2 = xi - nf * f1 / f2;
                        } else {
                            break;
                        }
                    }
                }
            }
            if (x2 - xi).abs() < 0.0001 && x2 <= max && x2 >= min {
                if x2 < 0.0000001 {
                    x2 = 0.0;
                }
                let known = root[..total].iter().any(|r| (r.a - x2).abs() <= 0.001);
                if !known {
                    root[total].a = x2;
                    total += 1;
                }
                iteration = 6;
            }
            if x2.abs() > 100.0 {
                iteration = 6;
            }
            xi = x2;
            iteration += 1;
        }
        temp += temp1;
    }
    for r in root[..total].iter_mut() {
        let xi = r.a;
        r.b = match fidelity {
            // Erratum 7, listing: `root[i].b := a[1]+xi*(a[2]*2+xi*a[3]*3)`.
            Fidelity::Listing => a[1] + xi * (a[2] * 2.0 + xi * a[3] * 3.0),
            // Thesis: f′ of the degree-n polynomial, Σ k a[k] x^(k−1).
            Fidelity::Thesis => (1..=n).rev().fold(0.0, |acc, k| acc * xi + k as f64 * a[k]),
        };
    }
    total
}

/// `sorting(tmax: real; number: integer; var roots: co2; pos: integer)`
/// (unit `proc`, OCR lines 1829–1855; ref. van Wijk 84): sorts
/// `roots[0..number]` by `.a` with the printed exchange sort and returns
/// the position (0-based) of the last record whose `.a` equals `tmax`, or
/// `None` where the listing would leave `pos` as it was.
///
/// Erratum 17 (legacy_pascal/DEVIATIONS.md): the listing's swap moves
/// the whole record j to i but only `.a` and `.b` of record i to j, so
/// record j keeps its own `.c` and both end up with j's (`Listing`); Ch. 4
/// says the procedure sorts the records by `root.a`, and `Thesis` swaps
/// whole records. The sweep driver does not call `sorting` (see
/// `shapes::sweep`).
pub fn sorting(tmax: f64, number: usize, roots: &mut [Root], fidelity: Fidelity) -> Option<usize> {
    let number = number.min(roots.len());
    for i in 0..number.saturating_sub(1) {
        for j in i + 1..number {
            if roots[i].a > roots[j].a {
                match fidelity {
                    // Erratum 17, listing: `temp := roots[i].a; temp2 :=
                    // roots[i].b; roots[i] := roots[j]; roots[j].a := temp;
                    // roots[j].b := temp2` — `.c` stays behind.
                    Fidelity::Listing => {
                        let temp = roots[i].a;
                        let temp2 = roots[i].b;
                        roots[i] = roots[j];
                        roots[j].a = temp;
                        roots[j].b = temp2;
                    }
                    // Thesis (Ch. 4: "sort the records of roots by
                    // root.a"): the records trade places.
                    Fidelity::Thesis => roots.swap(i, j),
                }
            }
        }
    }
    let mut pos = None;
    for (i, r) in roots[..number].iter().enumerate() {
        if r.a == tmax {
            pos = Some(i);
        }
    }
    pos
}

/// `spline(Bezier: integer; one, two, three, four: real; var u: coeff;
/// class: primitiveclass; …)` (unit `proc`, §2.2.2–2.2.3, OCR lines
/// 1857–1939): one coordinate of one cubic segment from its four control
/// values, x(t) = a t³ + b t² + c t + d on [first, last] = [0, 1].
///
/// - `bezier == Bspline` (the listing's `Bezier = 0`): T·M_s·G with
///   M_s = ⅙[−1 3 −3 1; 3 −6 3 0; −3 0 3 0; 1 4 1 0].
/// - `Bezier`: T·M_b·P with M_b = [−1 3 −3 1; 3 −6 3 0; −3 3 0 0; 1 0 0 0].
///
/// `min`, `max` bound the four control values (the convex hull holds the
/// curve). Then, as the listing widens the global class box (`tbox`,
/// `cbox`, `rbox`), this widens `bbox`: `flag = 1` the x extent, `flag = 2`
/// the y extent, or for `rotation` the z extent. Erratum 9: the listing
/// keeps one box per class; the caller chooses which box to pass.
#[allow(clippy::too_many_arguments)]
pub fn spline(
    bezier: CurveKind,
    one: f64,
    two: f64,
    three: f64,
    four: f64,
    u: &mut Coeff,
    class: PrimitiveClass,
    flag: u8,
    bbox: &mut BoundingBox,
) {
    match bezier {
        CurveKind::Bspline => {
            u.a = (-one + two * 3.0 + three * (-3.0) + four) / 6.0;
            u.b = (one * 3.0 + two * (-6.0) + three * 3.0) / 6.0;
            u.c = (one * (-3.0) + three * 3.0) / 6.0;
            u.d = (one + two * 4.0 + three) / 6.0;
        }
        CurveKind::Bezier => {
            u.a = -one + two * 3.0 + three * (-3.0) + four;
            u.b = one * 3.0 + two * (-6.0) + three * 3.0;
            u.c = one * (-3.0) + two * 3.0;
            u.d = one;
        }
    }
    u.first = 0.0;
    u.last = 1.0;
    let (temp1, temp2) = if one > two { (two, one) } else { (one, two) };
    let (temp3, temp4) = if three > four { (four, three) } else { (three, four) };
    u.min = if temp1 < temp3 { temp1 } else { temp3 };
    u.max = if temp2 < temp4 { temp4 } else { temp2 };
    let widen = |lo: &mut f64, hi: &mut f64| {
        if u.max > *hi {
            *hi = u.max;
        }
        if u.min < *lo {
            *lo = u.min;
        }
    };
    match (flag, class) {
        (1, PrimitiveClass::Translation | PrimitiveClass::Conic | PrimitiveClass::Rotation) => {
            widen(&mut bbox.xmin, &mut bbox.xmax)
        }
        (2, PrimitiveClass::Translation | PrimitiveClass::Conic) => widen(&mut bbox.ymin, &mut bbox.ymax),
        (2, PrimitiveClass::Rotation) => widen(&mut bbox.zmin, &mut bbox.zmax),
        _ => {}
    }
}

/// `outrectp(u, v: coeff; a, b, c, d, hu, hv: real; var outrect:
/// boolean)` with the nested `inshyp(u, v)` (unit `proc`, OCR lines
/// 1941–1986; ref. van Wijk 84): is the segment's box [u.min, u.max] ×
/// [v.min, v.max] clear of the ray's hyperbola d·u² = a v² + b v + c in
/// the (radius, height) plane of a rotation sweep? (hu, hv) is the
/// hyperbola's vertex, the ray's least radius and its height. `inshyp`
/// is true beyond the hyperbola (a larger radius than the ray has there).
/// Returns `outrect`: `true` means the ray cannot meet this segment.
///
/// As printed: left of the vertex the box is out; above (or below) the
/// vertex, where the branch rises (falls), it is out when its corner
/// nearest the branch from outside is beyond it, or its corner farthest
/// out is not; a box that straddles hv is out when both left corners are
/// beyond the branch.
#[allow(clippy::too_many_arguments)]
pub fn outrectp(u: &Coeff, v: &Coeff, a: f64, b: f64, c: f64, d: f64, hu: f64, hv: f64) -> bool {
    let inshyp = |u: f64, v: f64| (a * v + b) * v + c - d * u * u < 0.0;
    if u.max < hu {
        true
    } else if v.min > hv {
        if inshyp(u.max, v.min) {
            if u.min > hu {
                inshyp(u.min, v.max)
            } else {
                false
            }
        } else {
            true
        }
    } else if v.max < hv {
        if inshyp(u.max, v.max) {
            if u.min > hu {
                inshyp(u.min, v.min)
            } else {
                false
            }
        } else {
            true
        }
    } else if inshyp(u.min, v.min) {
        inshyp(u.min, v.max)
    } else {
        false
    }
}

/// What [`roottesting`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RootTest {
    /// The count was even; nothing changed.
    Even,
    /// The count was odd; the root with the least |c| was duplicated at
    /// the end, so the count is even now.
    Fixed,
    /// The count was odd and could not be made even: the listing's
    /// `writeln('**** impossible ****')`.
    Impossible,
}

/// `roottesting(var number: integer; var root: co2; temp: integer)` (unit
/// `proc`, OCR lines 1988–2017): a ray enters and leaves a closed sweep,
/// so the roots `root[temp..temp + number]` should be even in number. An
/// odd count has lost one root of a double (grazing) pair: the listing
/// copies the root with the least |c| (the first such, `temp+1` when
/// `number = 1`) to `root[temp + number]` and adds one to `number`.
///
/// Erratum 8: the listing then prints `**** impossible ****` if `number`
/// is still odd. As printed that cannot happen (an odd count always gains
/// one), except where the copy has no room: Pascal would stop on a range
/// error; here the count stays odd and the answer is
/// [`RootTest::Impossible`], which the caller sees (the listing's line on
/// standard output is not written). Both fidelities alike.
pub fn roottesting(number: &mut usize, root: &mut [Root], temp: usize) -> RootTest {
    if number.is_multiple_of(2) {
        return RootTest::Even;
    }
    let end = temp + *number;
    if end >= root.len() {
        return RootTest::Impossible;
    }
    // `number = 1`: root[temp+2] := root[temp+1]; the odd case picks the
    // least |c|, the first on ties; for one root both are the same copy.
    let mut pick = temp;
    let mut temp1 = root[temp].c;
    for (i, r) in root.iter().enumerate().take(end).skip(temp + 1) {
        if r.c.abs() < temp1.abs() {
            temp1 = r.c;
            pick = i;
        }
    }
    root[end] = root[pick];
    *number += 1;
    RootTest::Fixed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spline_bspline_coefficients_by_hand() {
        // Points 0, 6, 12, 30: a = (0 + 18 − 36 + 30)/6 = 2,
        // b = (0 − 36 + 36)/6 = 0, c = (0 + 36)/6 = 6, d = (0 + 24 + 12)/6 = 6.
        let mut u = Coeff::default();
        let mut bx = BoundingBox::EMPTY;
        spline(
            CurveKind::Bspline,
            0.0,
            6.0,
            12.0,
            30.0,
            &mut u,
            PrimitiveClass::Translation,
            1,
            &mut bx,
        );
        assert_eq!((u.a, u.b, u.c, u.d), (2.0, 0.0, 6.0, 6.0));
        assert_eq!((u.first, u.last, u.min, u.max), (0.0, 1.0, 0.0, 30.0));
        assert_eq!((bx.xmin, bx.xmax), (0.0, 30.0));
        assert!(bx.ymin.is_infinite() && bx.zmin.is_infinite());
    }

    #[test]
    fn spline_bezier_coefficients_by_hand() {
        // Points 1, 2, 4, 3: a = −1 + 6 − 12 + 3 = −4, b = 3 − 12 + 12 = 3,
        // c = −3 + 6 = 3, d = 1.
        let mut u = Coeff::default();
        let mut bx = BoundingBox::EMPTY;
        spline(
            CurveKind::Bezier,
            1.0,
            2.0,
            4.0,
            3.0,
            &mut u,
            PrimitiveClass::Rotation,
            2,
            &mut bx,
        );
        assert_eq!((u.a, u.b, u.c, u.d), (-4.0, 3.0, 3.0, 1.0));
        assert_eq!((u.min, u.max), (1.0, 4.0));
        // flag 2 of a rotation widens z, not y.
        assert_eq!((bx.zmin, bx.zmax), (1.0, 4.0));
        assert!(bx.ymin.is_infinite() && bx.xmin.is_infinite());
    }

    #[test]
    fn laguerre_cubic_roots() {
        // (t − 0.2)(t − 0.5)(t − 0.8) = t³ − 1.5t² + 0.66t − 0.08.
        let a = [-0.08, 0.66, -1.5, 1.0, 0.0, 0.0, 0.0];
        for fid in [Fidelity::Listing, Fidelity::Thesis] {
            let mut root = [Root::default(); LAGUERRE_ROOTS];
            let total = laguerre(3, &a, 1.0, 0.0, &mut root, fid);
            let mut got: Vec<f64> = root[..total].iter().map(|r| r.a).collect();
            got.sort_by(f64::total_cmp);
            assert_eq!(got.len(), 3, "{fid:?}: {got:?}");
            for (g, w) in got.iter().zip([0.2, 0.5, 0.8]) {
                assert!((g - w).abs() < 1e-9, "{fid:?}: {got:?}");
            }
            // b is f′(root) for a cubic in both fidelities.
            for r in &root[..total] {
                let d = 3.0 * r.a * r.a - 3.0 * r.a + 0.66;
                assert!((r.b - d).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn laguerre_erratum_7_derivative_of_the_sextic() {
        // (t − 0.1)(t − 0.3)(t − 0.45)(t − 0.6)(t − 0.75)(t − 0.9), expanded.
        let roots = [0.1, 0.3, 0.45, 0.6, 0.75, 0.9];
        let a = poly_from_roots(&roots);
        let mut lr = [Root::default(); LAGUERRE_ROOTS];
        let mut tr = [Root::default(); LAGUERRE_ROOTS];
        let nl = laguerre(6, &a, 1.0, 0.0, &mut lr, Fidelity::Listing);
        let nt = laguerre(6, &a, 1.0, 0.0, &mut tr, Fidelity::Thesis);
        assert_eq!(nl, nt);
        assert!(nl >= 1);
        for (l, t) in lr[..nl].iter().zip(&tr[..nt]) {
            assert_eq!(l.a, t.a);
            let x = t.a;
            let cubic = a[1] + 2.0 * a[2] * x + 3.0 * a[3] * x * x;
            let sextic: f64 = (1..=6).map(|k| k as f64 * a[k] * x.powi(k as i32 - 1)).sum();
            assert!((l.b - cubic).abs() < 1e-12, "listing keeps the cubic's f′");
            assert!((t.b - sextic).abs() < 1e-12, "thesis takes the sextic's f′");
            assert!((l.b - t.b).abs() > 1e-6, "the two differ at {x}");
        }
    }

    #[test]
    fn laguerre_erratum_7_stale_step_on_a_constant() {
        // f = 1: f′ = f″ = 0, H = 0, so the listing assigns no step and the
        // stale x2 (0) passes as a root; the thesis abandons the start.
        let a = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let mut root = [Root::default(); LAGUERRE_ROOTS];
        assert_eq!(laguerre(3, &a, 1.0, 0.0, &mut root, Fidelity::Listing), 1);
        assert_eq!(root[0].a, 0.0);
        assert_eq!(laguerre(3, &a, 1.0, 0.0, &mut root, Fidelity::Thesis), 0);
    }

    #[test]
    fn laguerre_erratum_7_division_by_zero_never_stored() {
        // f = (x − x0)² + 1 with x0 the first start: f′(x0) = 0 exactly,
        // H < 0, so the listing divides by zero (x2 = −∞) and gives up on
        // that start; no infinite root is stored.
        let x0 = 0.98 / 3.0;
        let a = [x0 * x0 + 1.0, -2.0 * x0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let (f1, f2, _) = laguerre_values(3, &a, x0);
        assert_eq!(f2, 0.0);
        assert!(f1 > 0.0);
        for fid in [Fidelity::Listing, Fidelity::Thesis] {
            let mut root = [Root::default(); LAGUERRE_ROOTS];
            let total = laguerre(3, &a, 1.0, 0.0, &mut root, fid);
            assert_eq!(total, 0, "{fid:?}");
            assert!(root.iter().all(|r| r.a.is_finite() && r.b.is_finite()));
        }
    }

    /// Erratum 7, where the listing's ±∞ step shows: f′ = 0 exactly at the
    /// first two starts, H < 0 at the first (the ±∞ step) and H ≥ 0 at the
    /// second (no step: x2 is read stale). The listing's stale x2 is ±∞, so
    /// the second start is abandoned and the root comes from the third;
    /// had the first start kept its x2 (the thesis's arm), the second
    /// would go on from there and store the root as its own iterate, which
    /// differs in the last digits.
    #[test]
    fn laguerre_erratum_7_the_infinite_step_abandons_the_next_start() {
        let t1 = 0.98 / 3.0;
        let a = [-0.505, 1.2805333333333333, -2.94, 2.0, 0.0, 0.0, 0.0];
        for x in [t1, t1 + t1] {
            assert_eq!(laguerre_values(3, &a, x).1, 0.0, "f′({x})");
        }
        let h = |x: f64| {
            let (f1, f2, f3) = laguerre_values(3, &a, x);
            2.0 * (2.0 * f2 * f2 - 3.0 * f1 * f3)
        };
        assert!(h(t1) < 0.0 && h(t1 + t1) >= 0.0);
        let mut root = [Root::default(); LAGUERRE_ROOTS];
        assert_eq!(laguerre(3, &a, 2.0, 0.0, &mut root, Fidelity::Listing), 1);
        assert_eq!(root[0].a, 1.0960220387673703);
    }

    #[test]
    fn sorting_orders_and_finds_tmax() {
        for fid in [Fidelity::Listing, Fidelity::Thesis] {
            let mut r: Vec<Root> = [3.0, 1.0, 2.0, 0.5]
                .iter()
                .map(|&a| Root {
                    a,
                    b: 10.0 * a,
                    c: a + 100.0,
                })
                .collect();
            let pos = sorting(2.0, 4, &mut r, fid);
            let a: Vec<f64> = r.iter().map(|x| x.a).collect();
            assert_eq!(a, vec![0.5, 1.0, 2.0, 3.0]);
            assert!(r.iter().all(|x| x.b == 10.0 * x.a), ".b travels with .a");
            assert_eq!(pos, Some(2));
            assert_eq!(sorting(7.0, 4, &mut r, fid), None);
        }
    }

    #[test]
    fn sorting_erratum_17_c_stays_behind() {
        // The swap of 3 and 1: the listing gives slot 1 the record of 1 and
        // slot 2 keeps its own c (of 1); the thesis swaps whole records.
        let rec = || vec![Root { a: 3.0, b: 0.0, c: 3.0 }, Root { a: 1.0, b: 0.0, c: 1.0 }];
        let mut q = rec();
        sorting(0.0, 2, &mut q, Fidelity::Listing);
        assert_eq!((q[0].a, q[0].c, q[1].a, q[1].c), (1.0, 1.0, 3.0, 1.0));
        let mut q = rec();
        sorting(0.0, 2, &mut q, Fidelity::Thesis);
        assert_eq!((q[0].a, q[0].c, q[1].a, q[1].c), (1.0, 1.0, 3.0, 3.0));
    }

    #[test]
    fn outrectp_inside_outside_straddling() {
        // The ray x = 1, y = t, z = t: r² = 1 + z², so a = 1, b = 0, c = 1,
        // d = 1; vertex (hu, hv) = (1, 0).
        let (a, b, c, d, hu, hv) = (1.0, 0.0, 1.0, 1.0, 1.0, 0.0);
        let rect = |umin: f64, umax: f64, vmin: f64, vmax: f64| {
            let u = Coeff {
                min: umin,
                max: umax,
                ..Coeff::default()
            };
            let v = Coeff {
                min: vmin,
                max: vmax,
                ..Coeff::default()
            };
            outrectp(&u, &v, a, b, c, d, hu, hv)
        };
        // Wholly inside the ray's radius: out.
        assert!(rect(0.0, 0.5, -1.0, 1.0));
        // Above the vertex, wholly beyond the branch (r > √(1+z²)): out.
        assert!(rect(3.0, 4.0, 1.0, 2.0));
        // Above the vertex, wholly short of it: out.
        assert!(rect(1.05, 1.2, 1.0, 2.0));
        // Above the vertex, crossed by the branch (√2 at z = 1): in.
        assert!(!rect(1.2, 1.6, 1.0, 2.0));
        // Below the vertex, mirrored: beyond, short, crossed.
        assert!(rect(3.0, 4.0, -2.0, -1.0));
        assert!(rect(1.05, 1.2, -2.0, -1.0));
        assert!(!rect(1.2, 1.6, -2.0, -1.0));
        // Straddling the vertex height: holds the vertex, or beyond it.
        assert!(!rect(0.5, 2.0, -0.5, 0.5));
        assert!(rect(1.5, 2.0, -0.5, 0.5));
        assert!(!rect(1.05, 2.0, -0.5, 0.5));
    }

    fn rec(a: f64, c: f64) -> Root {
        Root { a, b: 0.0, c }
    }

    #[test]
    fn roottesting_one_root() {
        let mut r = [rec(1.0, 0.3), Root::default(), Root::default()];
        let mut n = 1;
        assert_eq!(roottesting(&mut n, &mut r, 0), RootTest::Fixed);
        assert_eq!(n, 2);
        assert_eq!(r[1], r[0]);
    }

    #[test]
    fn roottesting_three_roots_copies_least_c() {
        let mut r = [
            rec(9.0, 0.0),
            rec(1.0, 0.5),
            rec(2.0, -0.01),
            rec(3.0, 0.2),
            Root::default(),
        ];
        // temp = 1: the object's roots are r[1..4].
        let mut n = 3;
        assert_eq!(roottesting(&mut n, &mut r, 1), RootTest::Fixed);
        assert_eq!(n, 4);
        assert_eq!(r[4], rec(2.0, -0.01));
        let mut n = 4;
        assert_eq!(roottesting(&mut n, &mut r, 1), RootTest::Even);
        assert_eq!(n, 4);
    }

    #[test]
    fn roottesting_impossible_when_no_room() {
        let mut r = [rec(1.0, 0.1), rec(2.0, 0.2), rec(3.0, 0.3)];
        let mut n = 3;
        assert_eq!(roottesting(&mut n, &mut r, 0), RootTest::Impossible);
        assert_eq!(n, 3, "the count stays odd");
    }

    /// Ascending coefficients of ∏(x − rᵢ), padded to seven.
    pub(crate) fn poly_from_roots(roots: &[f64]) -> [f64; 7] {
        let mut p = [0.0; 7];
        p[0] = 1.0;
        for (k, &r) in roots.iter().enumerate() {
            for i in (0..=k + 1).rev() {
                let lower = if i > 0 { p[i - 1] } else { 0.0 };
                p[i] = lower - r * p[i];
            }
        }
        p
    }
}
