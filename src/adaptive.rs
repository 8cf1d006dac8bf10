//! `--sampler adaptive`: how many rays each pixel gets (where in the pixel
//! and when in the shutter they go is the sampler's,
//! [`crate::sampler::PixelSampler`]). The port's extension, not the
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
//!   ([`Allocation`]): a pixel's need is the spread of its samples so far
//!   (space and time together: a sample varies in both), widened to its
//!   neighbours so an edge the first rays missed is still found, and
//!   lowered a little where the pixel's rays are dear ([`cost`]). A
//!   pixel's count after a pass is its first pass's or a multiple of the
//!   [`quantum`] (M², or the power of two below it, at most
//!   [`MAX_QUANTUM`]): its samples are then whole blocks of the Sobol
//!   sequence, each block evenly spread in place and time, where a count
//!   in between leaves a block part-filled and the pixel's mean less
//!   accurate than its count says.
//! - Sample j of a pixel is point j of a scrambled Sobol sequence
//!   ([`crate::sampler::PixelSamples`]): every prefix is well spread in place, time and
//!   both, so a pixel can stop after any count, and a row's pixels take
//!   their samples at shared instants, so the scene is posed once an
//!   instant, not once a ray ([`DueByInstant`]).
//!
//! Every choice depends on the pixel, the sample's index and the image's
//! counts after a whole pass, never on the order threads finish in: the
//! image is the same for any number of threads.

mod allocate;
mod rounding;

use crate::options::{Fidelity, Options, TimeSampler};
use crate::sampler::{PixelSamples, SHIFT_BLOCK};
use crate::types::Intensity;
pub use allocate::{allocate, Allocation};

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
/// every deck of the goal). [`Allocation`]'s needs compute exactly w^¾.
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

/// What a polynomial search costs, in rays that search nothing: in a
/// regression of each pixel's time on its rays, its object tests and its
/// searches (adaptive renders of the goal's four decks at 96², 16 and 64
/// rays a pixel; R² 0.99 without the 11 % of pixels a timer interrupt
/// spoiled), a ray took 90–180 ns and a search 540–1140.
pub const SEARCH_COST: f64 = 6.0;

/// A pixel's need is divided by the cost of its rays to this power
/// ([`cost`]): the counts that make the error least for a given time
/// rather than a given number of rays go as spread/√cost (Neyman's
/// allocation with costs); the budget here is rays, so only a little of
/// that. On the goal's decks at 96² (fig5_3 has no sweep and is not
/// touched): 3/16 took 4–16 % of the instructions off the adaptive renders
/// of fig5_9 and fig5_12 (4 % on fig5_9, 15–16 % on fig5_12) and moved their
/// RMSE by −1 % to +5 %; 1/8 took 3–11 %; 1/4 cost fig5_9 and fig5_12 up to
/// 7 % of RMSE, past the goal's half of the table's.
pub const COST_POWER: f64 = 0.1875;

/// The cost of a ray of the pixel against one that searches nothing,
/// 1 + [`SEARCH_COST`] · (searches a sample), to the power [`COST_POWER`]
/// (c^⅛ · c^¹⁄₁₆, four square roots; `powf` is a library call); exactly 1
/// for a pixel whose rays searched no polynomial, so a scene without
/// sweeps is allocated by its spreads alone.
pub fn cost(s: &PixelSum) -> f64 {
    if s.searched == 0 || s.n == 0 {
        return 1.0;
    }
    let c = 1.0 + SEARCH_COST * s.searched as f64 / s.n as f64;
    let eighth = c.sqrt().sqrt().sqrt();
    eighth * eighth.sqrt()
}

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
    /// The polynomials its samples' rays searched for roots
    /// ([`crate::trace::TraceStats::searched`]): their cost ([`cost`]).
    searched: u64,
}

impl PixelSum {
    /// One more sample.
    pub fn add(&mut self, c: Intensity) {
        self.n += 1;
        self.sum += c;
        self.sum_sq += c * c;
    }

