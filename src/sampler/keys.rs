//! Every key the port's samplers hash into a uniform ([`hashed_uniform`]),
//! in one place, so that no two streams of numbers share a key. The
//! streams that existed before the further dimensions keep the keys they
//! were made with (an image is the same byte for byte); the further
//! dimensions' keys carry their dimension in the top byte, which none of
//! the older keys reaches (a pixel or subpixel index stays below 2⁴⁰).

use crate::hash::hashed_uniform;

/// `--sampler random`: an independent uniform time for the `k`-th subpixel
/// of the scan order. Not the thesis's method. Key: `k`.
pub fn random_time(k: usize) -> f64 {
    hashed_uniform(k as u64)
}

/// `--sampler stratified`: the strata of pixel `pixel`'s n subpixels, a
/// permutation π of 0..n drawn for that pixel (Fisher–Yates on
/// [`hashed_uniform`]): every pixel sees each of the n strata once, and
/// neighbouring pixels see them in unrelated orders, so no pattern repeats
/// across the image. Not the thesis's method. Keys: pixel · 2²⁴ + i.
pub fn strata(pixel: usize, n: usize) -> Vec<u32> {
    shuffled((pixel as u64) << 24, n)
}

/// A permutation of 0..n drawn by Fisher–Yates from the keys `key` + i.
pub(crate) fn shuffled(key: u64, n: usize) -> Vec<u32> {
    let mut perm: Vec<u32> = (0..n as u32).collect();
    for i in 0..n.saturating_sub(1) {
        let r = i + (hashed_uniform(key + i as u64) * (n - i) as f64) as usize;
        perm.swap(i, r.min(n - 1));
    }
    perm
}

/// `--sampler stratified`: the time of subpixel `j` of pixel `pixel`,
/// a uniform place in its stratum `stratum` of n. Not the thesis's method.
pub fn stratified_time(pixel: usize, j: usize, stratum: u32, n: usize) -> f64 {
    let key = ((pixel as u64) << 24) ^ 0x00A5_A5A5 ^ ((j as u64) << 1) ^ (1 << 63);
    (stratum as f64 + hashed_uniform(key)) / n as f64
}

/// The scramble of Sobol dimension `d` < 4 for `key` (a pixel, or for the
/// time a row): the adaptive sampler's seeds of its place, time and shift.
pub(crate) fn sobol_seed(key: u64, d: u64) -> u32 {
    (hashed_uniform((key << 2 | d) ^ 0x5EED_0000_0000_0000) * 4_294_967_296.0) as u32
}

/// The streams of the further dimensions (the top byte of their keys,
/// below the dimension's number).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stream {
    /// `--sampler random`'s and every sampler's dimensions past its own:
    /// an independent uniform.
    Uniform = 1,
    /// `--sampler stratified`: the permutation of a pixel's strata.
    Strata = 2,
    /// `--sampler stratified`: the place in a stratum.
    Jitter = 3,
    /// `--sampler adaptive`: the scramble of a Sobol dimension.
    Scramble = 4,
    /// `--sampler table` and `stratified`: the order in which a pixel's
    /// subpixels take the M×M cells of a pair of dimensions (6: top
    /// nibble 5 is the Sobol seeds').
    Cells = 6,
}

/// The key of further dimension `d` of `index` (a subpixel, a pixel or a
/// pixel's sample) in `stream`: dimension and stream in the top byte and
/// a half, the index below.
pub(crate) fn dimension_key(stream: Stream, d: u32, index: u64) -> u64 {
    ((stream as u64) << 60) ^ ((u64::from(d) & 0xFFF) << 48) ^ (index & 0xFFFF_FFFF_FFFF)
}

/// A uniform in [0, 1) for further dimension `d` of `index` in `stream`.
pub(crate) fn dimension_uniform(stream: Stream, d: u32, index: u64) -> f64 {
    hashed_uniform(dimension_key(stream, d, index))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The further dimensions' keys never meet the older streams' (a
    /// subpixel index `k`, `pixel << 24 | i`, the stratified time's, the
    /// Sobol seeds'): their top nibble is a stream's, which no index below
    /// 2⁴⁰ reaches, and they differ across streams, dimensions and indices.
    #[test]
    fn dimension_keys_are_apart() {
        let mut seen = std::collections::HashSet::new();
        for stream in [
            Stream::Uniform,
            Stream::Strata,
            Stream::Jitter,
            Stream::Scramble,
            Stream::Cells,
        ] {
            for d in 0..16 {
                for index in [0u64, 1, 2, 1 << 20, (1 << 40) - 1] {
                    let k = dimension_key(stream, d, index);
                    assert!(k >> 60 >= 1, "{stream:?} {d} {index}");
                    assert!(seen.insert(k), "{stream:?} {d} {index}");
                }
            }
        }
        // The older keys' top nibbles: 0 (a subpixel k; pixel << 24 | i),
        // 5 (the Sobol seeds'), 8 and above (the stratified time's bit 63).
        let pixel: u64 = 8192 * 8192 - 1;
        let older = [
            pixel << 24 | 1023,
            pixel,
            ((pixel << 24) ^ 0x00A5_A5A5 ^ (1023 << 1) ^ (1 << 63)),
            (pixel << 2 | 3) ^ 0x5EED_0000_0000_0000,
        ];
        for k in older {
            assert!(!(1..=4).contains(&(k >> 60)) && k >> 60 != 6, "{k:#x}");
        }
    }
}
