//! The adaptive sampler's allocation: how many rays each pixel should
//! have after a pass ([`Allocation::allocate`]), from the spreads of its
//! samples so far. Between the passes, on one thread: a few loops over the
//! pixels. A render's passes share one [`Allocation`], which keeps each
//! pixel's spread and cost from the pass before and computes them again
//! only for the pixels the pass gave samples (at 9 rays a pixel, about
//! half of them a pass); the needs, from the spreads around each pixel,
//! are loops over rows of numbers. (The first form of this code, kept in the tests as the
//! reference the counts must equal, computed every spread every pass, in
//! loops with a branch a pixel, and took about 220 instructions a sample
//! of an adaptive render of fig5_3 at 160×135 pixels and 9 rays a pixel,
//! this one about 110; docs/performance.md.)

use super::rounding::Rounding;
use super::{cost, PixelSum, CAP, NEIGHBOUR};

/// The allocation of one render's passes: what [`Allocation::allocate`]
/// keeps of each pixel from one pass to the next, and the buffers of a
/// pass, kept for the next (allocated, zeroed and copied each pass they
/// took about 13 instructions a sample of fig5_3 at 9 rays a pixel).
#[derive(Clone, Debug, Default)]
pub struct Allocation {
    width: usize,
    /// Each pixel's samples when its spread and cost were last computed
    /// (none before the first allocation): a pixel's sum changes only by
    /// samples added, so a pixel whose count is the same has the same
    /// spread and cost.
    seen: Option<Vec<u32>>,
    spread: Vec<f64>,
    cost: Vec<f64>,
    /// Each pixel's bounds: its count so far, and that or the cap.
    low: Vec<f64>,
    high: Vec<f64>,
    /// The largest spread of the 3 pixels of the row around each.
    across: Vec<f64>,
    need: Vec<f64>,
    rounding: Rounding,
}

/// The counts every pixel of a `width`×`height` image should have after
/// the next pass, as [`Allocation::allocate`] of a new allocation.
pub fn allocate(sums: &[PixelSum], width: usize, budget: u32, extra: u64, quantum: u32) -> Vec<u32> {
    Allocation::new(width).allocate(sums, budget, extra, quantum)
}

impl Allocation {
    /// The allocation of the passes over an image `width` pixels wide.
    pub fn new(width: usize) -> Self {
        Allocation {
            width,
            ..Allocation::default()
        }
    }

    /// The counts every pixel of the image should have after the next
    /// pass, `spent` + its share of `extra` more rays in all, from `sums`,
    /// the sums of the pixels (row by row) after the passes so far.
    ///
    /// A pixel's need w is its spread σ, or [`NEIGHBOUR`] times the largest
    /// spread around it if that is more, to the power [`NEED_POWER`](super::NEED_POWER), over
    /// the cost of its rays ([`cost`](super::cost): a pixel of sweeps whose
    /// rays search many polynomials gets a little less). To make
    /// the summed error Σ σ²/n smallest for a fixed total, counts grow with σ
    /// (Neyman allocation): the new counts are max(n, λ·w), at most [`CAP`] times the
    /// average `budget`, with λ found so they add up to the total; then
    /// rounded to whole counts of n or multiples of `quantum` (the render's
    /// is [`quantum`](super::quantum) of the budget), by the largest fractions of the way to
    /// the next (ties to the first pixel; `Rounding::round`). When no pixel
    /// shows any spread, the rays go evenly, to within a quantum.
    pub fn allocate(&mut self, sums: &[PixelSum], budget: u32, extra: u64, quantum: u32) -> Vec<u32> {
        if sums.is_empty() || extra == 0 || self.width == 0 {
            return sums.iter().map(|s| s.n).collect();
        }
        self.needs(sums);
        let counts = self.seen.as_deref().unwrap_or_default();
        // The cap a whole number of quanta, so that every level below it is
        // one quantum from the next.
        let q = quantum.max(1);
        let cap = (budget.saturating_mul(CAP).max(1) / q * q).max(q) as f64;
        // Each pixel's bounds (extended from empty: neither zeroed first
        // nor checked for room pixel by pixel), and the rays spent and the
        // room below the caps, in integers: the sums of whole numbers in
        // floating point were exact too.
        let (low, high) = (&mut self.low, &mut self.high);
        low.clear();
        low.extend(counts.iter().map(|&n| n as f64));
        high.clear();
        high.extend(low.iter().map(|&n| cap.max(n)));
        let (mut spent, mut room) = (0u64, 0u64);
        for &n in counts {
            spent += n as u64;
            room += (cap as u32 - n.min(cap as u32)) as u64;
        }
        let (need, low, high) = (&self.need, &self.low, &self.high);
        let total = (spent + extra) as f64;
        if room <= extra {
            // More rays than the caps hold: every pixel to its cap.
            return high.iter().map(|&h| h as u32).collect();
        }
        let lambda = solve_lambda(need, low, high, total);
        let real = need.iter().zip(low.iter().zip(high)).map(|(&w, (&low, &high))| {
            // Most pixels stay at their count: no clamp to compute.
            let t = lambda * w;
            if t <= low {
                low
            } else {
                t.clamp(low, high)
            }
        });
        self.rounding.round(real, counts, spent + extra, cap as u32, quantum)
    }

