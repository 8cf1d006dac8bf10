//! `--sampler adaptive`: where in each pixel, and when in the shutter, its
//! rays go, and how many rays each pixel gets. The port's extension, not the
//! thesis's method: the thesis traces every pixel as the same `masksize` ×
//! `masksize` subpixels (§2.1.3 (2), supersampling) with times from its
//! pattern table (§2.6.4). Adaptive supersampling goes back to Whitted 1980,
//! which the thesis cites; this one follows its later form (Mitchell 1987;
//! the per-pixel noise estimate of Blender Cycles' adaptive sampling):
//!
//! - The budget is the deck's mask M: M² rays a pixel on average over the
//!   image, W·H·M² in all.
//! - A first pass gives every pixel [`first_pass`] rays; then [`PASSES`]
//!   passes deal out the rest, each a share of what is left, by need
//!   ([`allocate`]): a pixel's need is the spread of its samples so far
//!   (space and time together: a sample varies in both), widened to its
//!   neighbours so an edge the first rays missed is still found. A
//!   pixel's count after a pass is its first pass's or a multiple of the
//!   [`quantum`] (M², or the power of two below it, at most
//!   [`MAX_QUANTUM`]): its samples are then whole blocks of the Sobol
//!   sequence, each block evenly spread in place and time, where a count
//!   in between leaves a block part-filled and the pixel's mean less
//!   accurate than its count says.
//! - Sample j of a pixel is point j of a 3-D Sobol sequence (pixel x,
//!   pixel y, shutter time τ), Owen-scrambled (Burley 2020, *Practical
//!   hash-based Owen scrambling*): every prefix is well spread in all
//!   three, so a pixel can stop after any count. The place is scrambled by
//!   a seed of the pixel, the time by a seed of its row and a shift of the
//!   pixel ([`PixelSamples`]), so that a row's pixels take their samples
//!   at shared instants and the scene is posed once an instant, not once
//!   a ray.
//! - τ is uniform over [0, 1): the box shutter `blur 1` samples, so the
//!   picture converges to the same one as the other samplers'.
//!
//! Every choice depends on the pixel, the sample's index and the image's
//! counts after a whole pass, never on the order threads finish in: the
//! image is the same for any number of threads.

mod sobol;

use crate::drt::hashed_uniform;
use crate::types::{Fidelity, Intensity, Options, TimeSampler};
use sobol::{owen_scramble_reversed, sobol_reversed};

/// A sample of a pixel: where in it (`u` across to the right, `v` down,
/// both in [0, 1)) and when in the shutter (`tau` in [0, 1)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub u: f64,
    pub v: f64,
    pub tau: f64,
}

/// Later passes after the first: each deals out 1/(passes left) of the
/// rays not yet spent, on the spreads seen so far (6 measured better than
/// 3 and as well as 10 on the chart's decks).
pub const PASSES: usize = 6;

/// A neighbour's spread counts this much toward a pixel's need (the 8
/// pixels around it): enough to send rays along an edge the first pass
/// saw in only some of its pixels (0.25 and 1 both measured worse).
pub const NEIGHBOUR: f64 = 0.5;

/// Counts grow as the need to this power: a little less than Neyman's 1,
/// as scrambled Sobol points converge faster than independent ones where
/// a pixel is smooth (0.8 measured best of 0.65, 0.8, 1 and 1.25; 0.75,
/// which two square roots compute, within ±0.003 of its error ratios on
/// every deck of the goal). [`needs`] computes exactly w^¾.
pub const NEED_POWER: f64 = 0.75;

/// The largest [`quantum`]: a pixel's count after the first pass is its
/// first pass's or a multiple of the budget M² (or of the power of two
/// below it, at most this), so that its samples are whole blocks of the
/// Sobol sequence, each block a net stratified in place and time: on the
/// goal's decks at 16 rays a pixel this brought the RMSE ratio from
/// 0.51–0.54 to 0.47–0.49 (8 was between), at 64 from 0.38–0.42 to
/// 0.36–0.41 (16 and 32 were between, 12 worse than 8).
pub const MAX_QUANTUM: u32 = 64;

/// No pixel gets more than this many times the average budget.
pub const CAP: u32 = 16;

