//! `--sampler adaptive`'s samples: where in its pixel, and when in the
//! shutter, sample j of a pixel falls, with its further dimensions; how
//! many samples each pixel gets is [`crate::adaptive`]'s. The port's
//! extension, not the thesis's method.
//!
//! Sample j of a pixel is point j of a Sobol sequence (pixel x, pixel y,
//! shutter time τ, then the further dimensions), Owen-scrambled (Burley
//! 2020, *Practical hash-based Owen scrambling*): every prefix is well
//! spread in all of them, so a pixel can stop after any count. τ is
//! uniform over [0, 1): the box shutter `blur 1` samples, so the picture
//! converges to the same one as the other samplers'.

use super::keys::{dimension_uniform, sobol_seed, Stream};
use super::sobol::{owen_scramble_reversed, sobol_reversed, SOBOL_DIMENSIONS};
use super::{screen_f64, CameraSample, Sampler};

/// A sample of a pixel: where in it (`u` across to the right, `v` down,
/// both in [0, 1)) and when in the shutter (`tau` in [0, 1)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    pub u: f64,
    pub v: f64,
    pub tau: f64,
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

impl PixelSamples {
    /// The samples of pixel `pixel` (its index in the image, row by row)
    /// of an image `width` pixels wide.
    pub fn new(pixel: usize, width: usize) -> Self {
        let row = (pixel / width.max(1)) as u64;
        PixelSamples {
            seeds: [
                sobol_seed(pixel as u64, 0),
                sobol_seed(pixel as u64, 1),
                sobol_seed(row, 2),
            ],
            shift: sobol_seed(pixel as u64, 3) % SHIFT_BLOCK,
        }
    }

    /// The samples of pixel `pixel` (its index in the image, row by row)
    /// for `--sampler sobol`: the time scrambled by a seed of the pixel's
    /// own and not shifted, so that neighbouring pixels' times are not
    /// alike (the grid's loop poses the scene for every sample; there is
    /// no instant for a row to share).
    pub fn of_pixel(pixel: usize) -> Self {
        let pixel = pixel as u64;
        PixelSamples {
            seeds: [sobol_seed(pixel, 0), sobol_seed(pixel, 1), sobol_seed(pixel, 2)],
            shift: 0,
        }
    }

    /// Where sample `j` of pixel `x` of row `row` crosses the screen, in
    /// subpixel units of `masksize` `m`: pixel x spans scancol − ½ in
    /// [x·M, (x+1)·M), and the sample lies at its place (u, v) in the
    /// pixel, unjittered.
    pub fn camera(&self, x: usize, row: usize, m: usize, j: u32) -> CameraSample {
        let (u, v) = self.place(j);
        let m = screen_f64(m);
        CameraSample {
            scancol: (screen_f64(x) + u) * m + 0.5,
            scanline: (screen_f64(row) + v) * m + 0.5,
            jx: 0.0,
            jz: 0.0,
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
        unit(owen_scramble_reversed(sobol_reversed(j, d), self.seeds[d]))
    }
}

/// Sample `j` of pixel `pixel` (its index in the image, row by row) of an
/// image `width` pixels wide.
pub fn sample(pixel: usize, width: usize, j: u32) -> Sample {
    PixelSamples::new(pixel, width).sample(j)
}

/// The sample being traced by the adaptive sampler ([`Sampler`]): sample
/// `j` of pixel `x` of row `row`, whose samples are `samples` (the row's
/// [`PixelSamples`], indexed by the pixel's column).
#[derive(Debug)]
pub struct PixelSampler<'a> {
    samples: &'a [PixelSamples],
    /// The pixel's index in the image (the key of its further dimensions).
    first: usize,
    /// `masksize`: the subpixels a pixel spans on the camera's raster.
    m: usize,
    row: usize,
    x: usize,
    j: u32,
    /// The next further dimension.
    dim: u32,
}

impl<'a> PixelSampler<'a> {
    /// The sampler of row `row` of an image `width` pixels wide, with
    /// `masksize` `m`: `samples` are the row's pixels' samples.
    pub fn new(samples: &'a [PixelSamples], row: usize, width: usize, m: usize) -> Self {
        PixelSampler {
            samples,
            first: row * width,
            m,
            row,
            x: 0,
            j: 0,
            dim: 0,
        }
    }

