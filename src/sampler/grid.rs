//! The samplers of the listing's scanline loop (`--sampler table`,
//! `random`, `stratified`, `sobol`): one sample a subpixel (`scanline`,
//! `scancol`), `masksize`² a pixel, in the order the main program traces
//! them.
//!
//! Every value is a function of the subpixel, never of how many were taken
//! before it: where the listing keeps a cursor that it advances once a
//! subpixel (`aindex` for the jitter, `mindex` for the time, `dindex` for
//! `depthoffield`'s noise), the port takes the cursor of subpixel k of the
//! scan order to be k, which is what the sequential loop gives (and so the
//! same for any number of threads and any window of rows).

use super::array::Field;
use super::keys::{dimension_key, dimension_uniform, random_time, shuffled, strata, stratified_time, Stream};
use super::pixel::{further_dimension, PixelSamples};
use super::{screen_f64, CameraSample, Sampler};
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
    /// `noise2` in pairs: entries 2i and 2i + 1 at `noise2[i]`, the x and
    /// z jitter that `thesis` fidelity reads together (erratum 15), found
    /// by one index in an array of known length.
    noise2: Box<[[f64; 2]; MAXINDEX / 2]>,
    dimensions: Vec<Vec<f64>>,
}

// `noise2` pairs up whole.
const _: () = assert!(MAXINDEX.is_multiple_of(2));

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
        let noise2 = noise2_table();
        Tables {
            times,
            noise2: Box::new(std::array::from_fn(|i| [noise2[2 * i], noise2[2 * i + 1]])),
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
    /// of the pixel's own, for the time and for each further dimension; a
    /// pair of further dimensions drawn together, one point in each of
    /// the unit square's M×M cells.
    Stratified,
    /// Subpixel j of a pixel (row by row) takes point j of the pixel's
    /// Owen-scrambled Sobol sequence ([`PixelSamples::of_pixel`]) for its
    /// place in the pixel, its time and its further dimensions: all of
    /// them stratified together, not only each alone.
    Sobol,
}

/// Where a render's samples fall: on the subpixel grid, by one of its
/// samplers, or dealt out over the image by each pixel's need (the
/// adaptive sampler, [`crate::adaptive`]). Every `--sampler` is one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    Grid(GridKind),
    Adaptive,
}

impl Layout {
    /// The layout of `--sampler`.
    pub fn of(sampler: TimeSampler) -> Layout {
        match sampler {
            TimeSampler::Table => Layout::Grid(GridKind::Table),
            TimeSampler::Random => Layout::Grid(GridKind::Random),
            TimeSampler::Stratified => Layout::Grid(GridKind::Stratified),
            TimeSampler::Sobol => Layout::Grid(GridKind::Sobol),
            TimeSampler::Adaptive => Layout::Adaptive,
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
    /// The field of M elements, if any: the first pair's array.
    field: Option<Field>,
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
    /// For each pair of further dimensions drawn together (by its first),
    /// the shuffles that deal each pixel of the row its M×M cells and
    /// sub-cells (table, stratified), each made when first asked.
    cell_strata: Vec<Vec<Option<Vec<u32>>>>,
    /// The Sobol samples of each pixel of the row (`sobol`), made when the
    /// row's first sample asks.
    row_sobol: Vec<PixelSamples>,
    scanline: usize,
    scancol: usize,
    /// The subpixel's place in the scan order, 0-based (the extra column
    /// shares column 1's): the listing's cursors at it, found once a
    /// sample.
    k: usize,
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
            field: Field::of(m),
            width,
            virthighx: width * m,
            row: 0,
            row_strata: Vec::new(),
            dimension_strata: Vec::new(),
            cell_strata: Vec::new(),
            row_sobol: Vec::new(),
            scanline: 1,
            scancol: 1,
            k: 0,
            dim: 0,
        }
    }

    /// The row of pixels whose subpixels come next.
    pub fn start_row(&mut self, row: usize) {
        self.row = row;
        self.row_strata.clear();
        self.dimension_strata.clear();
        self.cell_strata.clear();
        self.row_sobol.clear();
    }

