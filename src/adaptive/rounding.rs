//! The adaptive sampler's rounding of the real counts of
//! [`Allocation::allocate`](super::Allocation::allocate) to whole ones.

/// The buffers of [`Rounding::round`], kept from one pass to the next.
#[derive(Clone, Debug, Default)]
pub(super) struct Rounding {
    /// The keys of the pixels that may step up with a fraction.
    candidates: Vec<u128>,
    /// The pixels that may step up without one.
    waiting: Vec<bool>,
}

impl Rounding {
    /// Whole counts from the real ones (`real`, pixel by pixel, each at
    /// least its count `low` so far) that add up to `total`: each pixel
    /// keeps `low` or takes a multiple of `quantum` above it, at most `cap`
    /// (a multiple of `quantum`). Each starts at the level at or below its
    /// real count; then, by the largest fraction of the way to its next
    /// level (ties to the first pixel), pixels step up to that level while
    /// the steps fit in the rays left; the last rays, fewer than
    /// `quantum`, go one each in the same order. With a quantum of 1 this
    /// is the whole part of each and a ray more to the largest fractions.
    /// The whole parts are conversions, as no count is negative (`floor`
    /// is a library call on this target).
    pub(super) fn round(
        &mut self,
        real: impl IntoIterator<Item = f64>,
        low: &[u32],
        total: u64,
        cap: u32,
        quantum: u32,
    ) -> Vec<u32> {
        let q = quantum.max(1);
        let next = |f: u32| (f / q + 1) * q;
        let mut given: u64 = low.iter().map(|&n| n as u64).sum();
        // The pixels that may step up to their next level (not beyond the
        // cap): those with a fraction of the way there, as keys in the
        // order of the smallest fraction, then the last pixel (a fraction
        // in (0, 1) orders as its bits do), and those without (most: the
        // pixels that keep their count), which come after them in their
        // order. A pixel steps once at most, so its next level is always
        // the one above its first.
        let Rounding { candidates, waiting } = self;
        candidates.clear();
        // Every pixel's is written: resized only for another image.
        waiting.resize(low.len(), false);
        // Collected from an iterator of known length: no copy of `low`,
        // nor a check of the room for each.
        let pixels = real.into_iter().zip(low).zip(waiting.iter_mut()).enumerate();
        let mut out: Vec<u32> = pixels
            .map(|(i, ((r, &n), waiting))| {
                // A pixel at its count so far (most) stays there, with no
                // fraction.
                if r <= n as f64 {
                    *waiting = n < cap;
                    return n;
                }
                let f = (r as u32 / q * q).max(n);
                given += (f - n) as u64;
                let fraction = (r - f as f64) / (next(f) - f) as f64;
                // next(f) ≤ cap, cap being a whole number of quanta.
                let stepping = fraction > 0.0;
                *waiting = f < cap && !stepping;
                if f < cap && stepping {
                    candidates.push(u128::from(fraction.to_bits()) << 32 | u128::from(!(i as u32)));
                }
                f
            })
            .collect();
        let mut left = total.saturating_sub(given);
        let mut without = (0..low.len()).filter(|&i| waiting[i]);
        // The first k candidates in the order of the largest fraction (the
        // last k keys): only which pixels they are matters, not their
        // order, so a selection, not a sort; taken from the end, where
        // taking them from the front moved the rest down.
        let mut first = |k: u64| -> Vec<usize> {
            let k = k as usize;
            let pixel = |key: u128| !(key as u32) as usize;
            if k < candidates.len() {
                let rest = candidates.len() - k;
                if k > 0 {
                    candidates.select_nth_unstable(rest);
                }
                return candidates.drain(rest..).map(pixel).collect();
            }
            let mut all: Vec<usize> = candidates.drain(..).map(pixel).collect();
            all.extend(without.by_ref().take(k - all.len()));
            all
        };
        // Each step is at most a quantum, so left / quantum of them fit.
        let mut up = first(left / q as u64);
        while !up.is_empty() {
            for &i in &up {
                let f = &mut out[i];
                left -= (next(*f) - *f) as u64;
                *f = next(*f);
            }
            up = first(left / q as u64);
        }
        for i in first(left) {
            out[i] += 1;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rounding of new buffers.
    fn round_counts(real: impl IntoIterator<Item = f64>, low: &[u32], total: u64, cap: u32, quantum: u32) -> Vec<u32> {
        Rounding::default().round(real, low, total, cap, quantum)
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
        assert_eq!(round_counts(real, &[0; 7], 40, 16, 1), want(&[]));
        assert_eq!(round_counts(real, &[0; 7], 41, 16, 1), want(&[5]));
        assert_eq!(round_counts(real, &[0; 7], 42, 16, 1), want(&[5, 1]));
        assert_eq!(round_counts(real, &[0; 7], 43, 16, 1), want(&[5, 1, 0]));
        assert_eq!(round_counts(real, &[0; 7], 44, 16, 1), want(&[5, 1, 0, 3]));
        // Past the fractions: the whole counts below the cap, in order.
        assert_eq!(round_counts(real, &[0; 7], 45, 16, 1), want(&[5, 1, 0, 3, 2]));
        assert_eq!(round_counts(real, &[0; 7], 46, 16, 1), want(&[5, 1, 0, 3, 2, 6]));
        assert_eq!(round_counts(real, &[0; 7], 50, 16, 1), want(&[5, 1, 0, 3, 2, 6]));
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
        assert_eq!(round_counts(real, &low, 116, 64, 8), vec![2, 2, 8, 16, 24, 64]);
        assert_eq!(round_counts(real, &low, 124, 64, 8), vec![2, 2, 8, 16, 32, 64]);
        // Two rays left after a quantum: one each, ties to the first.
        assert_eq!(round_counts(real, &low, 126, 64, 8), vec![2, 3, 8, 17, 32, 64]);
        // Three steps (one short, 2 → 8) leave 2 rays for the last two.
        assert_eq!(round_counts(real, &low, 140, 64, 8), vec![3, 8, 9, 24, 32, 64]);
        // Short steps leave a quantum more: a second round of steps.
        let real = [5.0; 8];
        assert_eq!(round_counts(real, &[2; 8], 48, 64, 8), vec![8, 8, 8, 8, 8, 3, 3, 2]);
        // None beyond the cap.
        assert_eq!(round_counts([16.0, 15.0], &[2, 2], 40, 16, 8), vec![16, 16]);
        // The fraction is of the step: 4.5 of the 6 from 2 to 8 (0.75)
        // before 5 of the 8 from 8 to 16 (0.625), though 5 rays are more.
        assert_eq!(round_counts([6.5, 13.0], &[2, 8], 18, 64, 8), vec![8, 9]);
    }
}