    /// Each pixel's need w of [`Allocation::allocate`]: its spread σ, or
    /// [`NEIGHBOUR`] times the largest spread of the 3×3 pixels around it if
    /// that is more, to the power [`NEED_POWER`](super::NEED_POWER), over its [`cost`]; at
    /// least a thousandth of the largest need, so that pixels without
    /// spread can take rays when the others are at the cap (and share them
    /// evenly when no pixel shows any). A pixel's spread and cost are
    /// computed again only when it has new samples (its count is kept in
    /// `seen`); the rest are loops over rows of numbers, without a branch
    /// at the image's edges, which the compiler does two pixels at a time.
    pub(super) fn needs(&mut self, sums: &[PixelSum]) -> &[f64] {
        let width = self.width;
        match &mut self.seen {
            Some(seen) if seen.len() == sums.len() => {
                let kept = seen.iter_mut().zip(self.spread.iter_mut().zip(&mut self.cost));
                for (s, (seen, (spread, c))) in sums.iter().zip(kept) {
                    if *seen != s.n {
                        *seen = s.n;
                        *spread = s.spread();
                        *c = cost(s);
                    }
                }
            }
            _ => {
                // A new image: every pixel's spread and cost, collected
                // (the buffers are not zeroed first).
                self.seen = Some(sums.iter().map(|s| s.n).collect());
                self.spread = sums.iter().map(PixelSum::spread).collect();
                self.cost = sums.iter().map(cost).collect();
            }
        }
        // The largest spread of the 3 pixels of the row around each, with
        // none beyond the edges (pixels past the last whole row have none
        // and no need but the floor): the larger of each and the one
        // before, then of that and the one after. The buffers here and
        // below are extended from empty, neither zeroed first nor checked
        // for room pixel by pixel.
        let across = &mut self.across;
        across.clear();
        for row in self.spread.chunks_exact(width) {
            let start = across.len();
            across.push(row[0]);
            across.extend(row.iter().zip(&row[1..]).map(|(&left, &mid)| larger(mid, left)));
            for (a, &right) in across[start..].iter_mut().zip(&row[1..]) {
                *a = larger(*a, right);
            }
        }
        let none = vec![0.0; width];
        let rows = across.len() / width;
        let row = |y: usize| match y {
            y if y < rows => &across[y * width..(y + 1) * width],
            _ => &none[..],
        };
        let need = &mut self.need;
        need.clear();
        let mut top = 0.0f64;
        for y in 0..rows {
            let (mid, up, down) = (row(y), row(y.wrapping_sub(1)), row(y + 1));
            let at = y * width..(y + 1) * width;
            let (spread, cost) = (&self.spread[at.clone()], &self.cost[at.clone()]);
            need.extend((0..width).map(|x| {
                let w = larger(spread[x], NEIGHBOUR * larger(larger(mid[x], up[x]), down[x]));
                // w^¾ ([`NEED_POWER`](super::NEED_POWER)) in two square roots, an
                // instruction each, where `powf` took a quarter of the
                // allocation's time.
                (w * w.sqrt()).sqrt() / cost[x]
            }));
            top = need[at].iter().fold(top, |t, &w| larger(t, w));
        }
        need.resize(sums.len(), 0.0);
        let floor = if top > 0.0 { top * 1e-3 } else { 1.0 };
        for w in need.iter_mut() {
            *w = larger(*w, floor);
        }
        need
    }
}

