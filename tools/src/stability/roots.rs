//! The root families: constructed polynomials with known roots, solved on
//! [0, 1] by `laguerre` and by the robust solver, and how the roots found
//! are matched to the true ones.

use raytrace::proc::sweep::{laguerre, Root, LAGUERRE_ROOTS};
use raytrace::robust::real_roots;

use super::{poly, Method, Rng};

/// A polynomial of degree `n` and its distinct roots in [0, 1].
#[derive(Clone, Debug)]
pub struct PolyCase {
    pub n: usize,
    pub a: [f64; 7],
    pub roots: Vec<f64>,
}

impl PolyCase {
    /// The polynomial with these roots (a repeated value is a multiple
    /// root, listed once among the true roots).
    pub fn new(all_roots: &[f64]) -> PolyCase {
        let mut roots: Vec<f64> = all_roots.iter().copied().filter(|x| (0.0..=1.0).contains(x)).collect();
        roots.sort_by(f64::total_cmp);
        roots.dedup();
        PolyCase {
            n: all_roots.len(),
            a: poly(all_roots, 1.0),
            roots,
        }
    }
}

/// A family of constructed polynomials.
pub struct PolyFamily {
    pub name: String,
    pub cases: Vec<PolyCase>,
}

/// `count` roots outside [0, 1], in [−1, −0.05] ∪ [1.05, 2].
fn outside(rng: &mut Rng, count: usize) -> Vec<f64> {
    (0..count)
        .map(|_| {
            if rng.uniform() < 0.5 {
                rng.range(-1.0, -0.05)
            } else {
                rng.range(1.05, 2.0)
            }
        })
        .collect()
}

/// Values in [lo, hi] at least `gap` from each other and from `taken`.
fn spread(rng: &mut Rng, count: usize, lo: f64, hi: f64, gap: f64, taken: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(count);
    while out.len() < count {
        let x = rng.range(lo, hi);
        if out.iter().chain(taken).all(|y| (x - y).abs() >= gap) {
            out.push(x);
        }
    }
    out
}

/// The root families, `per` polynomials each, for degrees 3 and 6.
pub fn poly_families(per: usize) -> Vec<PolyFamily> {
    let mut fams = Vec::new();
    for n in [3usize, 6] {
        let deg = if n == 3 { "cubic" } else { "sextic" };
        // For comparison: every root in [0, 1], at least 0.1 apart.
        let mut rng = Rng(0x5EED_0001 + n as u64);
        fams.push(PolyFamily {
            name: format!("separated roots, {deg} (for comparison)"),
            cases: (0..per)
                .map(|_| PolyCase::new(&spread(&mut rng, n, 0.05, 0.98, 0.1, &[])))
                .collect(),
        });
        // Double roots (a grazing ray): d twice in [0.05, 0.95], the others
        // at least 0.05 from it, half of them inside.
        let mut rng = Rng(0x5EED_0002 + n as u64);
        fams.push(PolyFamily {
            name: format!("double roots, {deg}"),
            cases: (0..per)
                .map(|_| {
                    let d = rng.range(0.05, 0.95);
                    let inside = (n - 2) / 2;
                    let mut r = vec![d, d];
                    r.extend(spread(&mut rng, inside, 0.0, 1.0, 0.05, &[d]));
                    r.extend(outside(&mut rng, n - 2 - inside));
                    PolyCase::new(&r)
                })
                .collect(),
        });
        // Near-double roots: d and d + δ, δ of one decade.
        for gap in [1e-3f64, 1e-5, 1e-7] {
            let mut rng = Rng(0x5EED_0003 + n as u64 + (gap.log10().abs() as u64) * 16);
            fams.push(PolyFamily {
                name: format!("near-double roots {gap:.0e} apart, {deg}"),
                cases: (0..per)
                    .map(|_| {
                        let d = rng.range(0.05, 0.9);
                        let delta = gap * rng.range(1.0, 10.0);
                        let mut r = vec![d, d + delta];
                        r.extend(spread(&mut rng, n - 2, 0.0, 1.0, 0.05, &[d, d + delta]));
                        PolyCase::new(&r)
                    })
                    .collect(),
            });
        }
        // Clustered roots: three within 0.002 (spacing 0.0003–0.001), the
        // others apart from the cluster.
        let mut rng = Rng(0x5EED_0004 + n as u64);
        fams.push(PolyFamily {
            name: format!("clustered roots (3 within 0.002), {deg}"),
            cases: (0..per)
                .map(|_| {
                    let c = rng.range(0.1, 0.9);
                    let c2 = c + rng.range(3e-4, 1e-3);
                    let c3 = c2 + rng.range(3e-4, 1e-3);
                    let mut r = vec![c, c2, c3];
                    r.extend(spread(&mut rng, n - 3, 0.0, 1.0, 0.05, &[c, c3]));
                    PolyCase::new(&r)
                })
                .collect(),
        });
    }
    fams
}