    /// Starts sample `j` of pixel `x` of the row.
    pub fn start(&mut self, x: usize, j: u32) {
        (self.x, self.j, self.dim) = (x, j, 0);
    }
}

impl Sampler for PixelSampler<'_> {
    /// The row's instant `j ⊕ c` ([`PixelSamples::tau`]).
    fn time(&mut self) -> f64 {
        self.samples[self.x].tau(self.j)
    }

    /// The sample's place in its pixel ([`PixelSamples::camera`]).
    fn camera(&self) -> CameraSample {
        self.samples[self.x].camera(self.x, self.row, self.m, self.j)
    }

    /// [`further_dimension`] d of the pixel's sample.
    fn get_1d(&mut self) -> f64 {
        let d = self.dim;
        self.dim += 1;
        further_dimension(self.first + self.x, self.j, d)
    }
}

/// Further dimension `d` of sample `j` of pixel `pixel` (its index in the
/// image, row by row): Sobol dimension 3 + d, scrambled by a seed of the
/// pixel and the dimension; past the last one, an independent uniform.
pub fn further_dimension(pixel: usize, j: u32, d: u32) -> f64 {
    let pixel = pixel as u64;
    let sobol = 3 + d as usize;
    if sobol < SOBOL_DIMENSIONS {
        let seed = (dimension_uniform(Stream::Scramble, d, pixel) * 4_294_967_296.0) as u32;
        unit(owen_scramble_reversed(sobol_reversed(j, sobol), seed))
    } else {
        dimension_uniform(Stream::Uniform, d, pixel << 20 | u64::from(j))
    }
}

/// 32 bits of [0, 1) as a number.
fn unit(bits: u32) -> f64 {
    bits as f64 / 4_294_967_296.0
}

#[cfg(test)]
mod tests {
    use super::super::sobol::sobol;
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

    /// The further dimensions of a pixel's samples: in [0, 1), each
    /// stratified over an aligned block of 2^k samples (the Sobol
    /// dimensions), the same for the same sample and pixel, different from
    /// pixel to pixel; past the Sobol dimensions, still in [0, 1).
    #[test]
    fn further_dimensions_are_stratified_per_pixel() {
        let w = 10;
        let samples: Vec<PixelSamples> = (0..w).map(|x| PixelSamples::new(3 * w + x, w)).collect();
        let mut s = PixelSampler::new(&samples, 3, w, 2);
        let n = 32u32;
        let dims = 12;
        let mut strata = vec![vec![false; n as usize]; SOBOL_DIMENSIONS - 3];
        for j in n..2 * n {
            s.start(4, j);
            let values: Vec<f64> = (0..dims).map(|_| s.get_1d()).collect();
            s.start(4, j);
            let again: Vec<f64> = (0..dims / 2).flat_map(|_| s.get_2d()).collect();
            assert_eq!(values, again);
            assert!(values.iter().all(|v| (0.0..1.0).contains(v)), "{values:?}");
            for (d, seen) in strata.iter_mut().enumerate() {
                let cell = (values[d] * f64::from(n)) as usize;
                assert!(!seen[cell], "dim {d}: two in stratum {cell}");
                seen[cell] = true;
            }
            s.start(5, j);
            assert_ne!(s.get_1d(), values[0], "pixel 5 and pixel 4, sample {j}");
        }
    }

    /// The camera sample lies in the pixel's square of M × M subpixels.
    #[test]
    fn the_place_lies_in_the_pixel() {
        let w = 7;
        let samples: Vec<PixelSamples> = (0..w).map(|x| PixelSamples::new(2 * w + x, w)).collect();
        let mut s = PixelSampler::new(&samples, 2, w, 4);
        for x in 0..w {
            for j in 0..40 {
                s.start(x, j);
                let c = s.camera();
                assert!((x as f64 * 4.0 + 0.5..(x + 1) as f64 * 4.0 + 0.5).contains(&c.scancol));
                assert!((8.5..12.5).contains(&c.scanline));
                assert_eq!((c.jx, c.jz), (0.0, 0.0));
            }
        }
    }
}
