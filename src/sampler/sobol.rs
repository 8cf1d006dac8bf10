//! The Sobol sequence of the adaptive sampler's samples (place in the
//! pixel, time, and the further dimensions) and its Owen scramble, apart
//! from the allocation and the passes that use them.

/// The dimensions with direction numbers here: 0–1 the place in the pixel,
/// 2 the time, 3–9 further dimensions (a lens point, a light point, a gloss
/// turn and one to spare); past them a sampler draws independent uniforms.
pub(crate) const SOBOL_DIMENSIONS: usize = 10;

/// The Sobol sequence's direction numbers, 32 bits: dimension 0 is the van
/// der Corput sequence; dimensions 1–9 come from Joe & Kuo 2008's first
/// nine rows (new-joe-kuo-6.21201: degree s, the polynomial's inner
/// coefficients a, the initial numbers m).
const DIRECTIONS: [[u32; 32]; SOBOL_DIMENSIONS] = [
    van_der_corput(),
    directions(1, 0, [1, 0, 0, 0, 0]),
    directions(2, 1, [1, 3, 0, 0, 0]),
    directions(3, 1, [1, 3, 1, 0, 0]),
    directions(3, 2, [1, 1, 1, 0, 0]),
    directions(4, 1, [1, 1, 3, 3, 0]),
    directions(4, 4, [1, 3, 5, 13, 0]),
    directions(5, 2, [1, 1, 5, 5, 17]),
    directions(5, 4, [1, 1, 5, 5, 5]),
    directions(5, 7, [1, 1, 7, 11, 19]),
];

const fn van_der_corput() -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        v[k] = 1 << (31 - k);
        k += 1;
    }
    v
}

/// Direction numbers of the polynomial of degree `s` whose inner
/// coefficients are the bits of `a` (highest first), initial numbers `m`:
/// v_k = a_1 v_{k−1} ⊕ … ⊕ a_{s−1} v_{k−s+1} ⊕ v_{k−s} ⊕ (v_{k−s} ≫ s).
const fn directions(s: usize, a: u32, m: [u32; 5]) -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        if k < s {
            v[k] = m[k] << (31 - k);
        } else {
            let mut x = v[k - s] ^ (v[k - s] >> s);
            let mut i = 1;
            while i < s {
                if (a >> (s - 1 - i)) & 1 == 1 {
                    x ^= v[k - i];
                }
                i += 1;
            }
            v[k] = x;
        }
        k += 1;
    }
    v
}

/// Point `j` of Sobol dimension `d`, as 32 bits of [0, 1): the XOR of
/// the direction numbers of `j`'s set bits.
const fn sobol_by_bits(j: u32, d: usize) -> u32 {
    let mut x = 0;
    let mut i = j;
    let mut k = 0;
    while i != 0 {
        if i & 1 == 1 {
            x ^= DIRECTIONS[d][k];
        }
        i >>= 1;
        k += 1;
    }
    x
}

/// [`sobol_by_bits`] of each byte of an index at each of its four places,
/// for the place and the time (dimensions 0–2, every sample's), with the bits already reversed for
/// [`owen_scramble_reversed`]: a point is then four lookups instead of a loop over
/// its bits with a branch each (the loop was 7 % of an adaptive render).
const SOBOL_BYTES: [[[u32; 256]; 4]; 3] = sobol_bytes();

const fn sobol_bytes() -> [[[u32; 256]; 4]; 3] {
    let mut t = [[[0u32; 256]; 4]; 3];
    let mut d = 0;
    while d < 3 {
        let mut place = 0;
        while place < 4 {
            let mut b = 0;
            while b < 256 {
                t[d][place][b] = sobol_by_bits((b as u32) << (8 * place), d).reverse_bits();
                b += 1;
            }
            place += 1;
        }
        d += 1;
    }
    t
}

/// Point `j` of Sobol dimension `d` (< [`SOBOL_DIMENSIONS`]) with its bits
/// reversed: for the place and the time by the byte tables (the sequence is
/// linear over bits, so the bytes' points XOR together), for the further
/// dimensions by the direction numbers.
pub(crate) fn sobol_reversed(j: u32, d: usize) -> u32 {
    match SOBOL_BYTES.get(d) {
        // The higher bytes' points are 0 below 256 (the adaptive sampler's
        // counts are mostly below).
        Some(t) if j < 256 => t[0][j as usize],
        Some(t) => {
            let [b0, b1, b2, b3] = j.to_le_bytes();
            t[0][b0 as usize] ^ t[1][b1 as usize] ^ t[2][b2 as usize] ^ t[3][b3 as usize]
        }
        None => sobol_by_bits(j, d).reverse_bits(),
    }
}

/// Point `j` of Sobol dimension `d`, as 32 bits of [0, 1).
#[cfg(test)]
pub(crate) fn sobol(j: u32, d: usize) -> u32 {
    sobol_reversed(j, d).reverse_bits()
}