/// The roots a method finds on [0, 1], each with its multiplicity (1 for
/// `laguerre`, which has none).
pub fn solve(method: Method, case: &PolyCase) -> Vec<(f64, u8)> {
    match method {
        Method::LaguerreListing | Method::LaguerreThesis => {
            let mut root = [Root::default(); LAGUERRE_ROOTS];
            let total = laguerre(case.n, &case.a, 1.0, 0.0, &mut root, method.options().fidelity);
            root[..total].iter().map(|r| (r.a, 1)).collect()
        }
        Method::Robust => {
            let r = real_roots(case.n, &case.a, 0.0, 1.0);
            (0..r.count).map(|i| (r.x[i], r.multiplicity[i])).collect()
        }
    }
}

/// How found roots match the true ones: (missed, rough, spurious, worst
/// error). Closest pairs within `tol` are matched first; a true root takes
/// one found root, a found root takes as many true roots as its
/// multiplicity (the robust solver reports two roots closer than rounding
/// can part as one double root). An unmatched found root within `rough`
/// of a true root is rough, farther from every true root spurious.
pub fn match_roots(truth: &[f64], found: &[(f64, u8)], tol: f64, rough: f64) -> (usize, usize, usize, f64) {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, t) in truth.iter().enumerate() {
        for (j, f) in found.iter().enumerate() {
            let e = (t - f.0).abs();
            if e <= tol {
                pairs.push((e, i, j));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut true_used = vec![false; truth.len()];
    let mut room: Vec<u8> = found.iter().map(|f| f.1.max(1)).collect();
    let mut matched_found = vec![false; found.len()];
    let mut worst = 0.0f64;
    for (e, i, j) in pairs {
        if !true_used[i] && room[j] > 0 {
            true_used[i] = true;
            room[j] -= 1;
            matched_found[j] = true;
            worst = worst.max(e);
        }
    }
    let missed = true_used.iter().filter(|u| !**u).count();
    let (mut n_rough, mut spurious) = (0, 0);
    for (j, f) in found.iter().enumerate() {
        if !matched_found[j] {
            if truth.iter().any(|t| (t - f.0).abs() <= rough) {
                n_rough += 1;
            } else {
                spurious += 1;
            }
        }
    }
    (missed, n_rough, spurious, worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poly_has_the_roots() {
        let a = poly(&[0.2, 0.5, 0.5], 2.0);
        for x in [0.2f64, 0.5] {
            let y: f64 = (0..7).map(|k| a[k] * x.powi(k as i32)).sum();
            assert!(y.abs() < 1e-15);
        }
        assert_eq!(PolyCase::new(&[0.2, 0.5, 0.5, 1.5]).roots, vec![0.2, 0.5]);
    }

    /// Matching: nearest first, one true root a found root unless the
    /// found root is double; the unmatched found roots are spurious.
    #[test]
    fn matching_counts_missed_and_spurious() {
        let truth = [0.2, 0.4, 0.4 + 1e-8];
        assert_eq!(match_roots(&truth, &[(0.2, 1), (0.4, 1)], 1e-6, 1e-3).0, 1);
        let (m, r, s, w) = match_roots(&truth, &[(0.2, 1), (0.4, 2), (0.9, 1)], 1e-6, 1e-3);
        assert_eq!((m, r, s), (0, 0, 1));
        assert!((w - 1e-8).abs() < 1e-12);
        assert_eq!(match_roots(&truth, &[], 1e-6, 1e-3), (3, 0, 0, 0.0));
        // 1e-5 off: rough, and the true root missed.
        let (m, r, s, _) = match_roots(&[0.5], &[(0.50001, 1)], 1e-6, 1e-3);
        assert_eq!((m, r, s), (1, 1, 0));
    }
}
