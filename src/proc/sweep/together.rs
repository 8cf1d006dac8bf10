//! [`laguerre`] under `Fidelity::Thesis`, its starts taken together: the
//! port's arrangement, for speed, of the same steps and the same roots.

#[cfg(doc)]
use super::laguerre;
use super::laguerre_values;

/// [`laguerre`]'s roots (its `root[i].a`, not `.b`) under
/// `Fidelity::Thesis`, for n = `N`, its n starts taken together: one
/// iteration of each live start in turn, where [`laguerre`] runs a start to
/// its end before the next. Under the thesis's guards a start reads
/// nothing another leaves (the stale x2 that a start can read from the one
/// before is `Fidelity::Listing`'s alone), so each start takes the same
/// steps with the same arithmetic (`laguerre_values` of the same n), and
/// its root is stored as [`laguerre`] stores it, in the starts' order,
/// dropped within 0.001 of one stored before: the same roots, to the bit,
/// in the same order. Together, the starts' chains of square roots and
/// divisions, each waiting on its own start's last, overlap in the
/// processor: a blob's quartic (4 starts of 4 iterations) in half the time
/// (docs/performance.md, "Blobs and patches"). Returns how many roots are
/// in `out[..total]`.
pub fn laguerre_together<const N: usize>(a: &[f64; 7], max: f64, min: f64, out: &mut [f64; 6]) -> usize {
    const { assert!(N >= 1 && N <= 6) };
    let nf = N as f64;
    // The starts as [`laguerre`] makes them, 0.98/n added up while < 1:
    // n of them.
    let temp1 = 0.98 / nf;
    let mut xi = [0.0; N];
    let mut temp = temp1;
    for x in xi.iter_mut() {
        *x = temp;
        temp += temp1;
    }
    debug_assert!(temp >= 1.0);
    // Each start's root once found, and whether it still iterates.
    let mut found = [None; N];
    let mut live = [true; N];
    for _ in 0..4 {
        for j in 0..N {
            if !live[j] {
                continue;
            }
            let (f1, f2, f3) = laguerre_values(N, a, xi[j]);
            let mut h = (nf - 1.0) * f2 * f2 - nf * f1 * f3;
            h *= nf - 1.0;
            // [`laguerre`]'s `Fidelity::Thesis` arms; where it breaks, the
            // start ends.
            let x2 = if h >= 0.0 {
                let h = h.sqrt();
                let den = if f2 < 0.0 { f2 - h } else { f2 + h };
                if den != 0.0 {
                    xi[j] - nf * f1 / den
                } else if f1 == 0.0 {
                    xi[j]
                } else {
                    live[j] = false;
                    continue;
                }
            } else if f2 != 0.0 {
                xi[j] - nf * f1 / f2
            } else {
                live[j] = false;
                continue;
            };
            if (x2 - xi[j]).abs() < 0.0001 && x2 <= max && x2 >= min {
                found[j] = Some(x2);
                live[j] = false;
            } else if x2.abs() > 100.0 {
                live[j] = false;
            }
            xi[j] = x2;
        }
    }
    let mut total = 0;
    for mut x2 in found.into_iter().flatten() {
        if x2 < 0.0000001 {
            x2 = 0.0;
        }
        if !out[..total].iter().any(|r| (r - x2).abs() <= 0.001) {
            out[total] = x2;
            total += 1;
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::super::{laguerre, Root, LAGUERRE_ROOTS};
    use super::*;
    use crate::hash::hashed_uniform;
    use crate::options::Fidelity;

    /// [`laguerre`]'s roots under `Fidelity::Thesis`, in its order.
    fn one_by_one(n: usize, a: &[f64; 7], max: f64, min: f64) -> Vec<u64> {
        let mut root = [Root::default(); LAGUERRE_ROOTS];
        let total = laguerre(n, a, max, min, &mut root, Fidelity::Thesis);
        root[..total].iter().map(|r| r.a.to_bits()).collect()
    }

    fn together(n: usize, a: &[f64; 7], max: f64, min: f64) -> Vec<u64> {
        let mut out = [0.0; 6];
        let total = match n {
            3 => laguerre_together::<3>(a, max, min, &mut out),
            4 => laguerre_together::<4>(a, max, min, &mut out),
            _ => laguerre_together::<6>(a, max, min, &mut out),
        };
        out[..total].iter().map(|r| r.to_bits()).collect()
    }

    /// The expanded coefficients of s·Π(x − rₖ).
    fn from_roots(roots: &[f64], s: f64) -> [f64; 7] {
        let mut p = [0.0; 7];
        p[0] = s;
        for (k, r) in roots.iter().enumerate() {
            for j in (0..=k + 1).rev() {
                p[j] = if j > 0 { p[j - 1] } else { 0.0 } - r * p[j];
            }
        }
        p
    }

    /// The same roots, bit for bit and in the same order, as [`laguerre`]
    /// under the thesis's fidelity: cubics, quartics and sextics with roots
    /// in and about [0, 1], close pairs and double roots among them (where
    /// several starts reach one root and the 0.001 rule keeps the first),
    /// roots near 0 (set to 0), and the guards' cases (a constant, f′ = 0
    /// at a start, a start that leaves by the ±100 bound, ±∞ and NaN
    /// coefficients).
    #[test]
    fn the_same_roots_as_laguerre() {
        let (min, max) = (-1e-9, 1.0 + 1e-9);
        let mut several = 0;
        for k in 0..6000u64 {
            let r = |j: u64| hashed_uniform(16 * k + j);
            let n = [3, 4, 6][(k % 3) as usize];
            let mut roots: Vec<f64> = (0..n).map(|j| 1.6 * r(j as u64) - 0.3).collect();
            match k % 5 {
                // A double root, or a pair closer than 0.001.
                0 => roots[1] = roots[0],
                1 => roots[1] = roots[0] + 0.0005 * r(9),
                // A root a hair from 0.
                2 => roots[0] = 1.2e-7 * r(10) - 1e-8,
                _ => {}
            }
            // A complex pair in place of two roots, now and then.
            let mut a = from_roots(&roots, 0.5 + r(11));
            if k % 7 == 0 {
                a[0] += 0.01 * r(12);
            }
            let want = one_by_one(n, &a, max, min);
            several += usize::from(want.len() > 1);
            assert_eq!(together(n, &a, max, min), want, "n = {n}, polynomial {k}: {a:?}");
        }
        assert!(several > 1000, "{several}");
        let t1 = 0.98 / 3.0;
        let cases: [[f64; 7]; 7] = [
            [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            // A cubic whose start at 2·0.98/3 steps to −123, past the
            // ±100 bound where it ends, and would come back to its root
            // near 0.040 if it went on (found by a search of random cubics).
            [
                -0.7288668077044209,
                20.30689421314298,
                -56.48748707243826,
                41.783639081278515,
                0.0,
                0.0,
                0.0,
            ],
            [0.0; 7],
            [t1 * t1 + 1.0, -2.0 * t1, 1.0, 0.0, 0.0, 0.0, 0.0],
            [-0.505, 1.2805333333333333, -2.94, 2.0, 0.0, 0.0, 0.0],
            [f64::INFINITY, 1.0, -3.0, 1.0, 2.0, 0.0, 1.0],
            [0.25, f64::NAN, 1.0, -2.0, 1.0, 0.5, -1.0],
        ];
        for a in cases {
            for n in [3, 4, 6] {
                for (min, max) in [(min, max), (0.0, 2.0)] {
                    assert_eq!(together(n, &a, max, min), one_by_one(n, &a, max, min), "n = {n}: {a:?}");
                }
            }
        }
    }
}