    /// The searches of the sample just added.
    pub fn add_searched(&mut self, k: u64) {
        self.searched += k;
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

/// The step of a pixel's counts after the first pass, for a budget of
/// `budget` rays a pixel: the largest power of two not above it, nor
/// above [`MAX_QUANTUM`].
pub fn quantum(budget: u32) -> u32 {
    let b = budget.clamp(1, MAX_QUANTUM);
    1 << (31 - b.leading_zeros())
}

/// The rays of the passes after the first, for an image of `pixels` pixels
/// and a budget of `budget` a pixel, `first` of which the first pass spent:
/// the `extra` of each pass, 1/(passes left) of what remains.
pub(crate) fn later_passes(pixels: usize, budget: u32, first: u32) -> Vec<u64> {
    let passes = PASSES;
    let mut left = pixels as u64 * budget.saturating_sub(first) as u64;
    let mut out = vec![0u64; passes];
    for (p, slot) in out.iter_mut().enumerate() {
        *slot = left / (passes - p) as u64;
        left -= *slot;
    }
    out
}

/// The samples of a row due in a pass, in the order they are traced: by
/// the row's instant k, then by pixel, where pixel x's sample j = k ⊕ c
/// ([`PixelSamples::at_instant`]) is due if it lies in
/// `start[x]..counts[x]`; so each instant's samples come together, and
/// the scene is posed once an instant. A counting sort on the instants:
/// about 37 instructions a sample on fig5_3 (M = 3), where visiting every
/// pixel of a block at each of its 16 instants to find the due ones
/// visited 3 or 4 pixels a sample and took about 75. Its buffers are kept
/// from one row to the next of a thread's rows: allocated and zeroed for
/// each row they took about 10 instructions a sample.
#[derive(Clone, Debug, Default)]
pub struct DueByInstant {
    /// How many samples each instant has more than the one before, then
    /// where its first sample goes, then its next; at the end, where its
    /// samples end.
    slot: Vec<u32>,
    /// The due samples as (x, j); only its first entries are the row's.
    order: Vec<(u32, u32)>,
}

impl DueByInstant {
    /// The due samples of a row, instant by instant: each instant that has
    /// any, in order, as its samples (x, j) by pixel.
    pub fn sort(
        &mut self,
        samples: &[PixelSamples],
        start: &[u32],
        counts: &[u32],
    ) -> impl Iterator<Item = &[(u32, u32)]> {
        let pixels = || samples.iter().zip(start.iter().zip(counts));
        // k = j ⊕ c is at_instant(j), the shift being its own inverse; it
        // lies in j's block of SHIFT_BLOCK, so below the last count's
        // block's end.
        // (A fold of numbers, which the compiler does four at a time, where
        // `max` compared references one by one.)
        let end = counts.iter().fold(0, |m, &n| m.max(n)).div_ceil(SHIFT_BLOCK) * SHIFT_BLOCK;
        let end = end as usize;
        // How many samples each instant has, as differences: a pixel's
        // due samples j in a..b, cut into aligned blocks of 2^p (the
        // largest that fit), are each the instants of an aligned block of
        // 2^p (k = j ⊕ c with c below SHIFT_BLOCK keeps j's block of any
        // size, and j's place in blocks of 16 or more), one more from its
        // first instant, one less after its last; a block, not a sample, at
        // a time (about 1 instruction a sample less on fig5_3, M = 3).
        let slot = &mut self.slot;
        slot.clear();
        slot.resize(end + 1, 0);
        for (s, (&a, &b)) in pixels() {
            let mut j = a;
            while j < b {
                let size = 1 << j.trailing_zeros().min(31 - (b - j).leading_zeros());
                let k = s.at_instant(j) & !(size - 1);
                let first = &mut slot[k as usize];
                *first = first.wrapping_add(1);
                // Below 0 until the block's first adds its 1 back (the
                // differences wrap, their sums do not).
                let after = &mut slot[(k + size) as usize];
                *after = after.wrapping_sub(1);
                j += size;
            }
        }
        // Then where each instant's first goes.
        let (mut count, mut at) = (0u32, 0u32);
        for slot in &mut slot[..end] {
            count = count.wrapping_add(*slot);
            *slot = at;
            at += count;
        }
        // Every entry below the total is written once: the buffer is not
        // cleared, only grown.
        let due = at as usize;
        if self.order.len() < due {
            self.order.resize(due, (0, 0));
        }
        let order = &mut self.order[..due];
        for (x, (s, (&a, &b))) in pixels().enumerate() {
            for j in a..b {
                let next = &mut slot[s.at_instant(j) as usize];
                order[*next as usize] = (x as u32, j);
                *next += 1;
            }
        }
        // Instant k's samples end where k + 1's begin.
        let order = &self.order[..due];
        let mut from = 0;
        slot[..end].iter().filter_map(move |&to| {
            let instant = &order[from..to as usize];
            from = to as usize;
            (!instant.is_empty()).then_some(instant)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The due samples of a row as (k, x), in the order of
    /// [`DueByInstant::sort`]'s instants; each instant's samples share its
    /// k, and no instant is empty.
    fn due_by_instant(
        kept: &mut DueByInstant,
        samples: &[PixelSamples],
        start: &[u32],
        counts: &[u32],
    ) -> Vec<(u32, u32)> {
        let mut due = Vec::new();
        for instant in kept.sort(samples, start, counts) {
            let k = samples[instant[0].0 as usize].at_instant(instant[0].1);
            for &(x, j) in instant {
                assert_eq!(samples[x as usize].at_instant(j), k, "pixel {x}'s sample {j}");
                due.push((k, x));
            }
        }
        due
    }

    /// The due samples by instant are every due sample of a row once, in
    /// the order of the scan of every instant and pixel they replace; with
    /// the buffers of a longer row, or of a row with more instants, as
    /// with new ones.
    #[test]
    fn due_by_instant_is_the_scan_order() {
        let w = 37;
        let samples: Vec<PixelSamples> = (0..w).map(|x| PixelSamples::new(x, w)).collect();
        let start: Vec<u32> = (0..w).map(|x| [0, 2, 5, 16, 17, 40][x % 6]).collect();
        let counts: Vec<u32> = (0..w)
            .map(|x| start[x] + [0, 1, 3, 14, 15, 16, 31, 70][x % 8])
            .collect();
        let due = |k: u32, x: usize| {
            let j = samples[x].at_instant(k);
            (j >= start[x] && j < counts[x]).then_some((k, x as u32))
        };
        let end = counts.iter().max().copied().unwrap_or(0).div_ceil(SHIFT_BLOCK) * SHIFT_BLOCK;
        let scan: Vec<(u32, u32)> = (0..end).flat_map(|k| (0..w).filter_map(move |x| due(k, x))).collect();
        let mut kept = DueByInstant::default();
        assert_eq!(due_by_instant(&mut kept, &samples, &start, &counts), scan);
        let total: u32 = (0..w).map(|x| counts[x] - start[x]).sum();
        assert_eq!(scan.len() as u32, total);
        assert!(due_by_instant(&mut kept, &samples[..2], &[3, 3], &[3, 2]).is_empty());
        assert!(due_by_instant(&mut kept, &[], &[], &[]).is_empty());
        // Kept buffers: a shorter row with fewer instants, then the first
        // again, sort as with new ones.
        let half = w / 2;
        let fewer: Vec<u32> = start[..half].iter().map(|&a| a + 3).collect();
        let short = (&samples[..half], &start[..half], &fewer[..]);
        let want = due_by_instant(&mut DueByInstant::default(), short.0, short.1, short.2);
        assert_eq!(want.len(), 3 * half);
        assert_eq!(due_by_instant(&mut kept, short.0, short.1, short.2), want);
        assert_eq!(due_by_instant(&mut kept, &samples, &start, &counts), scan);
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

    /// The first pass takes an eighth of the budget, within 2..=8 (a
    /// budget of one ray is all first pass), and the passes together
    /// spend the whole budget.
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

    /// The cost of a pixel's rays: 1 without searches (or samples), else
    /// (1 + 6 · searches a sample)^(3/16), from four square roots.
    #[test]
    fn cost_of_the_searches() {
        let mut s = PixelSum::default();
        assert_eq!(cost(&s), 1.0);
        s.add_searched(3);
        assert_eq!(cost(&s), 1.0, "no sample yet");
        for _ in 0..4 {
            s.add(Intensity::splat(0.5));
        }
        let want = (1.0 + SEARCH_COST * 0.75f64).powf(COST_POWER);
        assert!((cost(&s) - want).abs() < 1e-15, "{} against {want}", cost(&s));
        let mut none = PixelSum::default();
        none.add(Intensity::splat(0.5));
        assert_eq!(cost(&none), 1.0);
        // Dearer rays, a larger cost; 256 searches a ray cost 1537^(3/16).
        let mut dear = PixelSum::default();
        dear.add(Intensity::splat(0.5));
        dear.add_searched(256);
        assert!(cost(&dear) > cost(&s));
        assert!((cost(&dear) - 1537f64.powf(0.1875)).abs() < 1e-12);
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