    /// Starts the sample of subpixel (`scanline`, `scancol`), 1-based as in
    /// the listing; `scancol` 0 is erratum 13's extra column.
    #[inline]
    pub fn start(&mut self, scanline: usize, scancol: usize) {
        let k = (scanline - 1) * self.virthighx + scancol.max(1) - 1;
        (self.scanline, self.scancol, self.k, self.dim) = (scanline, scancol, k, 0);
    }

    /// The pixel of the row the subpixel lies in, and its index j among
    /// the pixel's M² subpixels (row by row).
    fn pixel_and_index(&self) -> (usize, usize) {
        let c = self.scancol.max(1) - 1;
        let sub = self.scanline - 1 - self.row * self.m;
        (c / self.m, sub * self.m + c % self.m)
    }

    /// `sobol`: the subpixel's pixel in the row, its Sobol samples, and
    /// its index among them.
    fn sobol(&mut self) -> (usize, PixelSamples, u32) {
        let (x, j) = self.pixel_and_index();
        if self.row_sobol.is_empty() {
            let first = self.row * self.width;
            self.row_sobol = (0..self.width).map(|x| PixelSamples::of_pixel(first + x)).collect();
        }
        (x, self.row_sobol[x], j as u32)
    }

    /// [`Sampler::time`] of `stratified` and `sobol`, which read the
    /// row's strata or Sobol samples: kept out of the table's path.
    #[inline(never)]
    fn pixel_time(&mut self) -> f64 {
        if self.kind == GridKind::Sobol {
            let (_, samples, j) = self.sobol();
            return samples.tau(j);
        }
        let (x, j) = self.pixel_and_index();
        let n = self.m * self.m;
        if self.row_strata.is_empty() {
            let first = self.row * self.width;
            self.row_strata = (0..self.width).map(|x| strata(first + x, n)).collect();
        }
        stratified_time(self.row * self.width + x, j, self.row_strata[x][j], n)
    }

    /// [`Sampler::camera`] of `sobol`: the sample's own place in the
    /// pixel, kept out of the other samplers' path.
    #[inline(never)]
    fn sobol_camera(&self) -> CameraSample {
        let (x, j) = self.pixel_and_index();
        let samples =
            (self.row_sobol.get(x).copied()).unwrap_or_else(|| PixelSamples::of_pixel(self.row * self.width + x));
        samples.camera(x, self.row, self.m, j as u32)
    }
}