/// The options the adaptive sampler cannot run with: `listing` fidelity
/// reads its times outside the shutter (erratum 2), so there is no
/// picture for the adaptive times to converge to.
pub fn check(opts: &Options) -> Result<(), String> {
    if opts.sampler == TimeSampler::Adaptive && opts.fidelity == Fidelity::Listing {
        return Err(
            "--sampler adaptive cannot be used with --fidelity listing: the listing's times leave the \
                    shutter [0, 1) (erratum 2), the adaptive sampler's stay in it; use --fidelity thesis"
                .into(),
        );
    }
    Ok(())
}

/// The rays every pixel gets in the first pass, for a budget of `m`² a
/// pixel: an eighth of the budget, at least 2 (a spread needs two) and at
/// most 8; a budget of 1 is all first pass. (A quarter measured worse: the
/// rays a still pixel spends in the first pass are lost to the others.)
pub fn first_pass(m: usize) -> u32 {
    let budget = (m * m) as u32;
    if budget <= 1 {
        budget.max(1)
    } else {
        (budget / 8).clamp(2, 8)
    }
}

/// What a pixel's samples add up to.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    /// Samples traced.
    pub n: u32,
    sum: Intensity,
    sum_sq: Intensity,
}

impl PixelSum {
    /// One more sample.
    pub fn add(&mut self, c: Intensity) {
        self.n += 1;
        self.sum += c;
        self.sum_sq += c * c;
    }

    /// The pixel's colour: the mean of its samples (a box filter, as
    /// `antialias`); black before any.
    pub fn mean(&self) -> Intensity {
        if self.n == 0 {
            Intensity::ZERO
        } else {
            self.sum / self.n as f64
        }
    }

    /// The spread of the samples: the standard deviation, the three
    /// channels' variances averaged; 0 for fewer than two.
    pub fn spread(&self) -> f64 {
        if self.n < 2 {
            return 0.0;
        }
        let n = self.n as f64;
        let var = (self.sum_sq - self.sum * self.sum / n) / (n - 1.0);
        (var.max(Intensity::ZERO).element_sum() / 3.0).sqrt()
    }
}

