//! Unit `drt` of the thesis (listing in the OCR text, lines 2021–2262):
//! distributed ray tracing. So far the lookup table of pixel jitter that
//! `initialize` builds (Ch. 4 (a) (3)); `motionblur`, `boundvolume`,
//! `depthoffield`, `jittering` and `Isblur` come with the motion-blur work.

/// `maxindex`: the length of the lookup tables the cursors `aindex`,
/// `dindex` and `mindex` run through (wrapping to 1 past it). Not printed;
/// the port's choice.
pub const MAXINDEX: usize = 1000;

/// Park & Miller's "minimal standard" generator (CACM 31(10), 1988),
/// x ← 16807·x mod (2³¹ − 1): contemporary with the thesis, whose own
/// generator is not printed. Returns uniforms in (0, 1).
#[derive(Clone, Debug)]
pub struct MinimalStandard(u64);

impl MinimalStandard {
    const MODULUS: u64 = 2_147_483_647;

    /// A generator from a seed in 1..2³¹−1 (0 is taken as 1).
    pub fn new(seed: u64) -> Self {
        let s = seed % Self::MODULUS;
        MinimalStandard(if s == 0 { 1 } else { s })
    }

    /// The next uniform in (0, 1).
    pub fn next_uniform(&mut self) -> f64 {
        self.0 = (self.0 * 16807) % Self::MODULUS;
        self.0 as f64 / Self::MODULUS as f64
    }
}

/// `noise2[1..maxindex]`: the pixel-jitter table of `initialize`
/// (Reconstructed: not printed). Uniform on (−½, ½), so that
/// `noise2[aindex]*aliasing` moves a subpixel sample by at most
/// `aliasing`/2 of a subpixel either way. Index 0 here is the Pascal's 1.
pub fn noise2_table() -> Vec<f64> {
    let mut rng = MinimalStandard::new(2);
    (0..MAXINDEX).map(|_| rng.next_uniform() - 0.5).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimal_standard_known_value() {
        // Park & Miller's check: from seed 1, the 10 000th value is 1043618065.
        let mut g = MinimalStandard::new(1);
        for _ in 0..10_000 {
            g.next_uniform();
        }
        assert_eq!(g.0, 1_043_618_065);
    }

    #[test]
    fn noise2_is_centred_and_bounded() {
        let t = noise2_table();
        assert_eq!(t.len(), MAXINDEX);
        assert!(t.iter().all(|v| (-0.5..0.5).contains(v)));
        let mean = t.iter().sum::<f64>() / t.len() as f64;
        // Uniform(−½,½) has σ = 1/√12; the mean of 1000 has σ ≈ 0.0091.
        assert!(mean.abs() < 0.04, "mean {mean}");
    }
}