/// A nested uniform (Owen) scramble by `seed` of a point given with its
/// 32 bits reversed, after Burley 2020: on the reversed bits, a hash in
/// which each bit depends only on the bits below it (adds and products by
/// even numbers carry upward only), so each digit of the point is flipped
/// by a function of the digits above it, as Owen's scramble does; the
/// point's bits in their own order come back.
pub(crate) fn owen_scramble_reversed(reversed: u32, seed: u32) -> u32 {
    let mut v = reversed;
    v = v.wrapping_add(seed);
    v ^= v.wrapping_mul(0x6c50_b47c);
    v ^= v.wrapping_mul(0xb82f_1e52);
    v ^= v.wrapping_mul(0xc7af_e638);
    v ^= v.wrapping_mul(0x8d22_f6e6);
    reverse(v)
}

/// The bits of every 16-bit number reversed, for [`reverse`].
static REVERSED_HALVES: [u16; 1 << 16] = reversed_halves();

const fn reversed_halves() -> [u16; 1 << 16] {
    let mut t = [0u16; 1 << 16];
    let mut i = 0;
    while i < t.len() {
        t[i] = (i as u16).reverse_bits();
        i += 1;
    }
    t
}

/// `v.reverse_bits()` in two lookups, each half's bits reversed and the
/// halves swapped: 7 instructions where `reverse_bits` takes 15 on x86-64,
/// which has no instruction for it (the adaptive sampler reverses two a
/// sample: 31 instructions a sample of fig5_3 were these).
fn reverse(v: u32) -> u32 {
    let half = |h: u32| u32::from(REVERSED_HALVES[h as usize & 0xffff]);
    half(v) << 16 | half(v >> 16)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reversal by halves is `reverse_bits`.
    #[test]
    fn reverse_by_halves() {
        for k in 0..70_000u32 {
            let v = k.wrapping_mul(0x9e37_79b9) ^ k;
            assert_eq!(reverse(v), v.reverse_bits(), "{v:#x}");
        }
        assert_eq!(reverse(1), 1 << 31);
        assert_eq!(reverse(u32::MAX - 1), u32::MAX >> 1);
    }

    /// The byte tables give the points the direction numbers give, for
    /// indices using every byte.
    #[test]
    fn byte_tables_are_the_sequence() {
        for d in 0..3 {
            for j in (0..5000u32).chain([0xff00, 0x1_2345, 0xdead_beef, u32::MAX]) {
                assert_eq!(sobol(j, d), sobol_by_bits(j, d), "dim {d} index {j}");
            }
        }
    }

    /// How many of the first 2^k points of the dimensions `dims` fall in
    /// each elementary box with `bits[i]` binary digits along dims[i].
    fn box_counts(dims: &[usize], bits: &[u32], k: u32) -> Vec<u32> {
        let total: u32 = bits.iter().sum();
        let mut counts = vec![0u32; 1 << total];
        for j in 0..1u32 << k {
            let mut cell = 0usize;
            for (&d, &b) in dims.iter().zip(bits) {
                let digits = if b == 0 { 0 } else { (sobol(j, d) >> (32 - b)) as usize };
                cell = (cell << b) | digits;
            }
            counts[cell] += 1;
        }
        counts
    }

    /// Every dimension, the further ones too, is a (0, 1)-sequence: each
    /// aligned block of 2^k points holds one point in each of the 2^k
    /// strata of [0, 1), so every dimension a shading step draws is as well
    /// spread as the time. The dimensions differ from one another.
    #[test]
    fn every_dimension_is_stratified() {
        for d in 0..SOBOL_DIMENSIONS {
            for k in 1..=9u32 {
                for block in [0u32, 1, 5] {
                    let n = 1u32 << k;
                    let mut seen = vec![false; n as usize];
                    for j in block * n..(block + 1) * n {
                        let cell = (sobol(j, d) >> (32 - k)) as usize;
                        assert!(!seen[cell], "dim {d}, k {k}, block {block}: two in stratum {cell}");
                        seen[cell] = true;
                    }
                }
            }
        }
        for a in 0..SOBOL_DIMENSIONS {
            for b in a + 1..SOBOL_DIMENSIONS {
                assert!((1..64).any(|j| sobol(j, a) != sobol(j, b)), "dims {a} and {b}");
            }
        }
    }

    /// The first 2^k points of the place in the pixel (dimensions 0 and 1)
    /// are a (0, k, 2)-net in base 2: each elementary box of area 2^−k holds
    /// exactly one. Each dimension alone, the time too, holds one point in
    /// each of 2^k strata, and the three together are a (1, k, 3)-net: each
    /// box of volume 2^(1−k) holds exactly two. So every prefix of a
    /// pixel's samples is spread in space, in time and in both.
    #[test]
    fn sobol_points_are_nets() {
        for k in 1..=10u32 {
            for split in 0..=k {
                assert!(
                    box_counts(&[0, 1], &[split, k - split], k).iter().all(|&c| c == 1),
                    "k {k} split {split}"
                );
            }
            for d in 0..3 {
                assert!(box_counts(&[d], &[k], k).iter().all(|&c| c == 1), "dim {d}, k {k}");
            }
            for a in 0..k {
                for b in 0..k - a {
                    let bits = [a, b, k - 1 - a - b];
                    assert!(
                        box_counts(&[0, 1, 2], &bits, k).iter().all(|&c| c == 2),
                        "k {k} bits {bits:?}"
                    );
                }
            }
        }
    }
}