impl Sampler for GridSampler<'_> {
    /// `--sampler table`: the first lines of `motionblur`
    /// ([`TimeTable::time`], errata 1 and 2); `random`: an independent
    /// uniform; `stratified`: a place in the stratum the pixel's
    /// permutation deals the subpixel.
    #[inline]
    fn time(&mut self) -> f64 {
        match self.kind {
            GridKind::Table => self.tables.times.time(self.scanline, self.scancol, self.k),
            GridKind::Random => random_time(self.k),
            GridKind::Stratified | GridKind::Sobol => self.pixel_time(),
        }
    }

    /// The subpixel, moved by `noise2[aindex]*aliasing` in x and z.
    ///
    /// Erratum 15 (the port's reading): `aindex := aindex + 1` is commented
    /// out in the listing, so every subpixel moves by the same
    /// `noise2[aindex]*aliasing`, in x and z alike; `thesis` fidelity
    /// (§2.1.3 (4), stochastic sampling) advances the cursor: subpixel k of
    /// the scan order takes entries 2k and 2k+1 (mod `maxindex`) for x and z.
    ///
    /// `sobol`: the sample's own place in the pixel, as the adaptive
    /// sampler's ([`PixelSamples::camera`]), for either fidelity.
    #[inline]
    fn camera(&self) -> CameraSample {
        if self.kind == GridKind::Sobol {
            return self.sobol_camera();
        }
        let noise2 = &self.tables.noise2;
        let (jx, jz) = match self.fidelity {
            Fidelity::Listing => {
                let j = noise2[0][0] * self.aliasing;
                (j, j)
            }
            // Entries (2k mod maxindex, 2k + 1 mod maxindex), the pair
            // k mod maxindex/2.
            Fidelity::Thesis => {
                let [ax, az] = noise2[self.k % (MAXINDEX / 2)];
                (ax * self.aliasing, az * self.aliasing)
            }
        };
        CameraSample {
            scancol: screen_f64(self.scancol),
            scanline: screen_f64(self.scanline),
            jx,
            jz,
        }
    }

    /// Further dimension d of subpixel k. `table`: entry k (mod
    /// `maxindex`) of the dimension's table, as `depthoffield` reads
    /// `noise[dindex]` (the port's reading of its cursor: one entry a
    /// subpixel); `random`: an independent uniform; `stratified`: a place
    /// in the stratum a permutation of the pixel's, one a dimension, deals
    /// the subpixel; `sobol`: the pixel's scrambled Sobol dimension 3 + d
    /// at the subpixel's index, as the adaptive sampler's
    /// ([`further_dimension`]). Past the table's (or the Sobol
    /// sequence's) dimensions, independent uniforms.
    fn get_1d(&mut self) -> f64 {
        let d = self.dim;
        self.dim += 1;
        let k = self.k as u64;
        match self.kind {
            GridKind::Table => match self.tables.dimensions.get(d as usize) {
                Some(table) => table[self.k % MAXINDEX] + 0.5,
                None => dimension_uniform(Stream::Uniform, d, k),
            },
            GridKind::Random => dimension_uniform(Stream::Uniform, d, k),
            GridKind::Sobol => {
                let (x, _, j) = self.sobol();
                further_dimension(self.row * self.width + x, j, d)
            }
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

    /// Further dimensions d and d + 1 together. `random`: two independent
    /// uniforms, as [`GridSampler::get_1d`] twice; `sobol`: the sample's
    /// Sobol dimensions d and d + 1, as `get_1d` twice. `table` and
    /// `stratified` (the port's, D48): the pixel's M² subpixels take the
    /// unit square's M×M cells once each, dealt by the pixel's own
    /// shuffle for the pair, never the time's (a ray's time does not
    /// decide its lens position, Cook 1984): for the first pair (the
    /// lens, when there is one) the cell of Bose's array of the
    /// subpixel's place (`Field::cell`) with its columns and rows
    /// shuffled, so that the lens is stratified with the place in the
    /// pixel too (where M has no field, along each axis only); for the
    /// others a permutation of the cells. Within its cell a point of one
    /// of M×M sub-cells, the sub-column by a permutation of the cell's
    /// row and the sub-row by one of its column, the same for the whole
    /// pixel (Kensler's correlated multi-jitter), so that each coordinate
    /// alone also takes each of M² strata once; the place in the sub-cell
    /// from the tables d and d + 1 at the subpixel's cursor (`table`, as
    /// `get_1d`) or a uniform (`stratified`).
    fn get_2d(&mut self) -> [f64; 2] {
        if matches!(self.kind, GridKind::Random | GridKind::Sobol) {
            let a = self.get_1d();
            return [a, self.get_1d()];
        }
        let d = self.dim;
        self.dim += 2;
        let (x, j) = self.pixel_and_index();
        let pixel = (self.row * self.width + x) as u64;
        let m = self.m;
        let slot = d as usize;
        if self.cell_strata.len() <= slot {
            self.cell_strata.resize(slot + 1, vec![None; self.width]);
        }
        // Keys pixel · 2¹¹ + i: the cells (i < 1024), then M each for the
        // sub-columns, sub-rows, and the array's columns and rows.
        let deal = self.cell_strata[slot][x].get_or_insert_with(|| {
            let key = dimension_key(Stream::Cells, d, pixel << 11);
            let mut deal = shuffled(key, m * m);
            for part in [1024, 1280, 1536, 1792] {
                deal.extend(shuffled(key + part, m));
            }
            deal
        });
        let n = m * m;
        let (column, row) = match (d, self.field) {
            (0, Some(field)) => {
                let (c, r) = field.cell(j % m, j / m);
                (deal[n + 2 * m + c] as usize, deal[n + 3 * m + r] as usize)
            }
            // No array of four columns (M = 2, 6, …): the cell's column by
            // the place's row and its row by the place's column, shuffled,
            // a bijection that takes every (place column, cell column) and
            // (place row, cell row) once, the pairs a defocused surface
            // adds along one axis.
            (0, None) => (deal[n + 2 * m + j / m] as usize, deal[n + 3 * m + j % m] as usize),
            _ => (deal[j] as usize % m, deal[j] as usize / m),
        };
        let (sub_column, sub_row) = (deal[n + row], deal[n + m + column]);
        let k = self.k;
        let place = |e: u32| match (self.kind, self.tables.dimensions.get(e as usize)) {
            (GridKind::Table, Some(table)) => table[k % MAXINDEX] + 0.5,
            _ => dimension_uniform(Stream::Jitter, e, pixel << 11 | j as u64),
        };
        let n = n as f64;
        [
            ((column * m) as f64 + f64::from(sub_column) + place(d)) / n,
            ((row * m) as f64 + f64::from(sub_row) + place(d + 1)) / n,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tables() -> Tables {
        Tables::new(TimeTable::with_default_pattern(2, 1, Fidelity::Thesis))
    }

    /// Every further dimension: in (0, 1); the same values when a sample
    /// is started again. `random` gives the same whether drawn one by one
    /// or in pairs; the others draw a pair from cells of its own.
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
            s.start(8, 5);
            let again: Vec<f64> = (0..6).flat_map(|_| s.get_2d()).collect();
            s.start(8, 5);
            assert_eq!(s.get_1d(), one[0], "{kind:?}");
            assert_eq!(two, again, "{kind:?}");
            assert_eq!(one == two, kind == GridKind::Random, "{kind:?}");
            for v in one.iter().chain(&two) {
                assert!(*v > 0.0 && *v < 1.0, "{kind:?}: {one:?} {two:?}");
            }
        }
    }

    /// The points of subpixel j's pairs of further dimensions and its
    /// time's stratum, over the pixel (`x`, `row`)'s M² subpixels:
    /// `points[p][j]` is pair p's.
    fn pixel_points(s: &mut GridSampler, x: usize, row: usize, pairs: usize) -> (Vec<Vec<[f64; 2]>>, Vec<usize>) {
        let m = s.m;
        let n = m * m;
        let mut points = vec![vec![[f64::NAN; 2]; n]; pairs];
        let mut times = vec![usize::MAX; n];
        for sub in 0..m {
            for c in 0..m {
                s.start(row * m + sub + 1, x * m + c + 1);
                let j = sub * m + c;
                times[j] = (s.time() * n as f64).min(n as f64 - 1.0) as usize;
                for point in points.iter_mut() {
                    let [u, v] = s.get_2d();
                    assert!((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v), "{u} {v}");
                    point[j] = [u, v];
                }
            }
        }
        (points, times)
    }

    /// As [`pixel_points`], each point's cell (column + M·row of the unit
    /// square's M×M).
    fn pixel_cells(s: &mut GridSampler, x: usize, row: usize, pairs: usize) -> (Vec<Vec<usize>>, Vec<usize>) {
        let m = s.m as f64;
        let (points, times) = pixel_points(s, x, row, pairs);
        let cell = |[u, v]: [f64; 2]| (u * m) as usize + s.m * (v * m) as usize;
        (
            points.iter().map(|p| p.iter().map(|&q| cell(q)).collect()).collect(),
            times,
        )
    }

    /// Table and stratified: within its cell each point lies in a sub-cell
    /// such that each coordinate alone takes each of the M² strata once
    /// over the pixel; the place in the sub-cell is the tables' entry at
    /// the subpixel's cursor (`table`: `noise` for the first coordinate,
    /// the next table for the second) or a uniform that differs from
    /// coordinate to coordinate, subpixel to subpixel and pixel to pixel
    /// (`stratified`).
    #[test]
    fn paired_coordinates_fill_their_strata() {
        let t = tables();
        let noise = noise_table();
        let (m, width) = (4usize, 300);
        let n = m * m;
        for kind in [GridKind::Table, GridKind::Stratified] {
            let mut s = GridSampler::new(&t, kind, Fidelity::Thesis, width, m, 0.5);
            let mut places = Vec::new();
            for (x, row) in [(0, 0), (7, 2), (299, 3)] {
                s.start_row(row);
                let (points, _) = pixel_points(&mut s, x, row, 2);
                for (p, pair) in points.iter().enumerate() {
                    for axis in 0..2 {
                        let mut strata: Vec<usize> = pair.iter().map(|q| (q[axis] * n as f64) as usize).collect();
                        strata.sort_unstable();
                        assert_eq!(
                            strata,
                            (0..n).collect::<Vec<_>>(),
                            "{kind:?} ({x}, {row}) pair {p} axis {axis}"
                        );
                    }
                }
                for (j, q) in points[0].iter().enumerate() {
                    let [pu, pv] = q.map(|c| c * n as f64 - (c * n as f64).floor());
                    if kind == GridKind::Table {
                        let k = (row * m + j / m) * width * m + x * m + j % m;
                        assert!((pu - (noise[k % MAXINDEX] + 0.5)).abs() < 1e-9, "({x}, {row}) {j}");
                        assert!(
                            (pv - (t.dimensions[1][k % MAXINDEX] + 0.5)).abs() < 1e-9,
                            "({x}, {row}) {j}"
                        );
                    }
                    assert!((pu - pv).abs() > 1e-12, "{kind:?} ({x}, {row}) {j}");
                    places.push(pu);
                }
            }
            places.sort_by(f64::total_cmp);
            places.dedup();
            assert_eq!(places.len(), 3 * n, "{kind:?}");
        }
    }

    /// Table and stratified: over a pixel's M² subpixels each pair of
    /// further dimensions drawn together takes each of the unit square's
    /// M×M cells exactly once (a lens point in every cell of the
    /// aperture), in every pixel, in an order that differs from pair to
    /// pair and from pixel to pixel.
    #[test]
    fn paired_dimensions_take_every_cell_once() {
        let t = tables();
        for kind in [GridKind::Table, GridKind::Stratified] {
            for m in [2usize, 3, 4, 8] {
                let width = 6;
                let mut s = GridSampler::new(&t, kind, Fidelity::Thesis, width, m, 0.5);
                let mut orders = Vec::new();
                for row in [0, 5] {
                    s.start_row(row);
                    for x in 0..width {
                        let (cells, _) = pixel_cells(&mut s, x, row, 3);
                        for (p, c) in cells.iter().enumerate() {
                            let mut sorted = c.clone();
                            sorted.sort_unstable();
                            assert_eq!(
                                sorted,
                                (0..m * m).collect::<Vec<_>>(),
                                "{kind:?} m {m} ({x}, {row}) pair {p}"
                            );
                        }
                        assert!(cells[1] != cells[0] || cells[2] != cells[1], "{kind:?} m {m}");
                        orders.push(cells[0].clone());
                    }
                }
                assert!(orders.iter().any(|o| o != &orders[0]), "{kind:?} m {m}");
            }
        }
    }

    /// Table and stratified: a subpixel's lens cell does not follow its
    /// time (Cook 1984): over many pixels, the subpixels of each time
    /// stratum take every lens cell about equally often (the cells are
    /// not dealt by the time's permutation, nor by a fixed pattern as
    /// the table's times are), with M = 2 (a permutation of the cells)
    /// and M = 4 (Bose's array, its columns and rows shuffled).
    #[test]
    fn paired_cells_do_not_follow_the_time() {
        for (m, width, rows) in [(2usize, 64, 32), (4, 128, 64)] {
            let t = Tables::new(TimeTable::with_default_pattern(m, 1, Fidelity::Thesis));
            let n = m * m;
            for kind in [GridKind::Table, GridKind::Stratified] {
                let mut s = GridSampler::new(&t, kind, Fidelity::Thesis, width, m, 0.5);
                let mut counts = vec![vec![0usize; n]; n];
                let mut same = 0;
                for row in 0..rows {
                    s.start_row(row);
                    for x in 0..width {
                        let (cells, times) = pixel_cells(&mut s, x, row, 1);
                        for j in 0..n {
                            counts[times[j]][cells[0][j]] += 1;
                        }
                        same += usize::from(cells[0] == times);
                    }
                }
                // 512 expected in each (stratum, cell), σ ≈ 20 (M = 2), 22.
                let expected = width * rows / n;
                for (stratum, row) in counts.iter().enumerate() {
                    for (cell, &c) in row.iter().enumerate() {
                        assert!(
                            c.abs_diff(expected) < expected / 4,
                            "{kind:?} m {m}: stratum {stratum}, cell {cell}: {c}"
                        );
                    }
                }
                // Equal orders by chance: 1 pixel in 24 (M = 2).
                assert!(same < width * rows / 12, "{kind:?} m {m}: {same}");
            }
        }
    }

    /// Table and stratified: the first pair's cells (the lens) with the
    /// subpixel's place in the pixel form an orthogonal array where M has
    /// a field: every (place column or row, cell column or row) once;
    /// without one, every (place column, cell column) and (place row,
    /// cell row) once.
    #[test]
    fn the_first_pair_is_stratified_with_the_place() {
        let t = tables();
        for kind in [GridKind::Table, GridKind::Stratified] {
            for m in [2usize, 3, 4, 5, 6, 8] {
                let mut s = GridSampler::new(&t, kind, Fidelity::Thesis, 4, m, 0.5);
                s.start_row(1);
                // Without a field, the pairs along each axis only.
                let projections = if Field::of(m).is_some() { 4 } else { 2 };
                for x in 0..4 {
                    let (cells, _) = pixel_cells(&mut s, x, 1, 1);
                    let mut seen = vec![[false; 4]; m * m];
                    for (j, &cell) in cells[0].iter().enumerate() {
                        let (i, r) = (j % m, j / m);
                        for (k, (a, b)) in [(i, cell % m), (r, cell / m), (i, cell / m), (r, cell % m)]
                            .into_iter()
                            .take(projections)
                            .enumerate()
                        {
                            assert!(
                                !seen[a * m + b][k],
                                "{kind:?} m {m} pixel {x}: projection {k} ({a}, {b}) twice"
                            );
                            seen[a * m + b][k] = true;
                        }
                    }
                }
            }
        }
    }

    /// Sobol: a pixel's M² = 16 subpixels take its first 16 scrambled
    /// Sobol points: their places a (0, 4, 2)-net over the pixel (one in
    /// each elementary box of area 1/16, whatever its shape), their times
    /// and each further dimension one in each of 16 strata; in both
    /// fidelities (the place is the Sobol point's, not the listing's
    /// jitter); the points differ from pixel to pixel, the time too.
    #[test]
    fn sobol_subpixels_are_a_pixels_net() {
        let t = tables();
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let (m, width) = (4usize, 5);
            let mut s = GridSampler::new(&t, GridKind::Sobol, fidelity, width, m, 0.5);
            let mut firsts = Vec::new();
            for (x, row) in [(0, 0), (3, 2), (4, 7)] {
                s.start_row(row);
                let mut points = Vec::new();
                for sub in 0..m {
                    for c in 0..m {
                        s.start(row * m + sub + 1, x * m + c + 1);
                        let cam = s.camera();
                        let u = (cam.scancol - 0.5) / m as f64 - x as f64;
                        let v = (cam.scanline - 0.5) / m as f64 - row as f64;
                        assert!((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v), "{u} {v}");
                        assert_eq!((cam.jx, cam.jz), (0.0, 0.0));
                        let tau = s.time();
                        let further: Vec<f64> = (0..4).map(|_| s.get_1d()).collect();
                        // The adaptive sampler's further dimensions of the pixel.
                        let j = (sub * m + c) as u32;
                        for (d, &value) in further.iter().enumerate() {
                            assert_eq!(value, further_dimension(row * width + x, j, d as u32));
                        }
                        points.push((u, v, tau, further));
                    }
                }
                for k in 0..=4u32 {
                    let (a, b) = (1usize << k, 1usize << (4 - k));
                    let mut cells: Vec<usize> = points
                        .iter()
                        .map(|p| (p.0 * a as f64) as usize * b + (p.1 * b as f64) as usize)
                        .collect();
                    cells.sort_unstable();
                    assert_eq!(
                        cells,
                        (0..16).collect::<Vec<_>>(),
                        "{fidelity:?} ({x}, {row}) boxes {a}×{b}"
                    );
                }
                for d in 0..5 {
                    let value = |p: &(f64, f64, f64, Vec<f64>)| if d == 0 { p.2 } else { p.3[d - 1] };
                    let mut strata: Vec<usize> = points.iter().map(|p| (value(p) * 16.0) as usize).collect();
                    strata.sort_unstable();
                    assert_eq!(
                        strata,
                        (0..16).collect::<Vec<_>>(),
                        "{fidelity:?} ({x}, {row}) dimension {d}"
                    );
                }
                firsts.push((points[0].0, points[0].2));
            }
            assert!(firsts[0].0 != firsts[1].0 && firsts[1].0 != firsts[2].0);
            assert!(firsts[0].1 != firsts[1].1 && firsts[1].1 != firsts[2].1);
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
