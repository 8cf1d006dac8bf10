//! A uniform from a key: what the port's own samplers and tests draw from,
//! so that a value depends on its key alone, whatever the thread. Not the
//! thesis's (its lookup tables are [`crate::drt`]'s).

/// A uniform in [0, 1) from a 64-bit key: the SplitMix64 finaliser (Steele,
/// Lea & Flood 2014). The samplers that are not the thesis's draw from it,
/// so a sample's value depends on its index only, whatever the thread.
pub fn hashed_uniform(key: u64) -> f64 {
    let mut z = key.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}
