//! The samplers of the listing's scanline loop (`--sampler table`,
//! `random`, `stratified`): one sample a subpixel (`scanline`, `scancol`),
//! `masksize`² a pixel, in the order the main program traces them.
//!
//! Every value is a function of the subpixel, never of how many were taken
//! before it: where the listing keeps a cursor that it advances once a
//! subpixel (`aindex` for the jitter, `mindex` for the time, `dindex` for
//! `depthoffield`'s noise), the port takes the cursor of subpixel k of the
//! scan order to be k, which is what the sequential loop gives (and so the
//! same for any number of threads and any window of rows).

use super::keys::{dimension_key, dimension_uniform, random_time, shuffled, strata, stratified_time, Stream};
use super::{CameraSample, Sampler};
use crate::drt::{noise2_table, noise_table, MinimalStandard, TimeTable, MAXINDEX};
use crate::options::{Fidelity, TimeSampler};

/// The further dimensions the table sampler reads from tables of its own
/// (dimension 0 from `noise`, the table `depthoffield` reads); past them,
/// independent uniforms.
pub const TABLE_DIMENSIONS: usize = 8;

/// The lookup tables `initialize` builds (Ch. 4 (a)(3)) that the samplers
/// read: the subpixel times (the pattern table and the CLT table), the
/// jitter table `noise2`, and for the further dimensions `noise` and one
/// table a dimension after it. Made once a render.
#[derive(Clone, Debug)]
pub struct Tables {
    pub times: TimeTable,
    noise2: Vec<f64>,
    dimensions: Vec<Vec<f64>>,
}

impl Tables {
    /// The tables, with the subpixel times `times`.
    pub fn new(times: TimeTable) -> Tables {
        let mut dimensions = vec![noise_table()];
        // The port's: one table a further dimension past `noise`, each
        // from its own seed of the same generator, on (−½, ½) as `noise`.
        dimensions.extend((1..TABLE_DIMENSIONS as u64).map(|d| {
            let mut rng = MinimalStandard::new(10 + d);
            (0..MAXINDEX).map(|_| rng.next_uniform() - 0.5).collect()
        }));
        Tables {
            times,
            noise2: noise2_table(),
            dimensions,
        }
    }
}

/// How the grid sampler chooses a subpixel's time and further dimensions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridKind {
    /// The thesis's pattern table with its CLT jitter; the tables' cursors.
    Table,
    /// Independent uniforms.
    Random,
    /// One value in each of the pixel's M² strata, dealt by a permutation
    /// of the pixel's own, for the time and for each further dimension.
    Stratified,
}

impl GridKind {
    /// The grid sampler of `--sampler`; `None` for the adaptive sampler,
    /// which is not laid out on the subpixel grid.
    pub fn of(sampler: TimeSampler) -> Option<GridKind> {
        match sampler {
            TimeSampler::Table => Some(GridKind::Table),
            TimeSampler::Random => Some(GridKind::Random),
            TimeSampler::Stratified => Some(GridKind::Stratified),
            TimeSampler::Adaptive => None,
        }
    }
}

/// The sample of subpixel (`scanline`, `scancol`) of the scanline loop
/// ([`Sampler`]): started by [`GridSampler::start`] within the row of
/// pixels [`GridSampler::start_row`] named.
#[derive(Clone, Debug)]
pub struct GridSampler<'a> {
    tables: &'a Tables,
    kind: GridKind,
    fidelity: Fidelity,
    /// `aliasing`: the jitter's amplitude.
    aliasing: f64,
    /// `masksize`.
    m: usize,
    /// Pixels a row.
    width: usize,
    /// `virthighx`: subpixels a scanline.
    virthighx: usize,
    row: usize,
    /// The strata of each pixel of the row (stratified times), made when
    /// the row's first time is asked.
    row_strata: Vec<Vec<u32>>,
    /// For each further dimension, the strata of each pixel of the row
    /// (stratified), each made when first asked.
    dimension_strata: Vec<Vec<Option<Vec<u32>>>>,
    scanline: usize,
    scancol: usize,
    dim: u32,
}

impl<'a> GridSampler<'a> {
    /// The sampler of an image `width` pixels wide of `m`×`m` subpixels a
    /// pixel, jittered by `aliasing`.
    pub fn new(tables: &'a Tables, kind: GridKind, fidelity: Fidelity, width: usize, m: usize, aliasing: f64) -> Self {
        GridSampler {
            tables,
            kind,
            fidelity,
            aliasing,
            m,
            width,
            virthighx: width * m,
            row: 0,
            row_strata: Vec::new(),
            dimension_strata: Vec::new(),
            scanline: 1,
            scancol: 1,
            dim: 0,
        }
    }

