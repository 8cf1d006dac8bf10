//! What each method did on a family: the counts and the time of a solve.

use std::time::Instant;

use super::{match_roots, solve, Method, PolyFamily, RayFamily, HIT_TOL, ROOT_TOL, ROUGH_TOL};
use crate::measure::median;

/// What a method did on one family.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    pub cases: usize,
    /// True roots (root families) or true hits (geometric families).
    pub truths: usize,
    pub missed: usize,
    /// Found roots off a true root by more than [`ROOT_TOL`] but not more
    /// than [`ROUGH_TOL`] (root families only; counted among the missed).
    pub rough: usize,
    pub spurious: usize,
    /// Of the roots (hits) found, the largest error (relative to the
    /// object's size for hits).
    pub worst: f64,
    /// Nanoseconds a solve (median of the timing runs).
    pub ns: f64,
    /// Root families: the largest rounding bound ε·Σ|aₖ|wᵏ/|p′(w)| of a
    /// true root w with no found root within [`ROOT_TOL`] (how far the
    /// rounding of the coefficients alone can move it); 0 when none.
    pub worst_bound_missed: f64,
    /// Root families: the largest distance from a missed true root to the
    /// nearest found root within [`ROUGH_TOL`]; 0 when none.
    pub worst_rough: f64,
}

/// How far rounding the coefficients of `a` (degree `n`) can move its
/// simple root `w`: ε·Σ|aₖ|wᵏ/|p′(w)| (infinite at a multiple root).
pub fn rounding_bound(n: usize, a: &[f64; 7], w: f64) -> f64 {
    let sum: f64 = (0..=n).map(|k| a[k].abs() * w.powi(k as i32)).sum();
    let dp: f64 = (1..=n).map(|k| k as f64 * a[k] * w.powi(k as i32 - 1)).sum();
    f64::EPSILON * sum / dp.abs()
}

/// Times `f` over all cases, repeated until each run takes 50 ms; the
/// median of 7 runs, in ns a case.
pub(super) fn time_per_case(cases: usize, mut f: impl FnMut()) -> f64 {
    let mut reps = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..reps {
            f();
        }
        if t.elapsed().as_secs_f64() > 0.05 || reps > 1 << 20 {
            break;
        }
        reps *= 2;
    }
    let runs: Vec<f64> = (0..7)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed().as_secs_f64() * 1e9 / (reps * cases.max(1)) as f64
        })
        .collect();
    median(&runs)
}

pub fn tally_poly(method: Method, fam: &PolyFamily) -> Tally {
    let mut t = Tally {
        cases: fam.cases.len(),
        ..Tally::default()
    };
    for case in &fam.cases {
        let found = solve(method, case);
        let (missed, rough, spurious, worst) = match_roots(&case.roots, &found, ROOT_TOL, ROUGH_TOL);
        t.truths += case.roots.len();
        t.missed += missed;
        t.rough += rough;
        for &w in &case.roots {
            let nearest = found.iter().map(|f| (f.0 - w).abs()).fold(f64::INFINITY, f64::min);
            if nearest > ROOT_TOL {
                t.worst_bound_missed = t.worst_bound_missed.max(rounding_bound(case.n, &case.a, w));
                if nearest <= ROUGH_TOL {
                    t.worst_rough = t.worst_rough.max(nearest);
                }
            }
        }
        t.spurious += spurious;
        t.worst = t.worst.max(worst);
    }
    t.ns = time_per_case(fam.cases.len(), || {
        for case in &fam.cases {
            std::hint::black_box(solve(method, std::hint::black_box(case)));
        }
    });
    t
}

pub fn tally_rays(method: Method, fam: &RayFamily) -> Tally {
    let opts = method.options();
    let mut t = Tally {
        cases: fam.cases.len(),
        ..Tally::default()
    };
    for case in &fam.cases {
        let got = case
            .sweep
            .object()
            .intersect(&case.ray, 1e-9, &opts, &mut 0)
            .map(|h| h.t);
        let tol = HIT_TOL * case.sweep.size;
        if case.truth.is_some() {
            t.truths += 1;
        }
        match (case.truth, got) {
            (Some(want), Some(g)) if (g - want).abs() <= tol => {
                t.worst = t.worst.max((g - want).abs() / case.sweep.size)
            }
            // A farther hit: the true surface was missed.
            (Some(want), Some(g)) if g > want => t.missed += 1,
            (Some(_), Some(_)) => t.spurious += 1,
            (Some(_), None) => t.missed += 1,
            (None, Some(_)) => t.spurious += 1,
            (None, None) => {}
        }
    }
    t.ns = time_per_case(fam.cases.len(), || {
        for case in &fam.cases {
            std::hint::black_box(
                case.sweep
                    .object()
                    .intersect(std::hint::black_box(&case.ray), 1e-9, &opts, &mut 0),
            );
        }
    });
    t
}