/// The larger of two spreads or needs, `f64::max` where neither is NaN (a
/// spread is not: [`PixelSum::spread`] takes the variance's larger with 0,
/// which drops a NaN, and a need is a spread's power over a cost of 1 or
/// more), nor −0: one comparison, where `max` looks for a NaN too.
fn larger(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// The λ of [`Allocation::allocate`]: Σ clamp(λ·need, low, high) reaches
/// `total`, by less than half a ray beyond it (the rounding then hands out
/// the rest exactly), where a pixel's low is its count so far and its high
/// that or the cap, whichever is more. The sum is piecewise linear and
/// grows with λ; Newton's steps on it, kept inside a bracket that halves
/// when a step would leave it, take a handful of sums where bisection
/// takes twenty or more. `total` must lie between Σ low and Σ high.
pub(super) fn solve_lambda(need: &[f64], low: &[f64], high: &[f64], total: f64) -> f64 {
    lambda_newton(|l| bounded_sum(l, need, low, high), need.iter().sum::<f64>(), total)
}

/// The sum of [`solve_lambda`] at λ = `l`, Σ clamp(λ·need, low, high)
/// over the pixels in order, and its slope (the needs of the pixels not
/// at a bound). Four pixels at a time: most are at their low bound, and
/// four of those are found in one branch (the compiler compares them two
/// at a time) and added in order, the same sums to the bit; about 5.3
/// instructions a pixel where one at a time took 6, in the 7 or so sums
/// of a pass (fig5_3, 9 rays a pixel).
fn bounded_sum(l: f64, need: &[f64], low: &[f64], high: &[f64]) -> (f64, f64) {
    let add = |(sum, slope): (f64, f64), w: f64, low: f64, high: f64| {
        let t = l * w;
        if t <= low {
            (sum + low, slope)
        } else if t >= high {
            (sum + high, slope)
        } else {
            (sum + t, slope + w)
        }
    };
    let mut at = (0.0, 0.0);
    let (need, low, high) = (need.chunks_exact(4), low.chunks_exact(4), high.chunks_exact(4));
    let rest = need.remainder().iter().zip(low.remainder()).zip(high.remainder());
    for ((w, low), high) in need.zip(low).zip(high) {
        // `&`, not `&&`: the four comparisons without a branch each.
        let at_low = (l * w[0] <= low[0]) & (l * w[1] <= low[1]) & (l * w[2] <= low[2]) & (l * w[3] <= low[3]);
        if at_low {
            // The four additions of `add`, in their order.
            at.0 += low[0];
            at.0 += low[1];
            at.0 += low[2];
            at.0 += low[3];
        } else {
            for k in 0..4 {
                at = add(at, w[k], low[k], high[k]);
            }
        }
    }
    for ((&w, &low), &high) in rest {
        at = add(at, w, low, high);
    }
    at
}

/// The Newton steps of [`solve_lambda`] on the sum `sum_at(λ)` = (Σ,
/// slope), from λ = `total`/`need_sum` (where the counts would add up
/// without their bounds).
pub(super) fn lambda_newton(sum_at: impl Fn(f64) -> (f64, f64), need_sum: f64, total: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, total / need_sum);
    let mut at = sum_at(hi);
    while at.0 < total {
        (lo, hi) = (hi, hi * 2.0);
        at = sum_at(hi);
    }
    let mut lambda = hi;
    for _ in 0..100 {
        let (sum, slope) = at;
        if sum >= total {
            hi = lambda;
            if sum - total < 0.5 {
                return hi;
            }
        } else {
            lo = lambda;
        }
        let step = if slope > 0.0 {
            lambda + (total - sum) / slope
        } else {
            f64::NAN
        };
        // Aim a little beyond the total, so that a step from below lands
        // above it rather than just short.
        let step = if sum < total && slope > 0.0 {
            step + 0.25 / slope
        } else {
            step
        };
        lambda = if step > lo && step < hi { step } else { 0.5 * (lo + hi) };
        at = sum_at(lambda);
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::super::{quantum, Intensity, COST_POWER, NEED_POWER, SEARCH_COST};
    use super::*;
    use crate::hash::hashed_uniform;

    /// The needs of a new allocation.
    fn needs(sums: &[PixelSum], width: usize) -> Vec<f64> {
        Allocation::new(width).needs(sums).to_vec()
    }

    /// The allocation as it was first written (separate collections), the
    /// reference the fused loops must give the same counts as. The λ is
    /// the module's own (its sums were not changed).
    mod plain {
        use super::super::super::{cost, PixelSum, CAP, NEIGHBOUR};
        use super::super::solve_lambda;

        pub(super) fn allocate(sums: &[PixelSum], width: usize, budget: u32, extra: u64, quantum: u32) -> Vec<u32> {
            let counts: Vec<u32> = sums.iter().map(|s| s.n).collect();
            if sums.is_empty() || extra == 0 || width == 0 {
                return counts;
            }
            let need = needs(sums, width);
            // The cap a whole number of quanta, so that every level below it is
            // one quantum from the next.
            let q = quantum.max(1);
            let cap = (budget.saturating_mul(CAP).max(1) / q * q).max(q) as f64;
            let spent: u64 = counts.iter().map(|&n| n as u64).sum();
            let room: f64 = counts.iter().map(|&n| cap - (n as f64).min(cap)).sum();
            let total = (spent + extra) as f64;
            let low: Vec<f64> = counts.iter().map(|&n| n as f64).collect();
            let high: Vec<f64> = low.iter().map(|&n| cap.max(n)).collect();
            if room <= extra as f64 {
                // More rays than the caps hold: every pixel to its cap.
                return high.iter().map(|&h| h as u32).collect();
            }
            let lambda = solve_lambda(&need, &low, &high, total);
            let real: Vec<f64> = (0..need.len())
                .map(|i| (lambda * need[i]).clamp(low[i], high[i]))
                .collect();
            round_counts(&real, &counts, spent + extra, cap as u32, quantum)
        }

        /// The needs as first written: every pixel's, every pass.
        fn needs(sums: &[PixelSum], width: usize) -> Vec<f64> {
            let spread: Vec<f64> = sums.iter().map(PixelSum::spread).collect();
            let mut across = vec![0.0; sums.len()];
            for (row, out) in spread.chunks_exact(width).zip(across.chunks_exact_mut(width)) {
                for x in 0..width {
                    let left = if x > 0 { row[x - 1] } else { 0.0 };
                    let right = if x + 1 < width { row[x + 1] } else { 0.0 };
                    out[x] = row[x].max(left).max(right);
                }
            }
            let height = sums.len() / width;
            let mut need = vec![0.0; sums.len()];
            let mut top = 0.0f64;
            for y in 0..height {
                for x in 0..width {
                    let i = y * width + x;
                    let up = if y > 0 { across[i - width] } else { 0.0 };
                    let down = if y + 1 < height { across[i + width] } else { 0.0 };
                    let w = spread[i].max(NEIGHBOUR * across[i].max(up).max(down));
                    need[i] = (w * w.sqrt()).sqrt() / cost(&sums[i]);
                    top = top.max(need[i]);
                }
            }
            let floor = if top > 0.0 { top * 1e-3 } else { 1.0 };
            for w in &mut need {
                *w = w.max(floor);
            }
            need
        }

        fn round_counts(real: &[f64], low: &[u32], total: u64, cap: u32, quantum: u32) -> Vec<u32> {
            let q = quantum.max(1);
            let mut out: Vec<u32> = (0..real.len()).map(|i| (real[i] as u32 / q * q).max(low[i])).collect();
            // The level above each (a candidate if not beyond the cap).
            let next: Vec<u32> = out.iter().map(|&f| (f / q + 1) * q).collect();
            let fraction: Vec<f64> = (0..out.len())
                .map(|i| (real[i] - out[i] as f64) / (next[i] - out[i]) as f64)
                .collect();
            let given: u64 = out.iter().map(|&n| n as u64).sum();
            let mut left = total.saturating_sub(given);
            // The candidates with a fraction, and those without (most: the
            // pixels that keep their count), which come after them in their order.
            let (mut candidates, without): (Vec<usize>, Vec<usize>) = (0..out.len())
                .filter(|&i| next[i] <= cap)
                .partition(|&i| fraction[i] > 0.0);
            let mut without = without.into_iter();
            // The first k candidates in the order of the largest fraction: only
            // which pixels they are matters, not their order, so a selection,
            // not a sort.
            let mut first = |k: u64| -> Vec<usize> {
                let k = k as usize;
                if k < candidates.len() {
                    if k > 0 {
                        candidates.select_nth_unstable_by(k - 1, |&a, &b| {
                            fraction[b].total_cmp(&fraction[a]).then(a.cmp(&b))
                        });
                    }
                    return candidates.drain(..k).collect();
                }
                let mut all = std::mem::take(&mut candidates);
                all.extend(without.by_ref().take(k - all.len()));
                all
            };
            // Each step is at most a quantum, so left / quantum of them fit.
            let mut up = first(left / q as u64);
            while !up.is_empty() {
                for &i in &up {
                    left -= (next[i] - out[i]) as u64;
                    out[i] = next[i];
                }
                up = first(left / q as u64);
            }
            for i in first(left) {
                out[i] += 1;
            }
            out
        }
    }

    /// Image `k`'s width (at least `least`, below `least` + `across`),
    /// height (below 1 + `down`), budget (one of `budgets`, in turn) and
    /// its quantum, drawn from `seed`.
    fn drawn(seed: u64, (least, across, down): (usize, f64, f64), budgets: &[u32], k: u64) -> (usize, usize, u32, u32) {
        let w = least + (hashed_uniform(seed) * across) as usize;
        let h = 1 + (hashed_uniform(seed + 1) * down) as usize;
        let budget = budgets[k as usize % budgets.len()];
        (w, h, budget, quantum(budget))
    }

    /// The fused allocation gives the counts of the plain one, to the ray:
    /// on images of noise of every kind (none, a few noisy pixels, noise
    /// everywhere, with NaN spreads), with counts from the first pass's to
    /// the cap, every quantum, and totals from a ray to past the caps.
    #[test]
    fn the_same_counts_as_the_plain_allocation() {
        let mut checked = 0;
        for k in 0..400u64 {
            let (w, h, budget, q) = drawn(64 * k, (1, 23.0, 17.0), &[1, 4, 16, 64, 9], k);
            let mut sums = vec![PixelSum::default(); w * h];
            for (i, s) in sums.iter_mut().enumerate() {
                let n = match k % 4 {
                    0 => 2,
                    1 => 2 + (hashed_uniform(7 * i as u64 + k) * 40.0) as u32 / q * q,
                    _ => 1 + (hashed_uniform(7 * i as u64 + k) * 6.0) as u32,
                };
                let noisy = match k % 3 {
                    0 => false,
                    1 => hashed_uniform(11 * i as u64 + k) < 0.05,
                    _ => true,
                };
                for j in 0..n {
                    let x = hashed_uniform(13 * (i as u64 * 64 + j as u64) + k);
                    let c = if noisy { x } else { 0.5 };
                    s.add(Intensity::new(c, 0.5, c * c));
                }
                if k % 29 == 0 && i == 0 {
                    s.add(Intensity::splat(f64::NAN));
                }
            }
            let pixels = (w * h) as u64;
            let extra = [1, pixels, pixels * budget as u64 / 3, pixels * budget as u64 * 20][(k / 5 % 4) as usize];
            let fused = allocate(&sums, w, budget, extra, q);
            assert_eq!(fused, plain::allocate(&sums, w, budget, extra, q), "image {k}: {w}×{h}");
            checked += 1;
        }
        assert_eq!(checked, 400);
    }

    /// One allocation through a render's passes, keeping its spreads and
    /// needs between them, gives each pass the plain allocation's counts
    /// (which computes them all again): on images whose pixels are still
    /// or noisy in patches, some with searches (costs), every quantum, with
    /// the samples each pass adds; and an image of another size after.
    #[test]
    fn passes_keep_the_plain_counts() {
        let mut passes = 0;
        for k in 0..24u64 {
            let (w, h, budget, q) = drawn(1000 * k, (2, 19.0, 13.0), &[4, 9, 16, 64], k);
            let mut allocation = Allocation::new(w);
            for image in 0..2 {
                let h = h + image;
                let noisy = |i: usize| hashed_uniform(17 * (i / 3) as u64 + k) < 0.3;
                let mut sums = vec![PixelSum::default(); w * h];
                let add = |sums: &mut [PixelSum], i: usize, to: u32| {
                    while sums[i].n < to {
                        let x = hashed_uniform(31 * (i as u64 * 4096 + sums[i].n as u64) + k);
                        sums[i].add(Intensity::splat(if noisy(i) { x } else { 0.25 }));
                        if i.is_multiple_of(5) {
                            sums[i].add_searched(3);
                        }
                    }
                };
                for i in 0..w * h {
                    add(&mut sums, i, 2);
                }
                let mut left = (w * h) as u64 * (budget as u64 - 2);
                for p in 0..6u64 {
                    let extra = left / (6 - p);
                    left -= extra;
                    let counts = allocation.allocate(&sums, budget, extra, q);
                    assert_eq!(
                        counts,
                        plain::allocate(&sums, w, budget, extra, q),
                        "image {k}.{image}, pass {p}"
                    );
                    for (i, &n) in counts.iter().enumerate() {
                        add(&mut sums, i, n);
                    }
                    passes += 1;
                }
            }
        }
        assert_eq!(passes, 24 * 2 * 6);
    }

    fn sums_with(spreads: &[(usize, f64)], len: usize, n: u32) -> Vec<PixelSum> {
        let mut sums = vec![PixelSum::default(); len];
        for s in sums.iter_mut() {
            for _ in 0..n {
                s.add(Intensity::splat(0.5));
            }
        }
        for &(i, d) in spreads {
            sums[i] = PixelSum::default();
            for j in 0..n {
                sums[i].add(Intensity::splat(if j % 2 == 0 { 0.5 - d } else { 0.5 + d }));
            }
        }
        sums
    }

    /// The rays go to the noisy pixel and its neighbours, they add up to
    /// the total, and no count shrinks or passes the cap.
    #[test]
    fn allocation_follows_the_spread() {
        let (w, h) = (8, 8);
        let sums = sums_with(&[(3 * w + 3, 0.4)], w * h, 4);
        let out = allocate(&sums, w, 16, 200, 1);
        assert_eq!(out.iter().map(|&n| n as u64).sum::<u64>(), 4 * 64 + 200);
        assert!(out.iter().all(|&n| (4..=16 * 16).contains(&n)));
        let noisy = out[3 * w + 3];
        let beside = out[3 * w + 4];
        let far = out[7 * w + 7];
        assert!(noisy > beside && beside > far, "{noisy} {beside} {far}");
        assert_eq!(far, 4);
        // Twice the spread, 2^NEED_POWER times the rays (Neyman's 2,
        // tempered).
        let sums = sums_with(&[(0, 0.4), (63, 0.2)], w * h, 4);
        let out = allocate(&sums, w, 16, 100, 1);
        assert!(
            (out[0] as f64 / out[63] as f64 - 2f64.powf(NEED_POWER)).abs() < 0.1,
            "{} {}",
            out[0],
            out[63]
        );
    }

    /// The need is the spread, or the neighbour's share of the largest
    /// spread around, to the power [`NEED_POWER`](super::NEED_POWER), with its floor.
    #[test]
    fn needs_are_spreads_to_the_power() {
        let (w, h) = (5, 4);
        let sums = sums_with(&[(2 * w + 2, 0.3)], w * h, 4);
        let sigma = sums[2 * w + 2].spread();
        let need = needs(&sums, w);
        let top = sigma.powf(NEED_POWER);
        assert!((need[2 * w + 2] - top).abs() < 1e-12);
        for i in [w + 1, w + 3, 3 * w + 2, 2 * w + 1] {
            assert!(
                (need[i] - (NEIGHBOUR * sigma).powf(NEED_POWER)).abs() < 1e-12,
                "pixel {i}"
            );
        }
        assert_eq!(need[0], top * 1e-3);
        assert_eq!(need[w * h - 1], top * 1e-3);
        assert!(needs(&sums_with(&[], w * h, 4), w).iter().all(|&n| n == 1.0));
        // A pixel whose rays searched polynomials needs less by its cost;
        // its neighbours, which searched none, need what they did.
        let mut dear = sums.clone();
        dear[2 * w + 2].add_searched(8);
        let lowered = needs(&dear, w);
        let c = cost(&dear[2 * w + 2]);
        assert_eq!(c, (1.0f64 + SEARCH_COST * 2.0).powf(COST_POWER));
        assert!((lowered[2 * w + 2] - top / c).abs() < 1e-12);
        assert_eq!(lowered[w + 1], need[w + 1]);
    }

    /// The quantum is the budget's power of two at or below it, at most
    /// [`MAX_QUANTUM`]; a render's counts after a later pass are the
    /// first pass's or multiples of it.
    #[test]
    fn counts_come_in_quanta() {
        let q: Vec<u32> = [1, 2, 4, 9, 16, 49, 64, 1024].into_iter().map(quantum).collect();
        assert_eq!(q, vec![1, 2, 4, 8, 16, 32, 64, 64]);
        let (w, h) = (16, 16);
        let sums = sums_with(&[(3 * w + 3, 0.4), (9 * w + 12, 0.2), (12 * w + 2, 0.1)], w * h, 2);
        let extra = (w * h) as u64 * 5;
        let out = allocate(&sums, w, 16, extra, 16);
        assert_eq!(out.iter().map(|&n| n as u64).sum::<u64>(), (w * h) as u64 * 7);
        let odd = out.iter().filter(|&&n| n != 2 && n % 16 != 0).count();
        assert!(odd < 16, "{odd} pixels off the levels: {out:?}");
        assert!(out.iter().any(|&n| n >= 32) && out.contains(&2));
    }

    /// λ makes the bounded counts add up to the total, by less than half a
    /// ray beyond it, whether few or most pixels end at a bound.
    #[test]
    fn lambda_meets_the_total() {
        let n = 500;
        let need: Vec<f64> = (0..n).map(|i| 0.001 + hashed_uniform(i as u64).powi(3)).collect();
        let counts: Vec<u32> = (0..n).map(|i| 2 + i as u32 % 5).collect();
        let low: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
        let high: Vec<f64> = low.iter().map(|&l| l.max(64.0)).collect();
        let sum = |l: f64| (0..n).map(|i| (l * need[i]).clamp(low[i], high[i])).sum::<f64>();
        let (lo_sum, hi_sum): (f64, f64) = (low.iter().sum(), high.iter().sum());
        for share in [0.001, 0.05, 0.3, 0.7, 0.95, 0.999] {
            let total = (lo_sum + share * (hi_sum - lo_sum)).round();
            let got = sum(solve_lambda(&need, &low, &high, total));
            assert!(got >= total && got - total < 0.5, "share {share}: {got} for {total}");
        }
    }

    /// The sum of four pixels at a time is the sum pixel by pixel, to the
    /// bit: at λ where the pixels are all at their low bound, some between
    /// the bounds, some at the cap, on every remainder of four pixels.
    #[test]
    fn bounded_sum_is_the_plain_sum() {
        let plain = |l: f64, need: &[f64], low: &[f64], high: &[f64]| {
            let (mut sum, mut slope) = (0.0f64, 0.0f64);
            for i in 0..need.len() {
                let t = l * need[i];
                if t <= low[i] {
                    sum += low[i];
                } else if t >= high[i] {
                    sum += high[i];
                } else {
                    sum += t;
                    slope += need[i];
                }
            }
            (sum, slope)
        };
        for n in 0..40usize {
            let need: Vec<f64> = (0..n)
                .map(|i| 0.001 + hashed_uniform((100 * n + i) as u64).powi(3))
                .collect();
            let low: Vec<f64> = (0..n).map(|i| (2 + i % 5) as f64).collect();
            let high: Vec<f64> = low.iter().map(|&l| l.max(64.0)).collect();
            for l in [0.0, 1.0, 7.3, 40.0, 333.3, 1e4] {
                let (got, want) = (bounded_sum(l, &need, &low, &high), plain(l, &need, &low, &high));
                assert_eq!(
                    (got.0.to_bits(), got.1.to_bits()),
                    (want.0.to_bits(), want.1.to_bits()),
                    "{n} pixels at λ {l}"
                );
            }
        }
    }

    /// With no spread anywhere the rays go evenly, the remainder to the
    /// first pixels; the cap holds when the need is all in one pixel.
    #[test]
    fn allocation_without_spread_is_even_and_capped() {
        let sums = sums_with(&[], 10, 2);
        assert_eq!(allocate(&sums, 5, 4, 25, 1), vec![5, 5, 5, 5, 5, 4, 4, 4, 4, 4]);
        // In quanta of 4: 4 each, and the 5 rays left a quantum to the
        // first pixel and one to the next.
        assert_eq!(allocate(&sums, 5, 4, 20, 4), vec![4; 10]);
        assert_eq!(allocate(&sums, 5, 4, 25, 4), vec![8, 5, 4, 4, 4, 4, 4, 4, 4, 4]);
        let sums = sums_with(&[(0, 0.4)], 100, 2);
        let out = allocate(&sums, 10, 4, 1000, 4);
        // The noisy pixel at the cap, 16 budgets, in quanta of 4; with a
        // budget of 49 in quanta of 32, the cap of 16 · 49 = 784 rounded
        // down to whole quanta, 768.
        assert_eq!(out[0], 64);
        assert_eq!(allocate(&sums, 10, 49, 20_000, 32)[0], 768);
        assert!(out.iter().all(|&n| n <= 64));
        assert_eq!(out.iter().map(|&n| n as u64).sum::<u64>(), 200 + 1000);
    }
}