    /// The row of pixels whose subpixels come next.
    pub fn start_row(&mut self, row: usize) {
        self.row = row;
        self.row_strata.clear();
        self.dimension_strata.clear();
    }

    /// Starts the sample of subpixel (`scanline`, `scancol`), 1-based as in
    /// the listing; `scancol` 0 is erratum 13's extra column.
    pub fn start(&mut self, scanline: usize, scancol: usize) {
        (self.scanline, self.scancol, self.dim) = (scanline, scancol, 0);
    }

    /// k: the subpixel's place in the scan order, 0-based (the extra
    /// column shares column 1's): the listing's cursors at it.
    fn k(&self) -> usize {
        (self.scanline - 1) * self.virthighx + self.scancol.max(1) - 1
    }

    /// The pixel of the row the subpixel lies in, and its index j among
    /// the pixel's M² subpixels (row by row).
    fn pixel_and_index(&self) -> (usize, usize) {
        let c = self.scancol.max(1) - 1;
        let sub = self.scanline - 1 - self.row * self.m;
        (c / self.m, sub * self.m + c % self.m)
    }
}

impl Sampler for GridSampler<'_> {
    /// `--sampler table`: the first lines of `motionblur`
    /// ([`TimeTable::time`], errata 1 and 2); `random`: an independent
    /// uniform; `stratified`: a place in the stratum the pixel's
    /// permutation deals the subpixel.
    fn time(&mut self) -> f64 {
        let k = self.k();
        match self.kind {
            GridKind::Table => self.tables.times.time(self.scanline, self.scancol, k),
            GridKind::Random => random_time(k),
            GridKind::Stratified => {
                let (x, j) = self.pixel_and_index();
                let n = self.m * self.m;
                if self.row_strata.is_empty() {
                    let first = self.row * self.width;
                    self.row_strata = (0..self.width).map(|x| strata(first + x, n)).collect();
                }
                stratified_time(self.row * self.width + x, j, self.row_strata[x][j], n)
            }
        }
    }

    /// The subpixel, moved by `noise2[aindex]*aliasing` in x and z.
    ///
    /// Erratum 15 (the port's reading): `aindex := aindex + 1` is commented
    /// out in the listing, so every subpixel moves by the same
    /// `noise2[aindex]*aliasing`, in x and z alike; `thesis` fidelity
    /// (§2.1.3 (4), stochastic sampling) advances the cursor: subpixel k of
    /// the scan order takes entries 2k and 2k+1 (mod `maxindex`) for x and z.
    fn camera(&self) -> CameraSample {
        let noise2 = &self.tables.noise2;
        let (jx, jz) = match self.fidelity {
            Fidelity::Listing => {
                let j = noise2[0] * self.aliasing;
                (j, j)
            }
            Fidelity::Thesis => {
                let k = self.k();
                let ax = (2 * k) % MAXINDEX;
                let az = (2 * k + 1) % MAXINDEX;
                (noise2[ax] * self.aliasing, noise2[az] * self.aliasing)
            }
        };
        CameraSample {
            scancol: self.scancol as f64,
            scanline: self.scanline as f64,
            jx,
            jz,
        }
    }

    /// Further dimension d of subpixel k. `table`: entry k (mod
    /// `maxindex`) of the dimension's table, as `depthoffield` reads
    /// `noise[dindex]` (the port's reading of its cursor: one entry a
    /// subpixel); `random`: an independent uniform; `stratified`: a place
    /// in the stratum a permutation of the pixel's, one a dimension, deals
    /// the subpixel. Past the table's dimensions, independent uniforms.
    fn get_1d(&mut self) -> f64 {
        let d = self.dim;
        self.dim += 1;
        let k = self.k() as u64;
        match self.kind {
            GridKind::Table => match self.tables.dimensions.get(d as usize) {
                Some(table) => table[self.k() % MAXINDEX] + 0.5,
                None => dimension_uniform(Stream::Uniform, d, k),
            },
            GridKind::Random => dimension_uniform(Stream::Uniform, d, k),
            GridKind::Stratified => {
                let (x, j) = self.pixel_and_index();
                let pixel = (self.row * self.width + x) as u64;
                let n = self.m * self.m;
                let d = d as usize;
                if self.dimension_strata.len() <= d {
                    self.dimension_strata.resize(d + 1, vec![None; self.width]);
                }
                // A permutation of the pixel's own for each dimension
                // (keys pixel · 2¹¹ + i: a pixel's n ≤ 1024 keys apart).
                let strata = self.dimension_strata[d][x]
                    .get_or_insert_with(|| shuffled(dimension_key(Stream::Strata, d as u32, pixel << 11), n));
                let jitter = dimension_uniform(Stream::Jitter, d as u32, pixel << 11 | j as u64);
                (f64::from(strata[j]) + jitter) / n as f64
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tables() -> Tables {
        Tables::new(TimeTable::with_default_pattern(2, 1, Fidelity::Thesis))
    }

    /// Every further dimension: in (0, 1); the same values when a sample
    /// is started again, whether drawn one by one or in pairs.
    #[test]
    fn further_dimensions_repeat_and_stay_in_the_unit_interval() {
        let t = tables();
        for kind in [GridKind::Table, GridKind::Random, GridKind::Stratified] {
            let mut s = GridSampler::new(&t, kind, Fidelity::Thesis, 8, 2, 0.5);
            s.start_row(3);
            s.start(8, 5);
            let one: Vec<f64> = (0..12).map(|_| s.get_1d()).collect();
            s.start(8, 5);
            let two: Vec<f64> = (0..6).flat_map(|_| s.get_2d()).collect();
            assert_eq!(one, two, "{kind:?}");
            assert!(one.iter().all(|v| *v > 0.0 && *v < 1.0), "{kind:?}: {one:?}");
        }
    }

    /// The table's first further dimension is `noise[dindex]` with the
    /// cursor at the subpixel's place k in the scan order.
    #[test]
    fn the_tables_first_dimension_is_depthoffields_noise() {
        let t = tables();
        let noise = noise_table();
        let mut s = GridSampler::new(&t, GridKind::Table, Fidelity::Listing, 300, 2, 0.5);
        for (scanline, scancol) in [(1, 1), (1, 0), (2, 7), (4, 600), (5, 3)] {
            s.start_row((scanline - 1) / 2);
            s.start(scanline, scancol);
            let k = (scanline - 1) * 600 + scancol.max(1) - 1;
            assert_eq!(s.get_1d(), noise[k % MAXINDEX] + 0.5, "({scanline}, {scancol})");
        }
    }

    /// Stratified: over a pixel's M² subpixels each further dimension (and
    /// the time) takes each of the M² strata once, in an order that differs
    /// from dimension to dimension (so one does not decide another).
    #[test]
    fn stratified_dimensions_fill_their_strata() {
        let t = tables();
        for m in [2usize, 3, 4] {
            let n = m * m;
            let mut s = GridSampler::new(&t, GridKind::Stratified, Fidelity::Thesis, 5, m, 0.5);
            let row = 2;
            s.start_row(row);
            let dims = 6;
            let mut cells = vec![vec![usize::MAX; n]; dims + 1];
            for sub in 0..m {
                for c in 0..m {
                    let (scanline, scancol) = (row * m + sub + 1, 3 * m + c + 1);
                    s.start(scanline, scancol);
                    let j = sub * m + c;
                    cells[0][j] = (s.time() * n as f64) as usize;
                    for d in 0..dims {
                        cells[d + 1][j] = (s.get_1d() * n as f64) as usize;
                    }
                }
            }
            for (d, c) in cells.iter().enumerate() {
                let mut sorted = c.clone();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "m {m}, dimension {d}");
            }
            assert!(cells[1..].iter().any(|c| c != &cells[0]), "m {m}");
            assert!(cells[2..].iter().any(|c| c != &cells[1]), "m {m}");
        }
    }

    /// Random: the further dimensions do not follow the time (Cook 1984:
    /// a ray's time must not decide its lens position): over many subpixels
    /// their correlation with the time is near 0.
    #[test]
    fn random_dimensions_are_independent_of_the_time() {
        let t = tables();
        let mut s = GridSampler::new(&t, GridKind::Random, Fidelity::Thesis, 64, 2, 0.5);
        let (mut times, mut firsts) = (Vec::new(), Vec::new());
        for row in 0..32 {
            s.start_row(row);
            for scanline in row * 2 + 1..=row * 2 + 2 {
                for scancol in 1..=128 {
                    s.start(scanline, scancol);
                    times.push(s.time());
                    firsts.push(s.get_1d());
                }
            }
        }
        let n = times.len() as f64;
        let mean = |v: &[f64]| v.iter().sum::<f64>() / n;
        let (mt, mf) = (mean(&times), mean(&firsts));
        let cov = times.iter().zip(&firsts).map(|(a, b)| (a - mt) * (b - mf)).sum::<f64>() / n;
        // Uniforms have variance 1/12; 8192 pairs give a correlation of σ ≈ 0.011.
        let corr = cov * 12.0;
        assert!(corr.abs() < 0.05, "correlation {corr}");
        assert!((mf - 0.5).abs() < 0.02, "mean {mf}");
    }
}