/// The counts every pixel of a `width`×`height` image should have after
/// the next pass, `spent` + its share of `extra` more rays in all.
///
/// A pixel's need w is its spread σ, or [`NEIGHBOUR`] times the largest
/// spread around it if that is more, to the power [`NEED_POWER`]. To make
/// the summed error Σ σ²/n smallest for a fixed total, counts grow with σ
/// (Neyman allocation): the new counts are max(n, λ·w), at most [`CAP`] times the
/// average `budget`, with λ found so they add up to the total; then
/// rounded to whole counts of n or multiples of `quantum` (the render's
/// is [`quantum`] of the budget), by the largest fractions of the way to
/// the next (ties to the first pixel; [`round_counts`]). When no pixel
/// shows any spread, the rays go evenly, to within a quantum.
pub fn allocate(sums: &[PixelSum], width: usize, budget: u32, extra: u64, quantum: u32) -> Vec<u32> {
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

/// The step of a pixel's counts after the first pass, for a budget of
/// `budget` rays a pixel: the largest power of two not above it, nor
/// above [`MAX_QUANTUM`].
pub fn quantum(budget: u32) -> u32 {
    let b = budget.clamp(1, MAX_QUANTUM);
    1 << (31 - b.leading_zeros())
}

/// Whole counts from the `real` ones (each at least the pixel's count
/// `low` so far) that add up to `total`: each pixel keeps `low` or takes
/// a multiple of `quantum` above it, at most `cap` (a multiple of
/// `quantum`). Each starts at the level at or below its real count; then,
/// by the largest fraction of the way to its next level (ties to the
/// first pixel), pixels step up to that level while the steps fit in the
/// rays left; the last rays, fewer than `quantum`, go one each in the same
/// order. With a quantum of 1 this is the whole part of each and a ray
/// more to the largest fractions. The whole parts are conversions, as no
/// count is negative (`floor` is a library call on this target).
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
                candidates.select_nth_unstable_by(k - 1, |&a, &b| fraction[b].total_cmp(&fraction[a]).then(a.cmp(&b)));
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

/// Each pixel's need w of [`allocate`]: its spread σ, or [`NEIGHBOUR`]
/// times the largest spread of the 3×3 pixels around it if that is more,
/// to the power [`NEED_POWER`]; at least a thousandth of the largest
/// need, so that pixels without spread can take rays when the others are
/// at the cap (and share them evenly when no pixel shows any). One loop
/// on one thread: a few operations a pixel, where the parallel version's
/// bookkeeping cost more than the work.
fn needs(sums: &[PixelSum], width: usize) -> Vec<f64> {
    let spread: Vec<f64> = sums.iter().map(PixelSum::spread).collect();
    // The largest spread of the 3 pixels of the row around each, row by
    // row (no division by the width a pixel).
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
    for y in 0..height {
        for x in 0..width {
            let i = y * width + x;
            let up = if y > 0 { across[i - width] } else { 0.0 };
            let down = if y + 1 < height { across[i + width] } else { 0.0 };
            let w = spread[i].max(NEIGHBOUR * across[i].max(up).max(down));
            // w^¾ ([`NEED_POWER`]) in two square roots, an instruction
            // each, where `powf` took a quarter of the allocation's time.
            need[i] = (w * w.sqrt()).sqrt();
        }
    }
    let top = need.iter().copied().fold(0.0f64, f64::max);
    let floor = if top > 0.0 { top * 1e-3 } else { 1.0 };
    for w in &mut need {
        *w = w.max(floor);
    }
    need
}

/// The λ of [`allocate`]: Σ clamp(λ·need, low, high) reaches `total`, by
/// less than half a ray beyond it (the rounding then hands out the rest
/// exactly). The sum is piecewise linear and grows with λ; Newton's steps
/// on it, kept inside a bracket that halves when a step would leave it,
/// take a handful of sums where bisection takes twenty or more. `total`
/// must lie between Σ low and Σ high.
fn solve_lambda(need: &[f64], low: &[f64], high: &[f64], total: f64) -> f64 {
    // The sum and its slope at λ (the needs of the pixels not at a bound).
    let sum_at = |l: f64| {
        let (mut sum, mut slope) = (0.0, 0.0);
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
    // The start: λ where the counts would add up without their bounds.
    let (mut lo, mut hi) = (0.0f64, total / need.iter().sum::<f64>());
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

/// The rays of the passes after the first, for an image of `pixels` pixels
/// and a budget of `budget` a pixel, `first` of which the first pass spent:
/// the `extra` of each pass, 1/(passes left) of what remains.
pub fn later_passes(pixels: usize, budget: u32, first: u32) -> Vec<u64> {
    let passes = PASSES;
    let mut left = pixels as u64 * budget.saturating_sub(first) as u64;
    let mut out = vec![0u64; passes];
    for (p, slot) in out.iter_mut().enumerate() {
        *slot = left / (passes - p) as u64;
        left -= *slot;
    }
    out
}

/// The samples of one pixel: the scrambles of its three dimensions, the
/// place in the pixel (dimensions 0 and 1) by a seed of the pixel, the
/// time (dimension 2) by a seed of its row, so that the rows' pixels can
/// share their instants (interleaved sampling, Keller & Heidrich 2001):
/// the scene at an instant (the poses, an in-between contour) is made
/// once for all the row's rays at it. Pixel x takes the row's time k for
/// its sample j = k ⊕ c with c < [`SHIFT_BLOCK`] a hash of the pixel: a
/// digital shift of its times (the Sobol points are linear over bits,
/// point k ⊕ c = point k ⊕ point c), so the pixels of a row do not all
/// take their first samples at the same instants (a first pass that
/// missed a brief change in one pixel would miss it along the whole
/// row), and each pixel's samples are still a scrambled 3-D Sobol
/// sequence, every prefix stratified in space, time and both.
#[derive(Clone, Copy, Debug)]
pub struct PixelSamples {
    seeds: [u32; 3],
    shift: u32,
}

/// The shifts of [`PixelSamples`] are below this (a power of two): the
/// row's instants k and a pixel's samples j = k ⊕ c then lie in the same
/// block of this many, and the instants a pass traces are at most the
/// blocks its samples reach (16: eight different first pairs of times in
/// a row, and still few instants a pass).
pub const SHIFT_BLOCK: u32 = 16;

/// The pixels of a row with samples due in a pass, block by block of
/// [`SHIFT_BLOCK`] instants: for each block that has any (in increasing
/// order), its number and the pixels (in increasing order) whose samples
/// `start[x]..counts[x]` reach it. A pixel's sample j = k ⊕ c at instant
/// k lies in k's block, so an instant need only visit its block's pixels,
/// not the whole row (visiting all was 6 % of an adaptive render).
pub fn blocks_due(start: &[u32], counts: &[u32]) -> Vec<(u32, Vec<usize>)> {
    let block = SHIFT_BLOCK;
    let span = |x: usize| (start[x] / block, counts[x].div_ceil(block));
    let due = |x: usize| counts[x] > start[x];
    let Some(first) = (0..start.len()).filter(|&x| due(x)).map(|x| span(x).0).min() else {
        return Vec::new();
    };
    let last = (0..start.len())
        .filter(|&x| due(x))
        .map(|x| span(x).1)
        .max()
        .unwrap_or(first);
    let mut lists = vec![Vec::new(); (last - first) as usize];
    for x in (0..start.len()).filter(|&x| due(x)) {
        let (a, b) = span(x);
        for list in &mut lists[(a - first) as usize..(b - first) as usize] {
            list.push(x);
        }
    }
    (first..last).zip(lists).filter(|(_, l)| !l.is_empty()).collect()
}

/// The scramble of dimension `d` for key `key`.
fn seed(key: u64, d: u64) -> u32 {
    (hashed_uniform((key << 2 | d) ^ 0x5EED_0000_0000_0000) * 4_294_967_296.0) as u32
}

impl PixelSamples {
    /// The samples of pixel `pixel` (its index in the image, row by row)
    /// of an image `width` pixels wide.
    pub fn new(pixel: usize, width: usize) -> Self {
        let row = (pixel / width.max(1)) as u64;
        PixelSamples {
            seeds: [seed(pixel as u64, 0), seed(pixel as u64, 1), seed(row, 2)],
            shift: seed(pixel as u64, 3) % SHIFT_BLOCK,
        }
    }

    /// The sample the pixel takes at its row's instant `k`.
    pub fn at_instant(&self, k: u32) -> u32 {
        k ^ self.shift
    }

    /// Sample `j` of the pixel.
    pub fn sample(&self, j: u32) -> Sample {
        let (u, v) = self.place(j);
        Sample { u, v, tau: self.tau(j) }
    }

    /// Where in the pixel sample `j` lies: `u` across, `v` down.
    pub fn place(&self, j: u32) -> (f64, f64) {
        (self.at(j, 0), self.at(j, 1))
    }

    /// The time of sample `j`: the row's instant `j ⊕ c`, the same for
    /// every pixel of the row at that instant.
    pub fn tau(&self, j: u32) -> f64 {
        self.at(j ^ self.shift, 2)
    }

    fn at(&self, j: u32, d: usize) -> f64 {
        owen_scramble_reversed(sobol_reversed(j, d), self.seeds[d]) as f64 / 4_294_967_296.0
    }
}

/// Sample `j` of pixel `pixel` (its index in the image, row by row) of an
/// image `width` pixels wide.
pub fn sample(pixel: usize, width: usize, j: u32) -> Sample {
    PixelSamples::new(pixel, width).sample(j)
}

#[cfg(test)]
mod tests {
    use super::sobol::sobol;
    use super::*;

    /// The scramble keeps the nets (it permutes elementary intervals
    /// within their parents) and changes the points.
    #[test]
    fn scrambled_samples_keep_their_strata() {
        // Every aligned block of 2^k samples, not only the first: the
        // counts come in such blocks ([`quantum`]).
        for pixel in [0usize, 7, 12345] {
            for (k, block) in [2u32, 4, 6].into_iter().flat_map(|k| [(k, 0u32), (k, 1), (k, 3)]) {
                let n = 1u32 << k;
                let mut times = vec![false; n as usize];
                let mut cells = vec![false; n as usize];
                let half = k / 2;
                for j in block * n..(block + 1) * n {
                    let s = sample(pixel, 100, j);
                    assert!((0.0..1.0).contains(&s.u) && (0.0..1.0).contains(&s.v) && (0.0..1.0).contains(&s.tau));
                    let t = (s.tau * n as f64) as usize;
                    assert!(!times[t], "pixel {pixel}: two of {n} times in stratum {t}");
                    times[t] = true;
                    let cell =
                        ((s.u * (1 << half) as f64) as usize) << (k - half) | (s.v * (1 << (k - half)) as f64) as usize;
                    assert!(!cells[cell], "pixel {pixel}: two of {n} positions in cell {cell}");
                    cells[cell] = true;
                }
            }
        }
        // Places differ from pixel to pixel; times from row to row, and
        // not between the pixels of a row.
        assert_ne!(sample(0, 100, 1).u, sample(1, 100, 1).u);
        assert_ne!(sample(0, 100, 1).v, sample(1, 100, 1).v);
        let (a, b) = (PixelSamples::new(0, 100), PixelSamples::new(99, 100));
        for k in 0..64 {
            assert_eq!(a.tau(a.at_instant(k)), b.tau(b.at_instant(k)), "instant {k}");
            assert_eq!(a.at_instant(a.at_instant(k)), k);
            assert_eq!(a.at_instant(k) / SHIFT_BLOCK, k / SHIFT_BLOCK);
        }
        // The first pairs of times of a row's pixels are not all the same.
        let first = |x: usize| sample(x, 100, 0).tau.min(sample(x, 100, 1).tau);
        assert!((1..100).any(|x| first(x) != first(0)));
        assert_ne!(sample(0, 100, 1).tau, sample(100, 100, 1).tau);
        assert_ne!(sample(0, 100, 0).tau, sobol(0, 2) as f64 / 4_294_967_296.0);
    }

    /// Visiting each block's pixels visits every due sample of a row once,
    /// in the order of the scan of every instant and pixel it replaces.
    #[test]
    fn blocks_due_visit_every_sample_in_scan_order() {
        let w = 37;
        let samples: Vec<PixelSamples> = (0..w).map(|x| PixelSamples::new(x, w)).collect();
        let start: Vec<u32> = (0..w).map(|x| [0, 2, 5, 16, 17, 40][x % 6]).collect();
        let counts: Vec<u32> = (0..w)
            .map(|x| start[x] + [0, 1, 3, 14, 15, 16, 31, 70][x % 8])
            .collect();
        let due = |k: u32, x: usize| {
            let j = samples[x].at_instant(k);
            (j >= start[x] && j < counts[x]).then_some((x, j))
        };
        let end = counts.iter().max().copied().unwrap_or(0).div_ceil(SHIFT_BLOCK) * SHIFT_BLOCK;
        let scan: Vec<(usize, u32)> = (0..end).flat_map(|k| (0..w).filter_map(move |x| due(k, x))).collect();
        let mut by_block = Vec::new();
        for (b, pixels) in blocks_due(&start, &counts) {
            assert!(!pixels.is_empty() && pixels.windows(2).all(|p| p[0] < p[1]));
            for k in b * SHIFT_BLOCK..(b + 1) * SHIFT_BLOCK {
                by_block.extend(pixels.iter().filter_map(|&x| due(k, x)));
            }
        }
        assert_eq!(by_block, scan);
        let total: u32 = (0..w).map(|x| counts[x] - start[x]).sum();
        assert_eq!(scan.len() as u32, total);
        assert!(blocks_due(&[3, 3], &[3, 2]).is_empty());
    }

    /// Every prefix length, pixel and channel: mean and spread as a
    /// textbook computes them.
    #[test]
    fn pixel_sum_mean_and_spread() {
        let mut s = PixelSum::default();
        assert_eq!(s.mean(), Intensity::ZERO);
        s.add(Intensity::splat(1.0));
        assert_eq!(s.spread(), 0.0);
        s.add(Intensity::new(0.0, 1.0, 1.0));
        s.add(Intensity::new(0.5, 1.0, 1.0));
        assert!((s.mean() - Intensity::new(0.5, 1.0, 1.0)).length() < 1e-12);
        // Red: 1, 0, 0.5 has variance 0.25; green and blue none.
        assert!((s.spread() - (0.25f64 / 3.0).sqrt()).abs() < 1e-12);
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
    /// spread around, to the power [`NEED_POWER`], with its floor.
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
    }

    /// The rounding gives the rays left to the largest fractions (not the
    /// largest ratios, nor the first pixels), ties to the first, and when
    /// the fractions are too few, to the whole counts below the cap in
    /// their order, never past the cap.
    #[test]
    fn rounding_follows_the_fractions() {
        let real = [4.3, 8.5, 2.0, 6.3, 16.0, 1.9, 3.0];
        // Whole parts 40, fractions 0.3, 0.5, 0, 0.3, 0, 0.9, 0.
        let want = |more: &[usize]| {
            let mut w = vec![4, 8, 2, 6, 16, 1, 3];
            for &i in more {
                w[i] += 1;
            }
            w
        };
        assert_eq!(round_counts(&real, &[0; 7], 40, 16, 1), want(&[]));
        assert_eq!(round_counts(&real, &[0; 7], 41, 16, 1), want(&[5]));
        assert_eq!(round_counts(&real, &[0; 7], 42, 16, 1), want(&[5, 1]));
        assert_eq!(round_counts(&real, &[0; 7], 43, 16, 1), want(&[5, 1, 0]));
        assert_eq!(round_counts(&real, &[0; 7], 44, 16, 1), want(&[5, 1, 0, 3]));
        // Past the fractions: the whole counts below the cap, in order.
        assert_eq!(round_counts(&real, &[0; 7], 45, 16, 1), want(&[5, 1, 0, 3, 2]));
        assert_eq!(round_counts(&real, &[0; 7], 46, 16, 1), want(&[5, 1, 0, 3, 2, 6]));
        assert_eq!(round_counts(&real, &[0; 7], 50, 16, 1), want(&[5, 1, 0, 3, 2, 6]));
    }

    /// In quanta: each pixel starts at its level (its count so far or the
    /// multiple at or below), steps go by the largest fraction of the way
    /// to the next level while they fit, and the last rays, fewer than a
    /// quantum, go one each; the total is exact.
    #[test]
    fn rounding_in_quanta() {
        let real = [2.0, 5.0, 9.5, 20.0, 31.9, 64.0];
        let low = [2; 6];
        // Levels 2, 2, 8, 16, 24, 64 (116 rays); fractions of the way to
        // 8, 8, 16, 24, 32 and none: 0, 0.5, 0.1875, 0.5, 0.9875.
        assert_eq!(round_counts(&real, &low, 116, 64, 8), vec![2, 2, 8, 16, 24, 64]);
        assert_eq!(round_counts(&real, &low, 124, 64, 8), vec![2, 2, 8, 16, 32, 64]);
        // Two rays left after a quantum: one each, ties to the first.
        assert_eq!(round_counts(&real, &low, 126, 64, 8), vec![2, 3, 8, 17, 32, 64]);
        // Three steps (one short, 2 → 8) leave 2 rays for the last two.
        assert_eq!(round_counts(&real, &low, 140, 64, 8), vec![3, 8, 9, 24, 32, 64]);
        // Short steps leave a quantum more: a second round of steps.
        let real = [5.0; 8];
        assert_eq!(round_counts(&real, &[2; 8], 48, 64, 8), vec![8, 8, 8, 8, 8, 3, 3, 2]);
        // None beyond the cap.
        assert_eq!(round_counts(&[16.0, 15.0], &[2, 2], 40, 16, 8), vec![16, 16]);
        // The fraction is of the step: 4.5 of the 6 from 2 to 8 (0.75)
        // before 5 of the 8 from 8 to 16 (0.625), though 5 rays are more.
        assert_eq!(round_counts(&[6.5, 13.0], &[2, 8], 18, 64, 8), vec![8, 9]);
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
        let low: Vec<f64> = (0..n).map(|i| (2 + i % 5) as f64).collect();
        let high: Vec<f64> = low.iter().map(|&l| l.max(64.0)).collect();
        let sum = |l: f64| (0..n).map(|i| (l * need[i]).clamp(low[i], high[i])).sum::<f64>();
        let (lo_sum, hi_sum): (f64, f64) = (low.iter().sum(), high.iter().sum());
        for share in [0.001, 0.05, 0.3, 0.7, 0.95, 0.999] {
            let total = (lo_sum + share * (hi_sum - lo_sum)).round();
            let got = sum(solve_lambda(&need, &low, &high, total));
            assert!(got >= total && got - total < 0.5, "share {share}: {got} for {total}");
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

    /// The passes deal out exactly the budget; the first pass is an eighth
    /// of it within 2..=8.
    #[test]
    fn passes_spend_the_budget() {
        assert_eq!(first_pass(1), 1);
        assert_eq!(first_pass(2), 2);
        assert_eq!(first_pass(4), 2);
        assert_eq!(first_pass(6), 4);
        assert_eq!(first_pass(8), 8);
        for m in [1usize, 2, 3, 4, 8, 32] {
            let first = first_pass(m);
            let later = later_passes(97, (m * m) as u32, first);
            assert_eq!(97 * first as u64 + later.iter().sum::<u64>(), 97 * (m * m) as u64);
        }
    }

    #[test]
    fn listing_fidelity_is_refused() {
        let opts = Options {
            fidelity: Fidelity::Listing,
            sampler: TimeSampler::Adaptive,
            ..Options::default()
        };
        let e = check(&opts).unwrap_err();
        assert!(e.contains("--sampler adaptive") && e.contains("--fidelity listing"));
        assert!(check(&Options::default()).is_ok());
    }
}
